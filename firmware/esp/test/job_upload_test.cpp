// A POST /print job's upload against the Mega's own command core: it lands bit-exact and starts
// only after M29 verified it, through noise, a Mega restart, a cancel, a refusal and bad records.
#include "job_upload.h"

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "error_codes.h"
#include "job_fixture.h"
#include "noisy_mega.h"

using namespace uv::esp;
using mega::jobs::Lines;

namespace {

struct SpooledText : JobText {
  Lines records;
  size_t next_ = 0;
  int failAt = -1;  // a read error at this record
  bool ok_ = true;
  bool rewind() override {
    next_ = 0;
    ok_ = true;
    return true;
  }
  int next(char* buf, uint8_t size) override {
    if (static_cast<int>(next_) == failAt) {
      ok_ = false;
      return -1;
    }
    if (next_ == records.size()) return -1;
    const std::string& r = records[next_++];
    snprintf(buf, size, "%s", r.c_str());
    return static_cast<int>(r.size());
  }
  bool ok() const override { return ok_; }
  uint32_t bytes() const {
    uint32_t n = 0;
    for (const std::string& r : records) n += static_cast<uint32_t>(r.size()) + 1;
    return n;
  }
  std::string text() const {
    std::string t;
    for (const std::string& r : records) t += r + "\n";
    return t;
  }
};

struct Bench : esptest::NoisyMega, MegaListener {
  MegaSender sender{*this, *this};
  JobUpload upload{sender};
  SpooledText text;
  std::map<uint16_t, uint16_t> answers;
  std::vector<UploadProgress> seen;  // each change the bridge would report
  uint32_t lastChange = 0;
  std::string wire;  // every byte the ESP wrote, before any noise

  bool write(const char* data, uint16_t n) override {
    wire.append(data, n);
    return NoisyMega::write(data, n);
  }
  // The bodies of the framed lines the ESP sent (`N<n> <body>*<cs>#<crc>`), in order.
  std::vector<std::string> sentBodies() const {
    std::vector<std::string> out;
    size_t at = 0;
    for (size_t end; (end = wire.find('\n', at)) != std::string::npos; at = end + 1) {
      std::string line = wire.substr(at, end - at);
      size_t space = line.find(' '), star = line.rfind('*');
      if (space != std::string::npos && star != std::string::npos && star > space) out.push_back(line.substr(space + 1, star - space - 1));
    }
    return out;
  }
  // The commands that start a job (M24 with or without P) the ESP sent.
  std::vector<std::string> starts() const {
    std::vector<std::string> out;
    for (const std::string& b : sentBodies())
      if (b == "M24" || b.rfind("M24 ", 0) == 0) out.push_back(b);
    return out;
  }
  // The Mega's first JOB:running report, or "".
  std::string runningLine() const {
    for (const std::string& l : mega.espLines)
      if (l.rfind("JOB:running", 0) == 0) return l;
    return "";
  }

  void line(const char*, uint8_t) override {}
  void answered(uint16_t tag, uint16_t error, bool) override {
    if (JobUpload::owns(tag)) upload.answered(tag, error);
    else answers[tag] = error;
  }
  void run(uint64_t us) {
    NoisyMega::run(
        us, [&](char c, uint32_t ms) { sender.received(c, ms); },
        [&](uint32_t ms) {
          upload.poll();
          sender.poll(ms);
          if (upload.changes() != lastChange) {
            lastChange = upload.changes();
            seen.push_back(upload.progress());
          }
        });
  }
  bool runUntil(const std::function<bool()>& done, uint64_t maxUs = 600000000) {
    for (uint64_t t = 0; t < maxUs; t += 10000) {
      if (done()) return true;
      run(10000);
    }
    return done();
  }
  bool command(const char* body, uint16_t tag) {
    sender.send(body, tag);
    return runUntil([&] { return answers.count(tag) > 0; });
  }
  // Homed and identified, with a job ready to upload.
  void ready(uint16_t cols = 20, uint16_t rows = 12, uint32_t seed = 5) {
    mega.begin();
    ASSERT_TRUE(command("M115", 1));
    ASSERT_TRUE(command("G28", 2));
    ASSERT_EQ(answers[2], 0);
    text.records = mega::jobs::encode(mega::jobs::header(cols, rows, uv::Strategy::Serpentine), mega::jobs::pattern(cols, rows, seed));
  }
  bool finished() const { return upload.progress().state != UploadState::Uploading; }
  bool jobRan() const {
    for (const std::string& l : mega.espLines)
      if (l.rfind("JOB:running", 0) == 0 || l.rfind("JOB:done", 0) == 0) return true;
    return false;
  }
};

}  // namespace

