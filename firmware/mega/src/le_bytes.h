// Little-endian numbers in byte buffers: how the Mega's files on the card and its EEPROM records
// store them.
#pragma once
#include <stdint.h>

namespace mega {

inline void putLe16(uint16_t v, char* out) {
  out[0] = static_cast<char>(v);
  out[1] = static_cast<char>(v >> 8);
}
inline void putLe32(uint32_t v, char* out) {
  putLe16(static_cast<uint16_t>(v), out);
  putLe16(static_cast<uint16_t>(v >> 16), out + 2);
}
inline uint16_t getLe16(const char* in) { return static_cast<uint16_t>(static_cast<uint8_t>(in[0]) | static_cast<uint8_t>(in[1]) << 8); }
inline uint32_t getLe32(const char* in) {
  uint32_t v = 0;
  for (uint8_t i = 0; i < 4; i++) v |= static_cast<uint32_t>(static_cast<uint8_t>(in[i])) << (8 * i);
  return v;
}

}  // namespace mega
