// Host tests of the Nano link codec against protocol/vectors/nano.json.
#include "nano_codec.h"

#include <gtest/gtest.h>

#include <vector>

#include "line_splitter.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace {

const json V = loadVectors("nano.json");
VectorCounter counted("nano.json");

struct Received {
  std::vector<std::string> usable;
  int dropped = 0;
};

// Runs bytes through the Nano's framing, as the firmware does.
Received receive(const std::string& bytes) {
  char buf[kNanoMaxLine + 1];
  LineSplitter s(buf, kNanoMaxLine);
  Received r;
  for (char c : bytes) {
    if (!s.push(c)) continue;
    if (s.length() == 0 && !s.overflow()) continue;
    if (nanoLineUsable(s.text(), s.length(), s.overflow())) r.usable.emplace_back(s.text(), s.length());
    else r.dropped++;
  }
  return r;
}

json commandJson(const NanoCommand& c) {
  json j = {{"op", std::string(1, c.op)}};
  if (c.op == 'F') j.update({{"mask", c.mask}, {"durations", {c.durations[0], c.durations[1], c.durations[2], c.durations[3]}}});
  if (c.op == 'L') j["baud"] = c.baud;
  return j;
}

// Parses a received line as a command, or null.
json parsed(const std::string& bytes) {
  Received r = receive(bytes);
  if (r.usable.size() != 1) return nullptr;
  NanoCommand c{};
  if (!parseNanoCommand(r.usable[0].data(), static_cast<uint8_t>(r.usable[0].size()), c)) return nullptr;
  return commandJson(c);
}

const char* colourName(Colour c) {
  switch (c) {
    case Colour::Green: return "green";
    case Colour::DimWhite: return "dim_white";
    case Colour::Purple: return "purple";
    case Colour::Cyan: return "cyan";
    case Colour::Orange: return "orange";
    case Colour::Red: return "red";
  }
  return "";
}

json replyJson(const NanoReply& r) {
  json j = {{"op", std::string(1, r.op)}};
  switch (r.op) {
    case 'S': j["mask"] = r.mask; break;
    case 'P': j["triggered"] = r.triggered; break;
    case 'E': j["flags"] = r.flags; break;
    case 'T': j["deciC"] = std::vector<int>(r.deciC, r.deciC + kSensorCount); break;
    case 'V': j["protocol"] = r.protocol; j["firmware"] = r.firmware; break;
    case 'C': j["boot"] = r.boot; j["fires"] = r.fires; j["whole"] = r.whole; break;
    case 'K': j["code"] = r.code; break;
    case 'Q': j["free"] = r.free; j["armed"] = r.armed; j["pass"] = r.pass; break;
    case 'W': j["us"] = r.us; break;
    case 'L': j["baud"] = r.baud; break;
    case 'O':
      j["exposure"] = r.exposure;
      if (r.exposure) j.update({{"program", r.program}, {"onUs", std::vector<uint32_t>(r.onUs, r.onUs + kLedCount)}});
      break;
  }
  return j;
}

NanoReply replyFrom(const json& j) {
  NanoReply r{};
  r.op = j["op"].get<std::string>()[0];
  if (j.contains("mask")) r.mask = j["mask"];
  if (j.contains("triggered")) r.triggered = j["triggered"];
  if (j.contains("flags")) r.flags = j["flags"];
  if (j.contains("deciC"))
    for (int i = 0; i < kSensorCount; i++) r.deciC[i] = j["deciC"][i];
  if (j.contains("protocol")) r.protocol = j["protocol"];
  if (j.contains("boot")) r.boot = j["boot"];
  if (j.contains("fires")) r.fires = j["fires"];
  if (j.contains("whole")) r.whole = j["whole"];
  if (j.contains("code")) r.code = j["code"];
  if (j.contains("free")) r.free = j["free"];
  if (j.contains("armed")) r.armed = j["armed"];
  if (j.contains("pass")) r.pass = j["pass"];
  if (j.contains("us")) r.us = j["us"];
  if (j.contains("baud")) r.baud = j["baud"];
  if (j.contains("exposure")) r.exposure = j["exposure"];
  if (j.contains("program")) r.program = j["program"];
  if (j.contains("onUs"))
    for (int i = 0; i < kLedCount; i++) r.onUs[i] = j["onUs"][i];
  if (j.contains("firmware")) snprintf(r.firmware, sizeof r.firmware, "%s", j["firmware"].get<std::string>().c_str());
  return r;
}

}  // namespace

