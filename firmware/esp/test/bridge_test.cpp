// The ESP's hub against the Mega's own command core: console lines from several clients and an
// upload share the UART, answers reach whoever asked, a slow client is closed and never slows
// the bridge, and the status says what the Mega reported.
#include "bridge.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "job_fixture.h"
#include "nlohmann_view.h"
#include "noisy_mega.h"

using namespace uv::esp;
using nlohmann::json;

namespace {

struct Clients : LiveClients {
  std::map<uint8_t, std::vector<json>> frames;
  std::map<uint8_t, bool> stalled;  // a client whose connection takes nothing
  std::map<uint8_t, uint16_t> closed;
  bool trySend(uint8_t client, const char* text, uint16_t len) override {
    if (stalled[client]) return false;
    json j = json::parse(std::string(text, len), nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << std::string(text, len);
    frames[client].push_back(j);
    return true;
  }
  void close(uint8_t client, uint16_t code, const char*) override { closed[client] = code; }
  std::vector<json> of(uint8_t client, const std::string& type) {
    std::vector<json> out;
    for (const json& f : frames[client])
      if (f["type"] == type) out.push_back(f);
    return out;
  }
};

struct SpooledText : JobText {
  mega::jobs::Lines records;
  size_t next_ = 0;
  bool rewind() override {
    next_ = 0;
    return true;
  }
  int next(char* buf, uint8_t size) override {
    if (next_ == records.size()) return -1;
    snprintf(buf, size, "%s", records[next_].c_str());
    return static_cast<int>(records[next_++].size());
  }
  bool ok() const override { return true; }
  uint32_t bytes() const {
    uint32_t n = 0;
    for (const std::string& r : records) n += static_cast<uint32_t>(r.size()) + 1;
    return n;
  }
};

struct Hub : esptest::NoisyMega {
  Clients clients;
  LiveChannel live{clients};
  Bridge bridge{*this, live};
  bool megaSilent = false;  // the Mega's wire is cut

