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

namespace {
// The settings file as network.cpp writes it and reads it back at the next start.
bool roundTrip(const WifiSettings& saved, WifiSettings& loaded) {
  char file[kWifiFileBytes];
  JsonWriter w(file, sizeof file);
  writeWifi(w, saved, true);
  if (!w.ok()) return false;
  json j = json::parse(w.text());
  RequestError e{};
  defaultWifi(9, random32, loaded);
  return applyWifi(uvtest::View{&j}, loaded, e);
}
}  // namespace

// Issue 15, defect 6: settings that POST /wifi accepted must load back equal at the next start,
// or the ESP forgets the network and draws a new AP password: the user is locked out.
TEST(Wifi, AcceptedSettingsLoadBackEqual) {
  const std::string ssids[] = {"café", std::string(16 * 2, 'x'), "éééééééééééééééé" /* 32 bytes */, "日本語のネットワーク" /* 30 bytes */};
  const std::string passwords[] = {std::string(63, '"'), std::string(63, '\\'), "hunter22", std::string(63, '~')};
  for (const std::string& ssid : ssids) {
    for (const std::string& pw : passwords) {
      WifiSettings s;
      defaultWifi(3, random32, s);
      RequestError e{};
      json body = {{"apPassword", pw}, {"staSsid", ssid}, {"staPassword", pw}};
      ASSERT_TRUE(applyWifi(uvtest::View{&body}, s, e)) << ssid << " " << e.path << ": " << e.message;
      WifiSettings loaded;
      ASSERT_TRUE(roundTrip(s, loaded)) << ssid << " / " << pw;
      EXPECT_STREQ(loaded.staSsid, ssid.c_str());
      EXPECT_STREQ(loaded.apPassword, pw.c_str());
      EXPECT_STREQ(loaded.staPassword, pw.c_str());
    }
  }
}

// An SSID is shown and stored as JSON text: bytes that are not UTF-8, or control characters,
// could not come back as they went in, so they are refused with the field named.
TEST(Wifi, AnSsidThatIsNotUtf8TextIsRefused) {
  WifiSettings s;
  defaultWifi(4, random32, s);
  RequestError e{};
  for (std::string bad : {std::string("caf\xE9"), std::string("\xC3"), std::string("a\x01z"), std::string("\xED\xA0\x80")}) {
    json body = {{"staSsid", bad}};
    EXPECT_FALSE(applyWifi(uvtest::View{&body}, s, e)) << bad;
    EXPECT_STREQ(e.path, "/staSsid");
  }
  EXPECT_STREQ(s.staSsid, "");
}

// A settings file that is not wholly valid (an older firmware's, or damaged) keeps every field
// that is still good: above all the AP password the user connects with.
TEST(Wifi, ADamagedFileKeepsTheFieldsThatAreStillGood) {
  WifiSettings s;
  defaultWifi(5, random32, s);
  const std::string fresh = s.apPassword;
  RequestError e{};
  // An older firmware wrote "café" as "caf\u00c3\u00a9" ("cafÃ©"): a 31-byte name grew past 32.
  json file = {{"apPassword", "my own password"}, {"staSsid", std::string(29, 'x') + "\xC3\x83\xC2\xA9"}, {"staPassword", "hunter22"}};
  EXPECT_FALSE(loadWifi(uvtest::View{&file}, s, e));
  EXPECT_STREQ(e.path, "/staSsid");
  EXPECT_STREQ(s.apPassword, "my own password");
  EXPECT_STREQ(s.staPassword, "hunter22");
  EXPECT_STREQ(s.staSsid, "");
  // A file whose AP password is bad keeps the fresh default, and says so.
  WifiSettings t;
  defaultWifi(5, random32, t);
  json bad = {{"apPassword", "short"}, {"colour", 1}};
  EXPECT_FALSE(loadWifi(uvtest::View{&bad}, t, e));
  EXPECT_EQ(strlen(t.apPassword), 12u);
  json notObject = json::array();
  EXPECT_FALSE(loadWifi(uvtest::View{&notObject}, t, e));
  json whole = {{"apPassword", "my own password"}, {"staSsid", "café"}, {"staPassword", ""}};
  EXPECT_TRUE(loadWifi(uvtest::View{&whole}, t, e));
  EXPECT_STREQ(t.staSsid, "café");
}