TEST(NanoVectors, LimitsAndColours) {
  EXPECT_EQ(kNanoMaxLine, V["maxLine"].get<int>());
  const Colour all[] = {Colour::Green, Colour::DimWhite, Colour::Purple, Colour::Cyan, Colour::Orange, Colour::Red};
  EXPECT_EQ(V["colours"].size(), 6u);
  for (Colour c : all) {
    Rgb rgb = colourRgb(c);
    EXPECT_EQ(json({rgb.r, rgb.g, rgb.b}), V["colours"][colourName(c)]) << colourName(c);
  }
  counted();
}

TEST(NanoVectors, CommandsEncodeParseAndFlash) {
  for (const json& c : V["commands"]) {
    std::string line = bytes(c["line"]);
    EXPECT_EQ(parsed(line), c["command"]) << line;
    NanoCommand cmd{};
    cmd.op = c["command"]["op"].get<std::string>()[0];
    if (cmd.op == 'F') {
      cmd.mask = c["command"]["mask"];
      for (int i = 0; i < 4; i++) cmd.durations[i] = c["command"]["durations"][i];
    }
    if (cmd.op == 'L') cmd.baud = c["command"]["baud"];
    char out[80];
    formatNanoCommand(cmd, out, sizeof out);
    EXPECT_EQ(std::string(out), line);
    EXPECT_STREQ(colourName(flashColour(cmd.op)), c["flash"].get<std::string>().c_str()) << line;
    counted();
  }
}

TEST(NanoVectors, LenientLinesParse) {
  for (const json& c : V["parseOnly"]) {
    EXPECT_EQ(parsed(bytes(c["line"])), c["command"]) << c["line"];
    counted();
  }
}

TEST(NanoVectors, MalformedLinesDoNothing) {
  for (const json& c : V["malformed"]) {
    std::string line = bytes(c["line"]);
    EXPECT_EQ(parsed(line), nullptr) << c["why"];
    Received after = receive(line + "S\n");
    ASSERT_FALSE(after.usable.empty());
    EXPECT_EQ(after.usable.back(), "S") << c["why"];
    counted();
  }
}

TEST(NanoVectors, RepliesRoundTrip) {
  for (const json& c : V["replies"]) {
    std::string line = bytes(c["line"]);
    NanoReply r{};
    ASSERT_TRUE(parseNanoReply(line.data(), line.size(), r)) << line;
    EXPECT_EQ(replyJson(r), c["reply"]) << line;
    char out[80];
    formatNanoReply(replyFrom(c["reply"]), out, sizeof out);
    EXPECT_EQ(std::string(out), line);
    counted();
  }
}

TEST(NanoVectors, BadRepliesRejected) {
  for (const json& c : V["badReplies"]) {
    std::string line = bytes(c["line"]);
    NanoReply r{};
    EXPECT_FALSE(parseNanoReply(line.data(), line.size(), r)) << line;
    counted();
  }
}

TEST(NanoVectors, StreamsSplitAnywhere) {
  for (const json& c : V["streams"]) {
    Received r = receive(bytes(c["bytes"]));
    EXPECT_EQ(json(r.usable), c["lines"]) << c["name"];
    EXPECT_EQ(r.dropped, c["dropped"].get<int>()) << c["name"];
    counted();
  }
}

TEST(NanoCodec, AMaskPastTheFourLedsIsNotFormatted) {
  NanoCommand f{};
  f.op = 'F';
  f.mask = 0xA7;  // found by fuzzing the Mega's printhead link: sent, and the Nano refused it
  char out[kNanoMaxLine + 2];
  EXPECT_EQ(formatNanoCommand(f, out, sizeof out), 0u);
  f.mask = 15;
  EXPECT_GT(formatNanoCommand(f, out, sizeof out), 0u);
}

TEST(NanoCodec, ASpeedNotInTheTableIsNotFormatted) {
  NanoCommand l{};
  l.op = 'L';
  char out[kNanoMaxLine + 2];
  for (uint32_t baud : {0u, 9600u, 115201u, 999999u, 2000000u, 0xFFFFFFFFu}) {
    l.baud = baud;
    EXPECT_EQ(formatNanoCommand(l, out, sizeof out), 0u) << baud;
  }
  l.baud = 1000000;
  EXPECT_EQ(formatNanoCommand(l, out, sizeof out), 10u);
  EXPECT_STREQ(out, "L:1000000\n");
}