  void start() {
    mega.begin();
    bridge.begin(nowMs(), "Wi-Fi UVPrinter-ABC123 pw abcdefghjkmn");
    run(1500000);
  }
  void join(uint8_t c) {
    ASSERT_TRUE(live.join(c));
    bridge.clientJoined(c, nowMs());
  }
  void run(uint64_t us) {
    NoisyMega::run(
        us,
        [&](char c, uint32_t ms) {
          if (!megaSilent) bridge.received(c, ms);
        },
        [&](uint32_t ms) {
          bridge.poll(ms);
          live.pump();  // the network side's turn
        });
  }
  bool runUntil(const std::function<bool()>& done, uint64_t maxUs = 300000000) {
    for (uint64_t t = 0; t < maxUs; t += 10000) {
      if (done()) return true;
      run(10000);
    }
    return done();
  }
  void say(uint8_t client, const json& m) { bridge.clientMessage(client, uvtest::View{&m}); }
  json status() {
    char buf[2048];
    JsonWriter w(buf, sizeof buf);
    bridge.writeStatus(w, nowMs());
    EXPECT_TRUE(w.ok());
    return json::parse(w.text());
  }
  std::vector<json> replies(uint8_t client, int64_t id) {
    std::vector<json> out;
    for (const json& f : clients.of(client, "reply"))
      if (f["id"] == id) out.push_back(f);
    return out;
  }
};

bool contains(const json& lines, const std::string& prefix) {
  for (const json& l : lines)
    if (l.get<std::string>().rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace

TEST(Bridge, GreetsAClientAndReportsTheMegaItIdentified) {
  Hub h;
  h.start();
  h.join(1);
  h.run(100000);
  ASSERT_FALSE(h.clients.frames[1].empty());
  EXPECT_EQ(h.clients.frames[1][0], json({{"type", "hello"}, {"protocol", 1}, {"firmware", std::string(kEspFirmware)}}));
  json s = h.status();
  EXPECT_EQ(s["mega"], "online");
  EXPECT_EQ(s["firmware"], "UVExposure 0.1.0 (Mega)");
  EXPECT_EQ(s["temps"].size(), 6u);
  // The soft limits come from the config the ESP lists at start (M503), not from the T: line.
  EXPECT_EQ(s["limits"], json({55.0, 55.0, 55.0, 55.0, 50.0, 50.0}));
  EXPECT_TRUE(s["position"].contains("x"));
  EXPECT_EQ(s["clients"], 1);
  // The Wi-Fi credentials reached the Mega's OLED.
  bool shown = false;
  for (const std::string& r : h.mega.display.rows) shown |= r.find("abcdefghjkmn") != std::string::npos || r.find("UVPrinter") != std::string::npos;
  EXPECT_TRUE(shown);
  // A status message every second.
  size_t before = h.clients.of(1, "status").size();
  h.run(3000000);
  EXPECT_GE(h.clients.of(1, "status").size() - before, 3u);
}

// The network side lets a client in before loop() hears of it: what loop() broadcasts in
// between (a line from the Mega) must not reach it before its hello and status (esp.md).
TEST(Bridge, AClientIsGreetedBeforeAnyBroadcast) {
  Hub h;
  h.start();
  ASSERT_TRUE(h.live.join(1));
  const char line[] = R"({"type":"line","line":"ok"})";
  h.live.broadcast(line, sizeof line - 1);
  h.live.pump();
  EXPECT_TRUE(h.clients.frames[1].empty());
  h.bridge.clientJoined(1, h.nowMs());
  h.live.broadcast(line, sizeof line - 1);
  h.live.pump();
  ASSERT_EQ(h.clients.frames[1].size(), 3u);
  EXPECT_EQ(h.clients.frames[1][0]["type"], "hello");
  EXPECT_EQ(h.clients.frames[1][1]["type"], "status");
  EXPECT_EQ(h.clients.frames[1][2]["type"], "line");
}

TEST(Bridge, TheApKeyGoesToTheOledAndNeverOnTheLiveChannel) {
  Hub h;
  ASSERT_TRUE(h.live.join(1));  // there before the ESP sends its first line
  h.bridge.clientJoined(1, h.nowMs());
  h.mega.begin();
  h.bridge.begin(h.nowMs(), "key:abcdefghjkmn");
  h.run(3000000);
  bool shown = false;
  for (const std::string& r : h.mega.display.rows) shown |= r.find("abcdefghjkmn") != std::string::npos;
  EXPECT_TRUE(shown);
  ASSERT_FALSE(h.clients.of(1, "sent").empty());  // the ESP's other lines are echoed
  for (const json& f : h.clients.frames[1]) EXPECT_EQ(f.dump().find("abcdefghjkmn"), std::string::npos) << f;
}

TEST(Bridge, EachConsoleLineIsAnsweredToItsOwnClientAndEchoedToAll) {
  Hub h;
  h.start();
  h.join(1);
  h.join(2);
  h.say(1, {{"type", "send"}, {"line", "M114"}, {"id", 7}});
  h.say(2, {{"type", "send"}, {"line", "G1 X10"}, {"id", 7}});  // the same id from another client
  h.say(2, {{"type", "send"}, {"line", "M105"}});               // no id: no reply
  ASSERT_TRUE(h.runUntil([&] { return !h.replies(1, 7).empty() && !h.replies(2, 7).empty(); }));
  json r1 = h.replies(1, 7)[0]["lines"];
  EXPECT_TRUE(contains(r1, "X:")) << r1;
  EXPECT_TRUE(r1.back().get<std::string>().rfind("ok N", 0) == 0) << r1;
  json r2 = h.replies(2, 7)[0]["lines"];
  EXPECT_TRUE(contains(r2, "echo:E14")) << r2;  // not homed: the Mega's own error, to its sender
  EXPECT_EQ(h.replies(1, 7).size(), 1u);
  h.run(200000);
  for (uint8_t c : {1, 2}) {
    std::vector<std::string> echoed;
    for (const json& f : h.clients.of(c, "sent")) echoed.push_back(f["line"]);
    EXPECT_NE(std::find(echoed.begin(), echoed.end(), "M114"), echoed.end());
    EXPECT_NE(std::find(echoed.begin(), echoed.end(), "M105"), echoed.end());
    EXPECT_FALSE(h.clients.of(c, "line").empty());
  }
}

TEST(Bridge, RefusesBadClientMessagesAndStaysOpen) {
  Hub h;
  h.start();
  h.join(1);
  h.say(1, json::array({1, 2}));
  h.say(1, {{"type", "shout"}, {"id", 1}});
  h.say(1, {{"type", "send"}, {"line", std::string(73, 'M')}, {"id", 2}});
  h.say(1, {{"type", "send"}, {"line", "M105\nM112"}, {"id", 3}});
  h.say(1, {{"type", "send"}, {"id", 4}});
  h.say(1, {{"type", "send"}, {"line", "M105"}, {"id", "x"}});
  h.say(1, {{"type", "ping"}});
  h.bridge.clientRefused(1, "bad_json", "not JSON");
  h.run(100000);
  std::vector<json> errors = h.clients.of(1, "error");
  ASSERT_EQ(errors.size(), 7u);
  EXPECT_EQ(errors[0]["code"], "bad_message");
  EXPECT_EQ(errors[1]["code"], "unknown_type");
  EXPECT_EQ(errors[1]["id"], 1);
  EXPECT_EQ(errors[2]["code"], "line_too_long");
  EXPECT_EQ(errors[3]["code"], "bad_line");
  EXPECT_EQ(errors[4]["code"], "bad_message");
  EXPECT_EQ(errors[5]["code"], "bad_message");
  EXPECT_EQ(errors[6]["code"], "bad_json");
  EXPECT_EQ(h.clients.of(1, "pong").size(), 1u);
  for (const json& f : h.clients.of(1, "sent")) EXPECT_EQ(f["from"], "esp") << f;  // nothing from the client went out
}

TEST(Bridge, ConsoleLinesAndAnUploadShareTheUart) {
  Hub h;
  h.rng.seed(4);
  h.start();
  h.join(1);
  h.say(1, {{"type", "send"}, {"line", "G28"}, {"id", 1}});
  ASSERT_TRUE(h.runUntil([&] { return !h.replies(1, 1).empty(); }));
  h.corrupt = 0.005;
  h.drop = 0.001;
  SpooledText text;
  text.records = mega::jobs::encode(mega::jobs::header(40, 24, uv::Strategy::Serpentine), mega::jobs::pattern(40, 24, 9));
  ASSERT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Accepted);
  h.bridge.startUpload(11, text, text.bytes());
  EXPECT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Busy);  // one job at a time
  int64_t id = 100;
  ASSERT_TRUE(h.runUntil([&] {
    if (h.bridge.uploading() && h.replies(1, id).size() == 1) h.say(1, {{"type", "send"}, {"line", "M105"}, {"id", ++id}});
    if (id == 100) h.say(1, {{"type", "send"}, {"line", "M105"}, {"id", ++id}});
    return !h.bridge.uploading();
  }));
  ASSERT_EQ(h.bridge.lastUpload()->state, UploadState::Started) << h.bridge.lastUpload()->message;
  std::string want;
  for (const std::string& r : text.records) want += r + "\n";
  EXPECT_EQ(h.mega.sd.contents("JOB11.UVJ"), want);
  EXPECT_GT(id - 100, 10);  // console lines kept being answered during the upload
  for (int64_t i = 101; i < id; i++) {
    ASSERT_EQ(h.replies(1, i).size(), 1u) << i;
    EXPECT_TRUE(contains(h.replies(1, i)[0]["lines"], "ok")) << i;
  }
  // The records' oks stay between the ESP and the Mega: the clients see the console's.
  size_t oks = 0;
  for (const json& f : h.clients.of(1, "line")) oks += f["line"].get<std::string>().rfind("ok", 0) == 0;
  // At most one per console line, start-up line (twice: the Mega's "start"), G28 and upload command.
  EXPECT_LE(oks, static_cast<size_t>(id - 100) + 16);
  EXPECT_LT(oks, static_cast<size_t>(id - 100) + text.records.size());
  // The upload's progress: at least every 500 ms, and its end.
  std::vector<json> ups = h.clients.of(1, "upload");
  ASSERT_GE(ups.size(), 3u);
  EXPECT_EQ(ups.front()["state"], "uploading");
  EXPECT_EQ(ups.back()["state"], "started");
  EXPECT_EQ(ups.back()["bytesVerified"], text.bytes());
  EXPECT_EQ(ups.back()["bytesTotal"], text.bytes());
  json s = h.status();
  EXPECT_EQ(s["job"]["id"], 11);
  EXPECT_EQ(s["job"]["upload"], "started");
}

TEST(Bridge, ASlowClientIsClosedAndNeverHoldsUpTheOthers) {
  Hub h;
  h.start();
  h.join(1);
  h.join(2);
  h.clients.stalled[2] = true;  // its TCP window is shut
  SpooledText text;
  text.records = mega::jobs::encode(mega::jobs::header(48, 32, uv::Strategy::Raster), mega::jobs::pattern(48, 32, 2));
  h.say(1, {{"type", "send"}, {"line", "G28"}, {"id", 1}});
  ASSERT_TRUE(h.runUntil([&] { return !h.replies(1, 1).empty(); }));
  ASSERT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Accepted);
  h.bridge.startUpload(12, text, text.bytes());
  ASSERT_TRUE(h.runUntil([&] { return !h.bridge.uploading(); }));
  EXPECT_EQ(h.bridge.lastUpload()->state, UploadState::Started);
  // Reports, status and progress keep coming while the job runs: the stalled client falls a ring behind.
  ASSERT_TRUE(h.runUntil([&] { return h.clients.closed.count(2) > 0; }, 60000000));
  EXPECT_EQ(h.clients.closed[2], 1008);
  EXPECT_EQ(h.clients.closed.count(1), 0u);
  EXPECT_EQ(h.live.closedSlow(), 1u);
  EXPECT_EQ(h.live.count(), 1);
  EXPECT_EQ(h.clients.of(1, "upload").back()["state"], "started");
}

TEST(Bridge, TheRingHoldsEightKilobytesPerClientAndDeliversInOrder) {
  Clients c;
  LiveChannel live(c);
  ASSERT_TRUE(live.join(1));
  ASSERT_TRUE(live.join(2));
  for (uint8_t client : {1, 2}) live.sendTo(client, "{}", 2);  // greeted: broadcasts are theirs from now on
  live.pump();
  c.frames.clear();
  c.stalled[1] = c.stalled[2] = true;
  std::string m = R"({"type":"line","line":")" + std::string(60, 'x') + R"("})";
  int n = 0;
  while (live.written() + m.size() + 4 <= LiveChannel::kRing) {  // to the ring's end, unwrapped
    live.broadcast(m.c_str(), static_cast<uint16_t>(m.size()));
    n++;
  }
  EXPECT_TRUE(c.closed.empty());  // just under 8 KB behind: still open
  c.stalled[2] = false;
  live.pump();
  EXPECT_EQ(static_cast<int>(c.frames[2].size()), n);
  live.broadcast(m.c_str(), static_cast<uint16_t>(m.size()));  // one more: client 1 is a ring behind
  EXPECT_TRUE(c.closed.empty());  // the writer never looks at the readers
  live.pump();  // the readers' side finds it a ring behind
  EXPECT_EQ(c.closed[1], 1008);
  EXPECT_EQ(c.closed.count(2), 0u);
  live.pump();
  EXPECT_EQ(static_cast<int>(c.frames[2].size()), n + 1);
  // Wrapping round the ring many times keeps every message whole and in order.
  for (int i = 0; i < 2000; i++) {
    std::string t = R"({"i":)" + std::to_string(i) + R"(,"pad":")" + std::string(static_cast<size_t>(i % 97), 'p') + R"("})";
    live.sendTo(2, t.c_str(), static_cast<uint16_t>(t.size()));
    if (i % 7 == 0) live.pump();
  }
  live.pump();
  int expect = 0;
  for (const json& f : c.frames[2])
    if (f.contains("i")) {
      EXPECT_EQ(f["i"], expect++);
    }
  EXPECT_EQ(expect, 2000);
  // At most four clients: the ESP8266's memory.
  EXPECT_TRUE(live.join(3));
  EXPECT_TRUE(live.join(4));
  EXPECT_TRUE(live.join(5));
  EXPECT_FALSE(live.join(6));
}

TEST(Bridge, AdmitsAPrintOnlyToAnOnlineIdleMegaAndCancelsWhatRuns) {
  Hub h;
  h.start();
  h.join(1);
  EXPECT_FALSE(h.bridge.cancel());  // nothing to cancel
  // A job running: DELETE aborts it with M524.
  h.say(1, {{"type", "send"}, {"line", "G28"}, {"id", 1}});
  ASSERT_TRUE(h.runUntil([&] { return !h.replies(1, 1).empty(); }));
  SpooledText text;
  text.records = mega::jobs::encode(mega::jobs::header(30, 20, uv::Strategy::Raster), mega::jobs::pattern(30, 20, 6));
  ASSERT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Accepted);
  h.bridge.startUpload(13, text, text.bytes());
  ASSERT_TRUE(h.runUntil([&] { return !h.bridge.uploading(); }));
  ASSERT_TRUE(h.runUntil([&] { return h.status()["job"]["state"] == "running"; }));
  EXPECT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Busy);
  EXPECT_TRUE(h.bridge.cancel());
  ASSERT_TRUE(h.runUntil([&] { return h.status()["job"]["state"] == "aborted"; }));
  EXPECT_FALSE(h.mega.nano.lit() != 0);
  // An upload cancelled half-way: the Mega keeps nothing.
  ASSERT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Accepted);
  h.bridge.startUpload(14, text, text.bytes());
  ASSERT_TRUE(h.runUntil([&] { return h.bridge.lastUpload()->bytesVerified > 1000; }));
  EXPECT_TRUE(h.bridge.cancel());
  ASSERT_TRUE(h.runUntil([&] { return !h.bridge.uploading(); }));
  EXPECT_EQ(h.clients.of(1, "upload").back()["state"], "failed");
  EXPECT_EQ(h.clients.of(1, "upload").back()["error"], "cancelled");
  EXPECT_FALSE(h.mega.sd.exists("JOB14.UVJ"));
  // A Mega that has gone quiet is offline after 5 s: 503.
  h.megaSilent = true;
  h.run(5500000);
  EXPECT_EQ(h.status()["mega"], "offline");
  EXPECT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::MegaOffline);
  bool toldOffline = false;
  for (const json& f : h.clients.of(1, "status")) toldOffline |= f["status"]["mega"] == "offline";
  EXPECT_TRUE(toldOffline);
}

