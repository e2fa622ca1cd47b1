// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF): the strong line check of protocol/mega.md §1.
#include "crc16.h"

#include "text_scan.h"

namespace uv {

// Bitwise: a 512-byte table would cost RAM on the Mega; a 96-byte line takes well under 1 ms.
uint16_t crc16(const char* data, size_t len) {
  uint16_t c = 0xFFFF;
  for (size_t i = 0; i < len; i++) {
    c ^= static_cast<uint16_t>(static_cast<uint8_t>(data[i]) << 8);
    for (uint8_t k = 0; k < 8; k++) c = (c & 0x8000) ? static_cast<uint16_t>((c << 1) ^ 0x1021) : static_cast<uint16_t>(c << 1);
  }
  return c;
}

void crc16Hex(uint16_t crc, char* out) {
  putHex(crc, 4, out);
  out[4] = '\0';
}

}  // namespace uv
