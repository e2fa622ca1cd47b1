// Host tests of the ESP's Wi-Fi settings: a random WPA2 password per device, and POST /wifi.
#include "wifi_settings.h"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <string>

#include "nlohmann_view.h"

using namespace uv::esp;
using nlohmann::json;

namespace {
std::mt19937 rng;
uint32_t random32() { return static_cast<uint32_t>(rng()); }
}  // namespace

TEST(Wifi, EachDeviceGetsARandomWpa2PasswordNotDerivedFromItsName) {
  std::set<std::string> passwords;
  for (int i = 0; i < 200; i++) {
    WifiSettings s;
    defaultWifi(0xABCDEF, random32, s);  // the same chip: its password still differs each first start
    EXPECT_STREQ(s.apSsid, "UVPrinter-ABCDEF");
    ASSERT_EQ(strlen(s.apPassword), 12u);
    for (const char* p = s.apPassword; *p; p++) EXPECT_EQ(strchr("0O1lI", *p), nullptr) << s.apPassword;
    passwords.insert(s.apPassword);
  }
  EXPECT_EQ(passwords.size(), 200u);
}

TEST(Wifi, ThePanelShowsThePasswordInSixteenCharacters) {
  WifiSettings s;
  defaultWifi(1, random32, s);
  char line[17];
  panelLine(s, line);
  EXPECT_EQ(std::string(line), std::string("key:") + s.apPassword);
  EXPECT_EQ(strlen(line), 16u);
}

TEST(Wifi, PostWifiChangesOnlyWhatIsValid) {
  WifiSettings s;
  defaultWifi(2, random32, s);
  WifiSettings before = s;
  RequestError e{};
  auto apply = [&](const json& j) { return applyWifi(uvtest::View{&j}, s, e); };
  EXPECT_FALSE(apply({{"apPassword", "short"}}));
  EXPECT_EQ(std::string(e.path), "/apPassword");
  EXPECT_FALSE(apply({{"apPassword", ""}}));  // an open access point is not allowed
  EXPECT_FALSE(apply({{"apPassword", std::string(64, 'a')}}));
  EXPECT_FALSE(apply({{"apPassword", "good password"}, {"staSsid", std::string(33, 's')}}));
  EXPECT_STREQ(s.apPassword, before.apPassword);  // nothing changed by a refused request
  EXPECT_FALSE(apply({{"colour", "red"}}));
  EXPECT_EQ(std::string(e.path), "/colour");
  EXPECT_TRUE(apply({{"apPassword", "good password"}, {"staSsid", "workshop"}, {"staPassword", "hunter22"}}));
  EXPECT_STREQ(s.apPassword, "good password");
  EXPECT_STREQ(s.staSsid, "workshop");
  EXPECT_TRUE(apply({{"staSsid", ""}, {"staPassword", ""}}));  // stop joining
  EXPECT_STREQ(s.staSsid, "");
  // Stored with passwords, shown without; the stored form reads back the same.
  char buf[256];
  JsonWriter shown(buf, sizeof buf);
  writeWifi(shown, s, false);
  EXPECT_EQ(json::parse(shown.text()), json({{"apSsid", std::string(s.apSsid)}, {"staSsid", ""}}));
  JsonWriter stored(buf, sizeof buf);
  writeWifi(stored, s, true);
  WifiSettings loaded;
  defaultWifi(2, random32, loaded);
  json file = json::parse(stored.text());
  ASSERT_TRUE(applyWifi(uvtest::View{&file}, loaded, e));
  EXPECT_STREQ(loaded.apPassword, "good password");
}
