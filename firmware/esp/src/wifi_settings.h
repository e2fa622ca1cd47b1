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
}  // namespace detail

// POST /wifi's body, or the stored file, over the settings: any of apPassword, staSsid and
// staPassword. Nothing changes unless all of it is valid. J is a JSON view (print_request.h).
template <class J>
bool applyWifi(const J& body, WifiSettings& s, RequestError& e) {
  using namespace detail;
  static const char* const keys[] = {"apPassword", "staSsid", "staPassword"};
  e = {0, "", "", ""};
  if (!object(body, "", keys, 3, keys, 0, e)) return false;
  WifiSettings next = s;
  if (body.has("apPassword")) {
    const J v = body.member("apPassword");
    if (!v.isString() || !passphrase(v.string())) return fail(e, "/apPassword", "8-63 printable ASCII characters (WPA2)");
    strcpy(next.apPassword, v.string());
  }
  if (body.has("staSsid")) {
    const J v = body.member("staSsid");
    if (!v.isString() || strlen(v.string()) > 32) return fail(e, "/staSsid", "a network name of 0-32 bytes");
    strcpy(next.staSsid, v.string());
  }
  if (body.has("staPassword")) {
    const J v = body.member("staPassword");
    if (!v.isString() || (v.string()[0] && !passphrase(v.string()))) return fail(e, "/staPassword", "empty (an open network) or 8-63 printable ASCII");
    strcpy(next.staPassword, v.string());
  }
  s = next;
  return true;
}

}  // namespace esp
}  // namespace uv
