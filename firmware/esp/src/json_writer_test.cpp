// The hub's JSON writer: commas, escapes, numbers and fixed decimals, and overflow reported.
#include "json_writer.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

using uv::esp::JsonWriter;

TEST(JsonWriter, WritesValidJsonWithEscapesAndExactDecimals) {
  char buf[256];
  JsonWriter w(buf, sizeof buf);
  const char damaged[] = {'o', 'k', '"', '\\', '\n', static_cast<char>(0xC3), 0};
  w.beginObject().key("line").string(damaged).key("n").number(-9007199254740993LL).key("z").number(0);
  w.key("mm").beginArray().fixed(-1500, 3).fixed(10, 3).fixed(-5, 1).fixed(123456, 1).endArray();
  w.key("ok").boolean(true).key("none").null().endObject();
  ASSERT_TRUE(w.ok());
  EXPECT_STREQ(buf, R"({"line":"ok\"\\\u000a\u00c3","n":-9007199254740993,"z":0,"mm":[-1.500,0.010,-0.5,12345.6],"ok":true,"none":null})");
  nlohmann::json j = nlohmann::json::parse(buf);
  EXPECT_EQ(j["n"].get<int64_t>(), -9007199254740993LL);
}

TEST(JsonWriter, SaysWhenItRanOutOfRoom) {
  char buf[16];
  JsonWriter w(buf, sizeof buf);
  w.beginObject().key("message").string("far too long for sixteen bytes").endObject();
  EXPECT_FALSE(w.ok());
  EXPECT_LT(w.length(), sizeof buf);
}
