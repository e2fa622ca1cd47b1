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

// A name typed by a user (an SSID, a field of a job) is UTF-8: it must read back as it was
// written, not as Latin-1 (issue 15, defect 6: "café" came back as "cafÃ©").
TEST(JsonWriter, WritesUtf8TextAsItIsSoItReadsBackTheSame) {
  char buf[128];
  JsonWriter w(buf, sizeof buf);
  const std::string names[] = {"café", "Wi-Fi ☕ 🛰", std::string(16 * 2 / 2, 'x') + "éééééééé"};
  w.beginArray();
  for (const std::string& n : names) w.string(n.c_str());
  w.endArray();
  ASSERT_TRUE(w.ok());
  nlohmann::json j = nlohmann::json::parse(buf);
  for (size_t i = 0; i < 3; i++) EXPECT_EQ(j[i].get<std::string>(), names[i]);
  EXPECT_EQ(std::string(buf).find("\\u"), std::string::npos) << buf;
}

// Bytes that are not UTF-8 (a truncated sequence, a stray continuation byte) stay visible and
// the JSON stays valid.
TEST(JsonWriter, EscapesBytesThatAreNotUtf8) {
  char buf[128];
  JsonWriter w(buf, sizeof buf);
  const char broken[] = {'a', static_cast<char>(0xE2), static_cast<char>(0x98), 'b', static_cast<char>(0x80), static_cast<char>(0xC0), static_cast<char>(0xAF), 0};
  w.string(broken);
  ASSERT_TRUE(w.ok());
  EXPECT_STREQ(buf, R"("a\u00e2\u0098b\u0080\u00c0\u00af")");
  EXPECT_TRUE(nlohmann::json::accept(buf));
}

// JSON text is written whole or not at all: a writer that ran out of room leaves no cut-off
// text behind for a careless caller to send (issue 15, defects 6 and 7).
TEST(JsonWriter, LeavesNoCutOffTextWhenItRunsOutOfRoom) {
  char buf[16];
  JsonWriter w(buf, sizeof buf);
  w.beginObject().key("message").string("far too long for sixteen bytes").endObject();
  EXPECT_FALSE(w.ok());
  EXPECT_STREQ(w.text(), "");
  EXPECT_EQ(w.length(), 0u);
}
