// Stream mode (M828) on a whole simulated Mega without a card: records checked as they arrive, a
// 512-byte buffer of rows, stops exposed as soon as no later row can change them, and the ways a
// stream ends (its end, a bad record, a buffer too small for the job, M112).
#include <gtest/gtest.h>

#include <algorithm>

#include "job_fixture.h"
#include "mega_rig.h"

using namespace mega;

namespace {

using namespace jobs;

class StreamTest : public ::testing::Test {
 protected:
  MegaRig m;
  void SetUp() override {
    m.sd.inserted = false;  // the Mega this mode is for
    m.begin();
    m.run(600000);
    m.cmd("G28");
  }
  Lines payload(const std::string& body) { return MegaRig::payload(m.cmd(body)); }
  // Sends a whole stream, each record after the last one's ok; returns every line the host read.
  Lines stream(const Lines& records) {
    size_t from = m.usbLines.size();
    m.cmd("M828");
    for (const std::string& r : records) m.cmd(r);
    m.cmd("M29");
    return Lines(m.usbLines.begin() + static_cast<long>(from), m.usbLines.end());
  }
  bool runUntil(const std::string& prefix, uint64_t maxUs = 120000000) {
    for (uint64_t t = 0; t < maxUs && !has(m.usbLines, prefix); t += 1000) m.run(1000);
    return has(m.usbLines, prefix);
  }
  void expectExposed(const std::vector<uv::Stop>& stops) {
    ASSERT_GT(stops.size(), 0u);
    ASSERT_EQ(m.nano.exposures.size(), stops.size());
    for (size_t i = 0; i < stops.size(); i++)
      for (int k = 0; k < 4; k++) ASSERT_EQ(m.nano.exposures[i].litUs[k], stops[i].us[k]) << "stop " << i;
  }
};

}  // namespace

TEST_F(StreamTest, AJobWiderThanItsBufferStreamsAndEachStopIsExposedOnceAsPlanned) {
  for (uv::Strategy s : {uv::Strategy::Raster, uv::Strategy::Serpentine, uv::Strategy::Random}) {
    m.nano.exposures.clear();
    m.usbLines.clear();
    uv::JobHeader h = header(40, 24, s);  // 24 rows of 40 cells: twice what the buffer holds
    Grid g = pattern(40, 24, static_cast<uint32_t>(s) + 1);
    Lines got = stream(encode(h, g));
    EXPECT_TRUE(has(got, "echo:Streaming: exposed as it arrives, no resume"));
    EXPECT_TRUE(has(got, "JOB:running file=stream stop=0/0 elapsed=0 leds=0 mode=stream"));
    EXPECT_TRUE(has(got, "busy: processing"));  // a record waited for room: the buffer was full
    EXPECT_TRUE(has(got, "echo:Stream complete."));
    EXPECT_FALSE(has(got, "Error:") || has(got, "echo:E"));
    ASSERT_TRUE(runUntil("JOB:done"));
    expectExposed(plan(h, g));
  }
  EXPECT_EQ(payload("M1000 S"), (Lines{"JOB:idle"}));  // no checkpoint: a stream cannot resume
}

TEST_F(StreamTest, AFormat2StreamOfRunLengthRowsIsExposedAsPlanned) {
  uv::JobHeader h = header(60, 24, uv::Strategy::Serpentine);
  Grid g = runs(60, 24, 9);
  Lines records = encode(h, g, 2);
  EXPECT_TRUE(std::any_of(records.begin(), records.end(), [](const std::string& r) { return r.rfind("rl ", 0) == 0; }));
  Lines got = stream(records);
  EXPECT_TRUE(has(got, "echo:Stream complete."));
  EXPECT_FALSE(has(got, "Error:") || has(got, "echo:E"));
  ASSERT_TRUE(runUntil("JOB:done"));
  expectExposed(plan(h, g));
}

TEST_F(StreamTest, ShortestStreamsWhenItsBandsFit) {
  uv::JobHeader h = header(6, 40, uv::Strategy::Shortest);
  Grid g = pattern(6, 40, 11);
  Lines got = stream(encode(h, g));
  EXPECT_FALSE(has(got, "Error:") || has(got, "echo:E"));
  ASSERT_TRUE(runUntil("JOB:done"));
  expectExposed(plan(h, g));
}

TEST_F(StreamTest, ABufferTooSmallForTheNextStopsFailsWithE28AndTheLedsGoOff) {
  uv::JobHeader h = header(40, 40, uv::Strategy::Shortest);  // a band reads 32 rows of 40 cells
  Lines got = stream(encode(h, pattern(40, 40, 5)));
  EXPECT_TRUE(has(got, "Error:E28 stream buffer too small for this job"));
  EXPECT_TRUE(has(got, "JOB:aborted"));
  EXPECT_EQ(m.nano.lit(), 0);
  EXPECT_TRUE(has(got, "Error:E28"));  // M29 repeats the stream's error
  EXPECT_EQ(std::count_if(got.begin(), got.end(), [](const std::string& l) { return l.rfind("Error:E28", 0) == 0; }), 2);
}

