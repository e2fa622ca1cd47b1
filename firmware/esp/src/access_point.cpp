// Per-device Wi-Fi credentials derived from the chip id: the AP is never open (protocol/esp.md).
#include "access_point.h"

#include <stdio.h>

namespace uv {
namespace esp {

void accessPointCredentials(uint32_t chipId, char* ssid, size_t ssidSize, char* password, size_t passwordSize) {
  snprintf(ssid, ssidSize, "UVPrinter-%06lX", static_cast<unsigned long>(chipId & 0xFFFFFF));
  // No 0/O or 1/l/I, so it can be read off a small OLED and typed on a phone.
  static const char kAlphabet[] = "abcdefghjkmnpqrstuvwxyz23456789";
  uint32_t x = chipId * 2654435761u ^ 0x5bd1e995u;  // spread the id's bits (Knuth multiplicative hash)
  size_t n = passwordSize - 1 < 12 ? passwordSize - 1 : 12;
  for (size_t i = 0; i < n; i++) {
    x ^= x << 13;
    x ^= x >> 17;
    x ^= x << 5;  // xorshift32
    password[i] = kAlphabet[x % (sizeof kAlphabet - 1)];
  }
  password[n] = '\0';
}

}  // namespace esp
}  // namespace uv