TEST(Bridge, AMegaRestartIsPickedUpAndItsReportsAskedForAgain) {
  Hub h;
  h.start();
  h.join(1);
  h.restart();
  h.run(2000000);
  json s = h.status();
  EXPECT_EQ(s["mega"], "online");
  h.say(1, {{"type", "send"}, {"line", "M115"}, {"id", 5}});
  ASSERT_TRUE(h.runUntil([&] { return !h.replies(1, 5).empty(); }, 5000000));
  EXPECT_TRUE(contains(h.replies(1, 5)[0]["lines"], "FIRMWARE_NAME:"));
  size_t before = h.clients.of(1, "line").size();
  h.run(2500000);
  bool temps = false;
  for (size_t i = before; i < h.clients.of(1, "line").size(); i++) temps |= h.clients.of(1, "line")[i]["line"].get<std::string>().rfind("T:", 0) == 0;
  EXPECT_TRUE(temps);  // M155 S1 was sent again
}

// Issue 15, defect 8: an id no int64 holds is refused, never wrapped (18446744073709551615 came
// back as -1) nor cast from a float (1e300, undefined behaviour).
TEST(Bridge, AnIdBeyondSixtyFourBitsIsRefusedNotWrapped) {
  Hub h;
  h.start();
  h.join(1);
  h.say(1, {{"type", "send"}, {"line", "M105"}, {"id", 18446744073709551615ull}});
  h.say(1, {{"type", "send"}, {"line", "M105"}, {"id", 1e300}});
  h.say(1, {{"type", "send"}, {"line", "M105"}, {"id", -9.3e18}});
  h.say(1, {{"type", "send"}, {"line", "M105"}, {"id", -9223372036854775807ll - 1}});
  h.run(200000);
  std::vector<json> errors = h.clients.of(1, "error");
  ASSERT_EQ(errors.size(), 3u);
  for (const json& e : errors) EXPECT_EQ(e["code"], "bad_message") << e;
  EXPECT_EQ(h.clients.of(1, "reply").size(), 1u);  // the smallest int64 is an id like any other
  EXPECT_EQ(h.clients.of(1, "reply")[0]["id"], -9223372036854775807ll - 1);
}
