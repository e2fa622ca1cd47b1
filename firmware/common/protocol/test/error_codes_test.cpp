// Checks the C++ error table against protocol/errors.csv.
#include "error_codes.h"

#include <gtest/gtest.h>

#include <string.h>

#include <fstream>
#include <set>
#include <sstream>

TEST(ErrorCodes, MatchErrorsCsv) {
  std::ifstream in(std::string(UV_VECTORS_DIR) + "/../errors.csv");  // the table, not a vector: never mutated
  ASSERT_TRUE(in);
  std::string row;
  std::getline(in, row);  // header
  int rows = 0;
  std::set<int> codes;
  while (std::getline(in, row)) {
    std::stringstream s(row);
    std::string code, name, message, resend, cls;
    std::getline(s, code, ',');
    std::getline(s, name, ',');
    std::getline(s, message, ',');
    std::getline(s, resend, ',');
    std::getline(s, cls, ',');
    const uint8_t c = static_cast<uint8_t>(std::stoi(code));
    EXPECT_EQ(cls, uv::isLineError(c) ? "link" : uv::isFault(c) ? "fault" : "refusal") << row;
    EXPECT_EQ(uv::isRefusal(c), cls == "refusal") << row;
    char got[64];
    ASSERT_TRUE(uv::errorName(static_cast<uint8_t>(std::stoi(code)), got, sizeof got)) << row;
    EXPECT_EQ(name, got);
    ASSERT_TRUE(uv::errorMessage(static_cast<uint8_t>(std::stoi(code)), got, sizeof got));
    EXPECT_EQ(message, got);
    codes.insert(std::stoi(code));
    rows++;
  }
  EXPECT_GT(rows, 0);
  // And the other way: the firmware knows no code the table lacks.
  for (int code = 0; code < 256; code++) {
    char got[64];
    EXPECT_EQ(uv::errorMessage(static_cast<uint8_t>(code), got, sizeof got), codes.count(code) == 1) << code;
  }
}

TEST(ErrorCodes, AnUnknownCodeStillWritesText) {
  // The host link formats `Error:E<code> <message>`: it once sent what was in its buffer before.
  char out[32];
  memset(out, 0x7f, sizeof out);
  EXPECT_FALSE(uv::errorMessage(59, out, sizeof out));
  EXPECT_STREQ(out, "unknown error");
  EXPECT_FALSE(uv::errorName(0, out, sizeof out));
  EXPECT_STREQ(out, "unknown");
}
