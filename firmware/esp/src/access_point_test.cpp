// Host tests of the per-device access-point credentials.
#include "access_point.h"

#include <gtest/gtest.h>

#include <cstring>
#include <set>
#include <string>

using uv::esp::accessPointCredentials;

TEST(AccessPoint, CredentialsAreWpa2ReadyAndPerDevice) {
  std::set<std::string> passwords;
  for (uint32_t id : {0u, 1u, 2u, 0xABCDEFu, 0xFFFFFFFFu, 123456u}) {
    char ssid[24], pass[16];
    accessPointCredentials(id, ssid, sizeof ssid, pass, sizeof pass);
    EXPECT_EQ(std::strlen(pass), 12u);  // WPA2-PSK needs 8-63 characters
    EXPECT_EQ(std::string(ssid).rfind("UVPrinter-", 0), 0u);
    for (const char* p = pass; *p; p++) EXPECT_EQ(std::strchr("0O1lI", *p), nullptr) << pass;
    passwords.insert(pass);
  }
  EXPECT_EQ(passwords.size(), 6u);
}

TEST(AccessPoint, SameChipSamePassword) {
  char a[16], b[16], s[24];
  accessPointCredentials(0x1234u, s, sizeof s, a, sizeof a);
  accessPointCredentials(0x1234u, s, sizeof s, b, sizeof b);
  EXPECT_STREQ(a, b);
}
