// CRC-32 (IEEE 802.3, reflected, as zlib): the whole-job hash of protocol/job.md.
#include "crc32.h"

#include "text_scan.h"

namespace uv {

// Bitwise on purpose: a 1 KB table would cost an eighth of the Mega's RAM, or flash reads,
// and the Mega hashes at serial speed (about 11.5 KB/s), far below this loop's rate.
uint32_t crc32Update(uint32_t crc, const char* data, size_t len) {
  uint32_t c = ~crc;
  for (size_t i = 0; i < len; i++) {
    c ^= static_cast<uint8_t>(data[i]);
    for (uint8_t k = 0; k < 8; k++) c = (c & 1) ? (0xEDB88320u ^ (c >> 1)) : (c >> 1);
  }
  return ~c;
}

void crc32Hex(uint32_t crc, char* out) {
  putHex(crc, 8, out);
  out[8] = '\0';
}

}  // namespace uv
