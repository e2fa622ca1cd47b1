// The ESP's Wi-Fi (protocol/esp.md "Wi-Fi"): its own WPA2 access point with a per-device random
// password kept on LittleFS, optionally joining a network too; the captive portal's DNS, the
// mDNS name, and GET/POST /wifi.
#pragma once
#include <ESPAsyncWebServer.h>

#include "http_rules.h"
#include "wifi_settings.h"

namespace uv {
namespace esp {

constexpr char kMdnsName[] = "uvprinter";

// Loads or creates the settings and brings the radio up; logs the credentials on `log`.
void beginNetwork(AsyncWebServer& server, Print& log, WifiSettings& settings);
void pollNetwork();
const char* apAddress();
// protocol/esp.md "Who may drive it": 403 for a request that names a page other than the hub's own.
HttpError foreignRequest(AsyncWebServerRequest* r);

}  // namespace esp
}  // namespace uv
