// The ESP's sender against the Mega's own command core (the whole simulated Mega of the Mega's
// host tests) on its ESP port: uploads arrive bit-exact through a noisy wire, answers go back to
// whoever asked, and a restarted Mega is picked up again.
#include "mega_sender.h"

#include <gtest/gtest.h>

#include "crc16.h"

#include <map>
#include <random>
#include <string>

#include "job_fixture.h"
#include "noisy_mega.h"

using namespace uv::esp;

namespace {

struct Bench : esptest::NoisyMega, MegaListener {
  MegaSender sender{*this, *this};
  std::map<uint16_t, uint16_t> answers;  // tag -> error
  std::vector<std::string> lines;

  void line(const char* text, uint8_t len) override { lines.emplace_back(text, len); }
  void answered(uint16_t tag, uint16_t error, bool) override { answers[tag] = error; }

  void run(uint64_t us) {
    NoisyMega::run(
        us, [&](char c, uint32_t ms) { sender.received(c, ms); }, [&](uint32_t ms) { sender.poll(ms); });
  }
  bool runUntil(const std::function<bool()>& done, uint64_t maxUs = 300000000) {
    for (uint64_t t = 0; t < maxUs; t += 10000) {
      if (done()) return true;
      run(10000);
    }
    return done();
  }
  // Queues lines as the queue frees, tagging each; returns when all are answered.
  bool sendAll(const std::vector<std::string>& bodies, uint16_t firstTag) {
    size_t next = 0;
    uint16_t tag = firstTag;
    return runUntil([&] {
      while (next < bodies.size() && sender.send(bodies[next].c_str(), tag)) {
        next++;
        tag++;
      }
      return next == bodies.size() && answers.count(static_cast<uint16_t>(tag - 1));
    });
  }
};

}  // namespace

TEST(MegaSender, UploadsAJobThroughTheWindowIntoTheMegasCardBitExact) {
  Bench b;
  b.mega.begin();
  ASSERT_TRUE(b.sendAll({"M115"}, 1));
  EXPECT_EQ(b.sender.window(), mega::kEspWindow);  // learned from Cap:RX_WINDOW on the Mega's ESP port
  mega::jobs::Lines records = mega::jobs::encode(mega::jobs::header(20, 10, uv::Strategy::Raster), mega::jobs::pattern(20, 10, 3));
  std::vector<std::string> upload = {"M28 ESP.UVJ"};
  upload.insert(upload.end(), records.begin(), records.end());
  upload.push_back("M29");
  ASSERT_TRUE(b.sendAll(upload, 100));
  std::string text;
  for (const std::string& r : records) text += r + "\n";
  EXPECT_EQ(b.mega.sd.contents("ESP.UVJ"), text);
  EXPECT_EQ(b.answers[static_cast<uint16_t>(100 + upload.size() - 1)], 0);  // M29 verified
  EXPECT_TRUE(std::find(b.lines.begin(), b.lines.end(), "echo:Done saving file.") != b.lines.end());
}

TEST(MegaSender, ANoisyWireStillDeliversEveryLineOnceAndInOrder) {
  uint32_t resends = 0, timeouts = 0;
  for (uint32_t seed = 1; seed <= 8; seed++) {
    Bench b;
    b.rng.seed(seed);
    b.mega.begin();
    b.corrupt = 0.01;
    b.drop = 0.003;
    ASSERT_TRUE(b.sendAll({"M115"}, 1)) << "seed " << seed;
    mega::jobs::Lines records = mega::jobs::encode(mega::jobs::header(24, 16, uv::Strategy::Shortest), mega::jobs::pattern(24, 16, seed));
    std::vector<std::string> upload = {"M28 NOISY.UVJ"};
    upload.insert(upload.end(), records.begin(), records.end());
    upload.push_back("M29");
    ASSERT_TRUE(b.sendAll(upload, 100)) << "seed " << seed;
    std::string text;
    for (const std::string& r : records) text += r + "\n";
    EXPECT_EQ(b.mega.sd.contents("NOISY.UVJ"), text) << "seed " << seed;
    resends += b.sender.health().resends;
    timeouts += b.sender.health().timeouts;
  }
  std::printf("[esp sender] 8 uploads through 1 %% corruption and 0.3 %% drops each way, all bit-exact: %u resends, %u time-outs\n",
              resends, timeouts);
  EXPECT_GT(resends, 0u);
}

TEST(MegaSender, EachAnswerGoesToItsSenderWithItsError) {
  Bench b;
  b.mega.begin();
  ASSERT_TRUE(b.sendAll({"M115", "G1 X10", "M114", "M9999"}, 1));
  EXPECT_EQ(b.answers[1], 0);
  EXPECT_EQ(b.answers[2], 14);  // not homed
  EXPECT_EQ(b.answers[3], 0);
  EXPECT_EQ(b.answers[4], 10);  // unknown command
}

