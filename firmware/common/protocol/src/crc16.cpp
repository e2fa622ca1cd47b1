// CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF): the strong line check of protocol/mega.md §1.
#include "crc16.h"

#ifdef __AVR__
#include <util/crc16.h>
#endif

#include "text_scan.h"

namespace uv {

// No table: 512 bytes would cost RAM on the Mega. On the AVRs, avr-libc's XMODEM step (the same
// polynomial, not reflected; only the initial value differs, and that is the caller's) takes about
// 20 cycles a byte instead of about 100 for the bit loop.
uint16_t crc16Update(uint16_t crc, uint8_t byte) {
#ifdef __AVR__
  return _crc_xmodem_update(crc, byte);
#else
  crc ^= static_cast<uint16_t>(byte << 8);
  for (uint8_t k = 0; k < 8; k++) crc = (crc & 0x8000) ? static_cast<uint16_t>((crc << 1) ^ 0x1021) : static_cast<uint16_t>(crc << 1);
  return crc;
#endif
}

uint16_t crc16(const char* data, size_t len) {
  uint16_t c = 0xFFFF;
  for (size_t i = 0; i < len; i++) c = crc16Update(c, static_cast<uint8_t>(data[i]));
  return c;
}

void crc16Hex(uint16_t crc, char* out) {
  putHex(crc, 4, out);
  out[4] = '\0';
}

}  // namespace uv
