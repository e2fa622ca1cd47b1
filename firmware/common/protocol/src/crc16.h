// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF): the strong line check of protocol/mega.md §1.
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace uv {

uint16_t crc16(const char* data, size_t len);
// One more byte of a running CRC-16/CCITT-FALSE (start from 0xFFFF).
uint16_t crc16Update(uint16_t crc, uint8_t byte);
// 4 lower-case hex digits and a NUL into out[5].
void crc16Hex(uint16_t crc, char* out);

}  // namespace uv