TEST_F(StreamTest, ABadRecordAbortsItTheRestIsReadAndDroppedAndM29SaysWhy) {
  uv::JobHeader h = header(30, 20, uv::Strategy::Raster);
  Lines records = encode(h, pattern(30, 20, 8));
  records[40][records[40].size() - 1] = 'Z';
  Lines got = stream(records);
  EXPECT_TRUE(has(got, "echo:E23 job record malformed: line 41"));
  EXPECT_TRUE(has(got, "JOB:aborted"));
  EXPECT_EQ(std::count_if(got.begin(), got.end(), [](const std::string& l) { return l.rfind("echo:E23", 0) == 0; }), 2);
  size_t fired = m.nano.exposures.size();
  m.run(1000000);
  EXPECT_EQ(m.nano.exposures.size(), fired);
  EXPECT_EQ(m.nano.lit(), 0);
  EXPECT_TRUE(has(payload("M114"), "X:"));  // commands again
}

TEST_F(StreamTest, AHostThatLeavesWithoutM29LeavesNothingBehind) {
  uv::JobHeader h = header(8, 8, uv::Strategy::Raster);
  Lines records = encode(h, pattern(8, 8, 2));
  m.cmd("M828");
  for (size_t i = 0; i < records.size() / 2; i++) m.cmd(records[i]);
  m.cmd("M524");  // obeyed between records: the job ends
  m.run(100000);
  EXPECT_TRUE(has(m.usbLines, "JOB:aborted"));
  Lines after = payload("G1 X5");  // a command: the stream is over, and this is obeyed
  EXPECT_EQ(after, Lines{});
  m.run(2000000);
  EXPECT_TRUE(has(payload("M114"), "X:5.000"));
  EXPECT_EQ(payload("M828"), Lines{"echo:Streaming: exposed as it arrives, no resume"});  // free for a new one
}

TEST_F(StreamTest, M112EndsAStreamAtOnce) {
  uv::JobHeader h = header(30, 30, uv::Strategy::Raster);
  Lines records = encode(h, pattern(30, 30, 12));
  m.cmd("M828");
  for (size_t i = 0; i < 40; i++) m.cmd(records[i]);
  m.cmd("M112");
  m.run(100000);
  EXPECT_EQ(m.nano.lit(), 0);
  size_t fired = m.nano.exposures.size();
  EXPECT_EQ(payload(records[40]), (Lines{"echo:E10 unknown command: r"}));  // read as a command now, not a record
  m.cmd("M999");
  m.run(500000);
  EXPECT_EQ(m.nano.exposures.size(), fired);
  m.cmd("G28");
  EXPECT_EQ(payload("M828"), Lines{"echo:Streaming: exposed as it arrives, no resume"});
}

TEST_F(StreamTest, NeedsHomingAndKeepsTheCardIdleWhileItsJobRuns) {
  m.cmd("M18");
  EXPECT_EQ(payload("M828"), (Lines{"echo:E14 axis not homed: home first (G28)"}));
  m.cmd("G28");
  m.sd.inserted = true;  // with a card too: its sector cache is the stream's buffer
  uv::JobHeader h = header(30, 30, uv::Strategy::Raster);
  h.fullUs = 200000;  // long enough to still run after M29
  Lines got = stream(encode(h, pattern(30, 30, 4)));
  ASSERT_TRUE(has(got, "echo:Stream complete."));
  EXPECT_EQ(payload("M20"), (Lines{"echo:E12 not allowed while a job is running"}));
  EXPECT_EQ(payload("M28 X.UVJ"), (Lines{"echo:E12 not allowed while a job is running"}));
  EXPECT_EQ(payload("M500"), (Lines{"echo:E12 not allowed while a job is running"}));
}

// Any host's job, whatever planned it: a stop off the bed stops the job with E15 there, the head
// never goes past the bed's edge, and no light falls off it.
TEST_F(StreamTest, AStopOffTheBedPausesTheJobWithE15AndTheHeadStaysOnTheBed) {
  uv::JobHeader h = header(10, 4, uv::Strategy::Raster);
  h.originUm[0] = 200000 - 5 * 100;  // half its columns beyond X 200 mm, the bed's edge
  Grid g(4, std::vector<uint8_t>(10, 255));
  Lines got = stream(encode(h, g));
  ASSERT_TRUE(runUntil("FAULT:E15 target outside soft limits at stop "));
  m.run(1000000);
  EXPECT_TRUE(has(m.usbLines, "JOB:paused")) << "a fault pauses a job, as an over-temperature does";
  EXPECT_LE(m.rig.head[0], 200 * 80);  // steps: never past the bed
  EXPECT_GT(m.nano.exposures.size(), 0u);  // the stops on the bed were exposed
  EXPECT_LT(m.nano.exposures.size(), plan(h, g).size());
  for (const std::array<int32_t, 3>& at : m.firedAt) EXPECT_LE(at[0], 200 * 80);
}