TEST(MegaSender, ALongCommandIsWaitedForNotResent) {
  Bench b;
  b.mega.rig.switchAt[0] = -80 * 150;  // homing X takes a few seconds
  b.mega.begin();
  ASSERT_TRUE(b.sendAll({"M115", "G28 X"}, 1));
  EXPECT_EQ(b.answers[2], 0);
  EXPECT_EQ(b.sender.health().timeouts, 0u);
}

TEST(MegaSender, AMegaThatRestartsIsNumberedFromZeroAgain) {
  Bench b;
  b.mega.begin();
  ASSERT_TRUE(b.sendAll({"M115", "M114", "M114"}, 1));
  b.restart();
  b.run(10000);
  b.sender.restart();
  ASSERT_TRUE(b.sendAll({"M115", "M105"}, 10));
  EXPECT_EQ(b.answers[10], 0);
}

namespace {

struct TapWire : MegaWire {
  std::string out;
  bool write(const char* data, uint16_t n) override {
    out.append(data, n);
    return true;
  }
};

struct Answers : MegaListener {
  std::map<uint16_t, uint16_t> errors;
  void line(const char*, uint8_t) override {}
  void answered(uint16_t tag, uint16_t error, bool) override { errors[tag] = error; }
};

// The Mega's `ok` with its flow fields and CRC (mega.md §2); n < 0: no N.
std::string okLine(int32_t n, int p, int b) {
  std::string body = "ok";
  if (n >= 0) body += " N" + std::to_string(n);
  body += " P" + std::to_string(p) + " B" + std::to_string(b);
  char hex[5];
  uv::crc16Hex(uv::crc16(body.data(), body.size()), hex);
  return body + "*" + hex + "\n";
}

// A sender whose Mega is the test: what it writes is kept, what the Mega says is fed to it.
struct Scripted {
  TapWire wire;
  Answers ears;
  MegaSender sender{wire, ears};
  void feed(const std::string& s) {
    for (char c : s) sender.received(c, 10);
  }
  // The link up: M110 N0 sent and answered.
  void up() {
    sender.restart();
    sender.poll(0);
    ASSERT_NE(wire.out.find("N0 M110 N0"), std::string::npos);
    feed(okLine(0, 8, 3));
  }
};

}  // namespace

// A resent line that is still running gets a bare ok at once, between its own reply's lines: the
// error already heard stays its, and its own ok N<n> then answers it with that error.
TEST(MegaSender, ABareOkInsideALinesReplyKeepsItsError) {
  Scripted m;
  m.up();
  ASSERT_TRUE(m.sender.send("M29", 7));
  m.sender.poll(1);
  ASSERT_NE(m.wire.out.find("N1 M29"), std::string::npos);
  m.feed("Error:E23 upload out of order\n");
  m.feed(okLine(-1, 8, 2));  // a duplicate of N1, still running
  EXPECT_EQ(m.ears.errors.count(7), 0u);
  m.sender.poll(2);  // every line answered, N1 unconfirmed: it goes again
  m.feed(okLine(-1, 8, 2));  // and is still running
  m.sender.poll(3);
  m.feed(okLine(1, 8, 3));
  ASSERT_EQ(m.ears.errors.count(7), 1u);
  EXPECT_EQ(m.ears.errors[7], 23);
}

// The same across a time-out: the error stays with the line still running, which its ok answers.
TEST(MegaSender, ATimeOutInsideALinesReplyKeepsItsError) {
  Scripted m;
  m.up();
  ASSERT_TRUE(m.sender.send("M29", 7));
  m.sender.poll(10);
  m.feed("Error:E23 upload out of order\n");
  m.sender.poll(10 + MegaSender::kReplyTimeoutMs);  // no ok yet: M29 goes again
  EXPECT_EQ(m.sender.health().timeouts, 1u);
  m.feed(okLine(1, 8, 3));
  ASSERT_EQ(m.ears.errors.count(7), 1u);
  EXPECT_EQ(m.ears.errors[7], 23);
}

// Issue 41: the job format the Mega reads comes from its M115 (Cap:JOB_FORMAT); an answer without
// it (an older Mega), or a Mega that restarted and has not answered again, means format 1.
TEST(MegaSender, LearnsTheJobFormatFromM115AndFallsBackToFormat1) {
  Bench b;
  b.mega.begin();
  EXPECT_EQ(b.sender.jobFormat(), 1);  // nothing said yet
  ASSERT_TRUE(b.sendAll({"M115"}, 1));
  EXPECT_EQ(b.sender.jobFormat(), 2);
  for (char c : std::string("FIRMWARE_NAME:UVExposure 0.0.9 (Mega) PROTOCOL_VERSION:1\nCap:RX_WINDOW:2\n")) b.sender.received(c, b.nowMs());
  EXPECT_EQ(b.sender.jobFormat(), 1);  // an older Mega's answer
  for (char c : std::string("Cap:JOB_FORMAT:3\n")) b.sender.received(c, b.nowMs());
  EXPECT_EQ(b.sender.jobFormat(), 2);  // the newest the hub writes
  b.sender.restart();
  EXPECT_EQ(b.sender.jobFormat(), 1);
}
