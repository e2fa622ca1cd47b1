// Host tests of the Mega dialect codec (framing, commands, receiver, replies) against protocol/vectors/mega.json.
#include <gtest/gtest.h>

#include <vector>

#include "dialect_command.h"
#include "dialect_frame.h"
#include "dialect_receiver.h"
#include "dialect_reply.h"
#include "line_splitter.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace {

const json V = loadVectors("mega.json");
VectorCounter counted("mega.json");

struct Split {
  std::string text;
  bool overflow;
};

Split split(const std::string& line) {
  char buf[kDialectMaxLine + 1];
  LineSplitter s(buf, kDialectMaxLine);
  for (char c : line) EXPECT_FALSE(s.push(c));
  EXPECT_TRUE(s.push('\n'));
  return {std::string(s.text(), s.length()), s.overflow()};
}

Frame frameOf(const Split& s) { return parseFrame(s.text.data(), static_cast<uint8_t>(s.text.size()), s.overflow); }

json commandJson(const Command& c) {
  json j = {{"word", std::string(1, c.letter) + std::to_string(c.code)}};
  if (c.text) {
    j["text"] = std::string(c.text, c.textLen);
    return j;
  }
  json params = json::object();
  for (int i = 0; i < 26; i++) {
    char letter = static_cast<char>('A' + i);
    if (c.has(letter)) params[std::string(1, letter)] = c.hasValue(letter) ? json(c.value(letter)) : json(nullptr);
  }
  j["params"] = params;
  return j;
}

struct Collect : ReplySink {
  std::vector<std::string> lines;
  void line(const char* t) override { lines.emplace_back(t); }
};

struct Flow : FlowCounters {
  uint8_t moves, window;
  uint8_t movesFree() const override { return moves; }
  uint8_t windowFree() const override { return window; }
};

json fieldsJson(const Reply& r) {
  json f = json::object();
  std::string s(r.text, r.textLen);
  size_t i = 0;
  while (i < s.size()) {
    size_t start = i + 1, eq = s.find('=', start), sp = s.find(' ', start);
    if (sp == std::string::npos) sp = s.size();
    f[s.substr(start, eq - start)] = s.substr(eq + 1, sp - eq - 1);
    i = sp;
  }
  return f;
}

json replyJson(const Reply& r) {
  static const char* const kProbe[] = {"triggered", "open", "alarm", "deployed", "stowed"};
  std::string text(r.text ? r.text : "", r.textLen);
  switch (r.kind) {
    case ReplyKind::Ok:
      if (!r.hasFlow) return json{{"kind", "ok"}};
      return r.hasN ? json{{"kind", "ok"}, {"n", r.n}, {"p", r.p}, {"b", r.b}} : json{{"kind", "ok"}, {"p", r.p}, {"b", r.b}};
    case ReplyKind::Error: return {{"kind", "error"}, {"code", r.code}, {"message", text}};
    case ReplyKind::Fault: return {{"kind", "fault"}, {"code", r.code}, {"message", text}};
    case ReplyKind::Resend: return {{"kind", "resend"}, {"n", r.n}};
    case ReplyKind::Temps:
      return {{"kind", "temps"}, {"deciC", std::vector<int>(r.deciC, r.deciC + kSensorCount)}};
    case ReplyKind::Position:
      return {{"kind", "position"}, {"um", {r.um[0], r.um[1], r.um[2]}}, {"steps", {r.steps[0], r.steps[1], r.steps[2]}}};
    case ReplyKind::ProbePoint: return {{"kind", "probePoint"}, {"um", {r.um[0], r.um[1], r.um[2]}}};
    case ReplyKind::Job: return {{"kind", "job"}, {"state", jobStateName(static_cast<JobState>(r.state))}, {"fields", fieldsJson(r)}};
    case ReplyKind::Probe: return {{"kind", "probe"}, {"state", kProbe[r.state]}};
    case ReplyKind::Test: return {{"kind", "test"}, {"mode", r.state ? "full" : "quick"}, {"fields", fieldsJson(r)}};
    case ReplyKind::Echo: return {{"kind", "echo"}, {"text", text}};
    case ReplyKind::Busy: return {{"kind", "busy"}};
    case ReplyKind::Start: return {{"kind", "start"}};
    case ReplyKind::Firmware: return {{"kind", "firmware"}, {"name", text}, {"protocol", r.value}};
    case ReplyKind::Cap: return {{"kind", "cap"}, {"name", text}, {"value", r.value}};
    case ReplyKind::Other: return {{"kind", "other"}, {"text", text}};
    case ReplyKind::Dose: {
      const DoseReport& d = r.dose;
      json j = {{"kind", "dose"}, {"stop", d.stop}, {"program", d.program}, {"exposure", d.exposure},
                {"onUs", std::vector<uint32_t>(d.onUs, d.onUs + 4)}, {"cut", d.cut}, {"again", d.again}};
      if (d.hasPlan) j["planUs"] = std::vector<uint32_t>(d.planUs, d.planUs + 4);
      return j;
    }
  }
  return nullptr;
}

}  // namespace

