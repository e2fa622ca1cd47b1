// The ESP's Wi-Fi settings: a random per-device AP password, and what is shown and stored.
#include "wifi_settings.h"

#include <stdio.h>

namespace uv {
namespace esp {

void defaultWifi(uint32_t chipId, uint32_t (*random32)(), WifiSettings& out) {
  out = WifiSettings{};
  snprintf(out.apSsid, sizeof out.apSsid, "UVPrinter-%06lX", static_cast<unsigned long>(chipId & 0xFFFFFF));
  static const char kAlphabet[] = "abcdefghjkmnpqrstuvwxyz23456789";
  const uint32_t n = sizeof kAlphabet - 1;
  const uint32_t limit = 0xFFFFFFFFu - 0xFFFFFFFFu % n;  // no modulo bias
  for (uint8_t i = 0; i < 12; i++) {
    uint32_t x;
    do x = random32();
    while (x >= limit);
    out.apPassword[i] = kAlphabet[x % n];
  }
  out.apPassword[12] = 0;
}

void panelLine(const WifiSettings& s, char out[17]) {
  // A password of up to 12 characters fits after "key:"; a longer one was set by the user, who knows it.
  if (strlen(s.apPassword) <= 12) snprintf(out, 17, "key:%.12s", s.apPassword);
  else snprintf(out, 17, "%.16s", s.apSsid);
}

void writeWifi(JsonWriter& w, const WifiSettings& s, bool withPasswords) {
  w.beginObject();
  if (withPasswords) {
    w.key("apPassword").string(s.apPassword);
    w.key("staSsid").string(s.staSsid);
    w.key("staPassword").string(s.staPassword);
  } else {
    w.key("apSsid").string(s.apSsid);
    w.key("staSsid").string(s.staSsid);
  }
  w.endObject();
}

}  // namespace esp
}  // namespace uv
