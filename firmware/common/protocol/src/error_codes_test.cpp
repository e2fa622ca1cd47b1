// Checks the C++ error table against protocol/errors.csv.
#include "error_codes.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

TEST(ErrorCodes, MatchErrorsCsv) {
  std::ifstream in(std::string(UV_VECTORS_DIR) + "/../errors.csv");  // the table, not a vector: never mutated
  ASSERT_TRUE(in);
  std::string row;
  std::getline(in, row);  // header
  int rows = 0;
  while (std::getline(in, row)) {
    std::stringstream s(row);
    std::string code, name, message;
    std::getline(s, code, ',');
    std::getline(s, name, ',');
    std::getline(s, message, ',');
    char got[64];
    ASSERT_TRUE(uv::errorName(static_cast<uint8_t>(std::stoi(code)), got, sizeof got)) << row;
    EXPECT_EQ(name, got);
    ASSERT_TRUE(uv::errorMessage(static_cast<uint8_t>(std::stoi(code)), got, sizeof got));
    EXPECT_EQ(message, got);
    rows++;
  }
  EXPECT_EQ(rows, 30);
  char none[8];
  EXPECT_FALSE(uv::errorMessage(7, none, sizeof none));
}