TEST(JobUpload, LandsBitExactAndStartsOnlyAfterTheWholeJobVerified) {
  Bench b;
  b.ready();
  b.upload.start(7, b.text, b.text.bytes());
  ASSERT_TRUE(b.runUntil([&] { return b.finished(); }));
  const UploadProgress& p = b.upload.progress();
  ASSERT_EQ(p.state, UploadState::Started) << p.message;
  EXPECT_EQ(b.mega.sd.contents("JOB7.UVJ"), b.text.text());
  EXPECT_EQ(p.bytesSent, b.text.bytes());
  EXPECT_EQ(p.bytesVerified, b.text.bytes());
  EXPECT_EQ(p.attempt, 1);
  // Progress only grows, verified never ahead of sent, and nothing started before the end.
  for (size_t i = 1; i < b.seen.size(); i++) {
    EXPECT_GE(b.seen[i].bytesVerified, b.seen[i - 1].bytesVerified);
    EXPECT_LE(b.seen[i].bytesVerified, b.seen[i].bytesSent);
  }
  EXPECT_GT(b.seen.size(), 5u);
  ASSERT_TRUE(b.runUntil([&] { return b.jobRan(); }, 5000000));
}

TEST(JobUpload, ANoisyWireStillLandsEveryJobBitExact) {
  uint32_t attempts = 0;
  for (uint32_t seed = 1; seed <= 6; seed++) {
    Bench b;
    b.rng.seed(seed);
    b.ready(24, 16, seed);
    b.corrupt = 0.01;
    b.drop = 0.003;
    b.upload.start(seed, b.text, b.text.bytes());
    ASSERT_TRUE(b.runUntil([&] { return b.finished(); })) << "seed " << seed;
    ASSERT_EQ(b.upload.progress().state, UploadState::Started) << "seed " << seed << ": " << b.upload.progress().message;
    EXPECT_EQ(b.mega.sd.contents("JOB" + std::to_string(seed) + ".UVJ"), b.text.text()) << "seed " << seed;
    attempts += b.upload.progress().attempt;
  }
  std::printf("[esp upload] 6 jobs through 1 %% corruption and 0.3 %% drops each way, all bit-exact, in %u attempts\n", attempts);
}

// mega.md "Pacing": a paced job starts with `M24 P1` and the Mega runs it paced; any other with `M24`.
TEST(JobUpload, APacedJobStartsWithM24P1AndAnyOtherWithM24) {
  for (bool paced : {false, true}) {
    Bench b;
    b.ready();
    b.upload.start(10, b.text, b.text.bytes(), paced);
    ASSERT_TRUE(b.runUntil([&] { return b.finished(); })) << paced;
    ASSERT_EQ(b.upload.progress().state, UploadState::Started) << b.upload.progress().message;
    std::vector<std::string> sent = b.sentBodies();
    ASSERT_FALSE(sent.empty());
    EXPECT_EQ(sent.back(), paced ? "M24 P1" : "M24");  // the upload's last command, after M23
    EXPECT_EQ(b.starts().size(), 1u);
    ASSERT_TRUE(b.runUntil([&] { return !b.runningLine().empty(); }, 5000000));
    EXPECT_EQ(b.runningLine().find(" paced=1") != std::string::npos, paced) << b.runningLine();
  }
}

TEST(JobUpload, AMegaRestartMidUploadSendsTheWholeJobAgain) {
  Bench b;
  b.ready(30, 20, 3);
  b.upload.start(3, b.text, b.text.bytes(), true);  // and the retry keeps it paced
  ASSERT_TRUE(b.runUntil([&] { return b.upload.progress().bytesVerified > b.text.bytes() / 2; }));
  b.restart();
  bool restarted = false;
  ASSERT_TRUE(b.runUntil([&] {
    if (!restarted && b.fed == b.mega.espLines.size()) {  // the ESP has read "start"
      restarted = true;
      b.sender.restart();
      b.upload.megaRestarted();
      b.sender.send("G28", 9);  // the restarted Mega must home again before M24
    }
    return b.finished();
  }));
  EXPECT_EQ(b.upload.progress().attempt, 2);
  ASSERT_EQ(b.upload.progress().state, UploadState::Started) << b.upload.progress().message;
  EXPECT_EQ(b.mega.sd.contents("JOB3.UVJ"), b.text.text());
  EXPECT_EQ(b.starts(), std::vector<std::string>{"M24 P1"});
}

