// The ESP's Wi-Fi: its own WPA2 access point, never open, with a password drawn at random on
// first start (the hardware RNG) and kept on LittleFS, which the user can read (serial log, the
// Mega's OLED) and change; and optionally a network to join. protocol/esp.md "Wi-Fi".
#pragma once
#include <stdint.h>
#include <string.h>

#include "json_writer.h"
#include "print_request.h"

namespace uv {
namespace esp {

// The settings file as written in one buffer (network.cpp): two 63-character passwords each of
// which may be all `"` or `\` (escaped, 126 bytes), a 32-byte SSID (64 escaped), the keys (46).
constexpr uint16_t kWifiFileBytes = 384;

struct WifiSettings {
  char apSsid[33];
  char apPassword[64];
  char staSsid[33];  // "" = don't join a network
  char staPassword[64];
};

// The AP's name from the chip id, and a fresh 12-character password from `random32` (the
// hardware RNG on the ESP). Letters and digits that can't be misread: no 0/O or 1/l/I.
void defaultWifi(uint32_t chipId, uint32_t (*random32)(), WifiSettings& out);

// What the Mega's 16-character OLED row shows, so a user without the serial log can connect.
void panelLine(const WifiSettings& s, char out[17]);

// The settings as stored (with passwords) or as GET /wifi shows them (without).
void writeWifi(JsonWriter& w, const WifiSettings& s, bool withPasswords);

namespace detail {
// A WPA2 passphrase: 8-63 printable ASCII.
inline bool passphrase(const char* p) {
  size_t n = strlen(p);
  if (n < 8 || n > 63) return false;
  for (; *p; p++)
    if (*p < 0x20 || *p > 0x7e) return false;
  return true;
}
// A network name: 0-32 bytes of UTF-8 text without control characters. 802.11 allows any bytes,
// but the name is kept and shown as JSON text, which could not give other bytes back as they were.
inline bool ssid(const char* p) {
  size_t n = strlen(p);
  if (n > 32) return false;
  for (size_t i = 0; i < n;) {
    unsigned char c = static_cast<unsigned char>(p[i]);
    if (c < 0x80) {
      if (c < 0x20 || c == 0x7f) return false;
      i++;
      continue;
    }
    uint8_t k = utf8Sequence(p + i, n - i);
    if (!k) return false;
    i += k;
  }
  return true;
}

// One of the settings' fields judged and, if valid, set in `next`.
template <class J>
bool wifiField(const J& body, const char* key, WifiSettings& next, RequestError& e) {
  const J v = body.member(key);
  if (strcmp(key, "apPassword") == 0) {
    if (!v.isString() || !passphrase(v.string())) return fail(e, "/apPassword", "8-63 printable ASCII characters (WPA2)");
    strcpy(next.apPassword, v.string());
  } else if (strcmp(key, "staSsid") == 0) {
    if (!v.isString() || !ssid(v.string())) return fail(e, "/staSsid", "a network name of 0-32 bytes of UTF-8 text");
    strcpy(next.staSsid, v.string());
  } else {
    if (!v.isString() || (v.string()[0] && !passphrase(v.string()))) return fail(e, "/staPassword", "empty (an open network) or 8-63 printable ASCII");
    strcpy(next.staPassword, v.string());
  }
  return true;
}
constexpr const char* kWifiKeys[] = {"apPassword", "staSsid", "staPassword"};
}  // namespace detail

// POST /wifi's body over the settings: any of apPassword, staSsid and staPassword. Nothing changes
// unless all of it is valid. J is a JSON view (print_request.h).
template <class J>
bool applyWifi(const J& body, WifiSettings& s, RequestError& e) {
  using namespace detail;
  e = {0, "", "", ""};
  if (!object(body, "", kWifiKeys, 3, kWifiKeys, 0, e)) return false;
  WifiSettings next = s;
  for (const char* key : kWifiKeys)
    if (body.has(key) && !wifiField(body, key, next, e)) return false;
  s = next;
  return true;
}

// The stored file over the defaults (`s` holds them), judged as strictly as POST /wifi. True when
// all of it is valid. Otherwise each field that is valid on its own is still taken and `e` names
// the first that is not: a damaged file never costs the user an AP password that is still good.
template <class J>
bool loadWifi(const J& file, WifiSettings& s, RequestError& e) {
  using namespace detail;
  if (applyWifi(file, s, e)) return true;
  if (!file.isObject()) return false;
  RequestError ignored{};
  for (const char* key : kWifiKeys)
    if (file.has(key)) wifiField(file, key, s, ignored);
  return false;
}

}  // namespace esp
}  // namespace uv
