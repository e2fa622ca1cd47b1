// Fuzzes the ESP's Wi-Fi settings file as it loads at start-up. Holds: settings that load are
// ones POST /wifi would take; written back, they fit the file's buffer and load back equal.
#include <string.h>

#include <string>

#include "fuzz_checks.h"
#include "nlohmann_view.h"
#include "wifi_settings.h"

using namespace uv::esp;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  nlohmann::json file = nlohmann::json::parse(std::string(reinterpret_cast<const char*>(data), size), nullptr, false);
  if (file.is_discarded()) return 0;
  WifiSettings s;
  defaultWifi(0x1234, [] { return 0x9e3779b9u; }, s);
  uv::esp::RequestError e{};
  if (!loadWifi(uvtest::View{&file}, s, e)) return 0;
  char text[kWifiFileBytes];
  JsonWriter w(text, sizeof text);
  writeWifi(w, s, true);
  FUZZ_REQUIRE(w.ok(), "loaded settings that do not fit the settings file");
  nlohmann::json again = nlohmann::json::parse(w.text(), nullptr, false);
  FUZZ_REQUIRE(!again.is_discarded(), "settings written as something other than JSON");
  WifiSettings t;
  defaultWifi(0x1234, [] { return 0x12345678u; }, t);
  FUZZ_REQUIRE(loadWifi(uvtest::View{&again}, t, e), "saved settings that do not load");
  FUZZ_REQUIRE(memcmp(&s, &t, sizeof s) == 0 || (strcmp(s.apSsid, t.apSsid) == 0 && strcmp(s.apPassword, t.apPassword) == 0 &&
                                                  strcmp(s.staSsid, t.staSsid) == 0 && strcmp(s.staPassword, t.staPassword) == 0),
               "saved settings load back changed");
  return 0;
}