TEST(MegaVectors, Limits) {
  EXPECT_EQ(kDialectMaxLine, V["maxLine"].get<int>());
  counted();
}

TEST(MegaVectors, Frames) {
  for (const json& c : V["frames"]) {
    std::string line = bytes(c["line"]);
    Split in = split(line);  // the frame points into it
    Frame f = frameOf(in);
    EXPECT_EQ(f.error, 0) << line;
    json got = {{"body", std::string(f.body, f.bodyLen)}};
    if (f.hasN) got["n"] = f.n;
    EXPECT_EQ(got, c["frame"]) << line;
    if (c["canonical"].get<bool>() && c["frame"].contains("n")) {
      char out[128];
      encodeFrame(c["frame"]["n"], c["frame"]["body"].get<std::string>().c_str(), out, sizeof out);
      EXPECT_EQ(std::string(out), line);
    }
    counted();
  }
}

TEST(MegaVectors, FrameErrors) {
  for (const json& c : V["frameErrors"]) {
    std::string line = bytes(c["line"]);
    Split in = split(line);
    Frame f = frameOf(in);
    EXPECT_EQ(f.error, c["error"].get<int>()) << line;
    if (c.contains("n")) {
      EXPECT_TRUE(f.hasN) << line;
      EXPECT_EQ(f.n, c["n"].get<uint32_t>()) << line;
    } else {
      EXPECT_FALSE(f.hasN) << line;
    }
    counted();
  }
}

TEST(MegaVectors, Commands) {
  for (const json& c : V["commands"]) {
    std::string body = c["body"];
    Command cmd;
    uint8_t err = parseCommand(body.data(), static_cast<uint8_t>(body.size()), cmd);
    if (c.contains("error")) {
      EXPECT_EQ(err, c["error"].get<int>()) << body;
    } else {
      EXPECT_EQ(err, 0) << body;
      EXPECT_EQ(commandJson(cmd), c["command"]) << body;
    }
    counted();
  }
}

TEST(MegaVectors, ReceiverSessions) {
  for (const json& s : V["sessions"]) {
    Flow flow;
    flow.moves = V["movesFree"];
    flow.window = V["window"];
    LineReceiver rx(flow);
    for (const json& step : s["steps"]) {
      if (step.contains("answered")) {
        rx.markAnswered(step["answered"].get<int32_t>());  // the executor finished that line
        continue;
      }
      Split in = split(bytes(step["rx"]));
      Collect out;
      Frame f{};
      Acceptance a = rx.accept(in.text.data(), static_cast<uint8_t>(in.text.size()), in.overflow, out, f);
      if (step.contains("execute")) {
        EXPECT_EQ(a, Acceptance::Execute) << s["name"] << " " << step["rx"];
        EXPECT_EQ(std::string(f.body, f.bodyLen), step["execute"].get<std::string>());
      } else if (step["reply"].empty()) {
        EXPECT_EQ(a, Acceptance::None) << s["name"];
      } else {
        EXPECT_EQ(a, Acceptance::Replied) << s["name"] << " " << step["rx"];
        EXPECT_EQ(json(out.lines), step["reply"]) << s["name"] << " " << step["rx"];
      }
    }
    counted();
  }
}

TEST(MegaVectors, Replies) {
  for (const json& c : V["replies"]) {
    std::string line = c["line"];
    Reply r;
    ASSERT_TRUE(parseReply(line.data(), static_cast<uint8_t>(line.size()), r)) << line;
    EXPECT_EQ(replyJson(r), c["reply"]) << line;
    if (c["canonical"].get<bool>()) {
      char out[160];
      formatReply(r, out, sizeof out);
      EXPECT_EQ(std::string(out), line);
    }
    counted();
  }
}

TEST(MegaVectors, BadRepliesRejected) {
  for (const json& c : V["badReplies"]) {
    std::string line = c["line"];
    Reply r;
    EXPECT_FALSE(parseReply(line.data(), static_cast<uint8_t>(line.size()), r)) << c["why"];
    counted();
  }
}