TEST(JobUpload, ACancelledUploadLeavesNothingOnTheCardAndNeverStarts) {
  Bench b;
  b.ready(30, 20, 4);
  b.upload.start(4, b.text, b.text.bytes());
  ASSERT_TRUE(b.runUntil([&] { return b.upload.progress().bytesSent > 300; }));
  EXPECT_TRUE(b.upload.cancel());
  EXPECT_FALSE(b.upload.cancel());  // once is enough
  ASSERT_TRUE(b.runUntil([&] { return b.finished(); }));
  EXPECT_EQ(b.upload.progress().state, UploadState::Failed);
  EXPECT_STREQ(b.upload.progress().message, "cancelled");
  b.run(500000);
  EXPECT_FALSE(b.mega.sd.exists("JOB4.UVJ"));
  EXPECT_FALSE(b.jobRan());
  EXPECT_TRUE(b.sender.idle());
}

TEST(JobUpload, ACancelBeforeTheMegaHeardOfItSendsNothing) {
  Bench b;
  b.ready();
  b.upload.start(5, b.text, b.text.bytes());
  EXPECT_TRUE(b.upload.cancel());
  EXPECT_EQ(b.upload.progress().state, UploadState::Failed);
  b.run(200000);
  EXPECT_EQ(b.sender.health().linesSent, 2u);  // M115 and G28 only
}

TEST(JobUpload, ABusyMegaRefusesAndTheUploadSaysWhy) {
  Bench b;
  b.ready();
  b.upload.start(1, b.text, b.text.bytes());
  ASSERT_TRUE(b.runUntil([&] { return b.finished(); }));
  ASSERT_EQ(b.upload.progress().state, UploadState::Started);
  // A second job while the first runs: M28 is refused with E12.
  SpooledText second = b.text;
  b.upload.start(2, second, second.bytes());
  ASSERT_TRUE(b.runUntil([&] { return b.finished(); }));
  EXPECT_EQ(b.upload.progress().state, UploadState::Failed);
  EXPECT_EQ(b.upload.progress().error, uv::kBusy);
  EXPECT_EQ(b.upload.progress().attempt, 1);
}

TEST(JobUpload, ABadRecordFailsEachAttemptAndNothingRuns) {
  Bench b;
  b.ready();
  b.text.records[5].back() = 'G';  // not a hex digit: E23 on arrival
  b.upload.start(6, b.text, b.text.bytes());
  ASSERT_TRUE(b.runUntil([&] { return b.finished(); }));
  EXPECT_EQ(b.upload.progress().state, UploadState::Failed);
  EXPECT_EQ(b.upload.progress().error, uv::kJobMalformed);
  EXPECT_EQ(b.upload.progress().attempt, JobUpload::kAttempts);
  EXPECT_FALSE(b.mega.sd.exists("JOB6.UVJ"));
  EXPECT_FALSE(b.jobRan());
}

TEST(JobUpload, AWrongHashFailsAtM29AndNothingRuns) {
  Bench b;
  b.ready();
  std::string& end = b.text.records.back();
  end.back() = end.back() == '0' ? '1' : '0';
  b.upload.start(8, b.text, b.text.bytes());
  ASSERT_TRUE(b.runUntil([&] { return b.finished(); }));
  EXPECT_EQ(b.upload.progress().state, UploadState::Failed);
  EXPECT_EQ(b.upload.progress().error, uv::kJobHashMismatch);
  EXPECT_LT(b.upload.progress().bytesVerified, b.text.bytes());
  EXPECT_FALSE(b.mega.sd.exists("JOB8.UVJ"));
  EXPECT_FALSE(b.jobRan());
}

TEST(JobUpload, ASpoolThatCannotBeReadEndsTheUploadCleanly) {
  Bench b;
  b.ready();
  b.text.failAt = 9;
  b.upload.start(9, b.text, b.text.bytes());
  ASSERT_TRUE(b.runUntil([&] { return b.finished(); }));
  EXPECT_EQ(b.upload.progress().state, UploadState::Failed);
  EXPECT_STREQ(b.upload.progress().message, "the spooled job could not be read");
  EXPECT_FALSE(b.mega.sd.exists("JOB9.UVJ"));
  EXPECT_TRUE(b.sender.idle());
}
