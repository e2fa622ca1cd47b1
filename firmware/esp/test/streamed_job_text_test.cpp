// The job text made again from the spooled body as the upload pulls it: the same bytes as the
// conversion that accepted the job, every time it is rewound, and a job that lands on the Mega.
#include "streamed_job_text.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bridge.h"
#include "job_conversion.h"
#include "nlohmann_view.h"
#include "noisy_mega.h"

using namespace uv;
using namespace uv::esp;
using namespace uvtest;
using nlohmann::json;

namespace {

struct Text : RecordSink {
  std::string text;
  void record(const char* t, uint8_t len) override { text += std::string(t, len) + "\n"; }
};

std::string body(std::mt19937& rng, unsigned cols, unsigned rows, double fill) {
  json j = {{"grid", {{"cols", cols}, {"rows", rows}}},
            {"pitchUm", {{"x", 100}, {"y", 100}}},
            {"originUm", {{"x", 5000}, {"y", 5000}}},
            {"dose", {{"map", "linear"}, {"fullUs", 3000}}},
            {"leds", {{"offsets", {{0, 0}, {0, 1}, {0, 2}, {0, 3}}}}},
            {"strategy", {{"name", "serpentine"}}}};
  json g = json::array();
  std::uniform_real_distribution<double> u(0, 1);
  for (unsigned r = 0; r < rows; r++) {
    json row = json::array();
    for (unsigned c = 0; c < cols; c++) row.push_back(u(rng) < fill ? static_cast<int>(1 + rng() % 255) : 0);
    g.push_back(row);
  }
  j["gridData"] = g;
  return j.dump();
}

// What accepting the job does: a whole conversion, for its header and the text's size.
std::string accept(const std::string& b, JobHeader& h) {
  json header = parseWithoutGridData(b);
  std::istringstream in(b);
  StreamReader reader{in};
  std::vector<uint8_t> cells(kJobMaxSide);
  Text out;
  JobConversion<StreamReader> c(reader, out, cells.data());
  EXPECT_TRUE(c.begin(View{&header}));
  while (c.step() == ConversionStep::More) {
  }
  EXPECT_EQ(c.textBytes(), out.text.size());
  h = c.header();
  return out.text;
}

// The upload's view of a spooled body: its reader and the text made from it.
struct Spooled {
  std::istringstream in;
  StreamReader reader{in};
  std::vector<uint8_t> cells = std::vector<uint8_t>(kJobMaxSide);
  StreamedJobText<StreamReader> text;
  Spooled(const std::string& body, const JobHeader& h) : in(body), text(reader, h, cells.data()) {}
};

std::string pull(JobText& t) {
  std::string s;
  char buf[100];
  EXPECT_TRUE(t.rewind());
  for (int n; (n = t.next(buf, sizeof buf)) >= 0;) s += std::string(buf, static_cast<size_t>(n)) + "\n";
  EXPECT_TRUE(t.ok());
  return s;
}

}  // namespace

TEST(StreamedJobText, PullsTheSameTextAsTheConversionEveryTimeItIsRewound) {
  std::mt19937 rng(3);
  for (int i = 0; i < 60; i++) {
    unsigned cols = 1 + rng() % 300, rows = 1 + rng() % 40;
    std::string b = body(rng, cols, rows, i % 4 == 0 ? 0.0 : (rng() % 100) / 100.0);
    JobHeader h;
    std::string want = accept(b, h);
    Spooled s(b, h);
    ASSERT_EQ(pull(s.text), want) << cols << "x" << rows;
    ASSERT_EQ(pull(s.text), want) << "after a rewind";
  }
}

TEST(StreamedJobText, ABodyThatReadsDifferentlyNowEndsTheText) {
  std::mt19937 rng(5);
  std::string b = body(rng, 20, 6, 0.5);
  JobHeader h;
  accept(b, h);
  std::string damaged = b.substr(0, b.find("gridData") + 60);  // flash lost the rest of the rows
  Spooled s(damaged, h);
  ASSERT_TRUE(s.text.rewind());
  char buf[100];
  while (s.text.next(buf, sizeof buf) >= 0) {
  }
  EXPECT_FALSE(s.text.ok());
}

TEST(StreamedJobText, APostedBodyLandsOnTheMegaThroughTheBridge) {
  esptest::NoClients clients;
  esptest::NoisyMega m;
  LiveChannel live(clients);
  Bridge bridge(m, live);
  auto run = [&](uint64_t us) {
    m.run(
        us, [&](char c, uint32_t ms) { bridge.received(c, ms); }, [&](uint32_t ms) { bridge.poll(ms); });
  };
  m.mega.begin();
  bridge.begin(m.nowMs());
  run(1500000);
  m.mega.cmd("G28");
  std::mt19937 rng(8);
  std::string b = body(rng, 120, 60, 0.3);
  JobHeader h;
  std::string want = accept(b, h);
  Spooled s(b, h);
  ASSERT_EQ(bridge.admitPrint(m.nowMs()), Admission::Accepted);
  bridge.startUpload(21, s.text, static_cast<uint32_t>(want.size()));
  for (int i = 0; i < 60000 && bridge.uploading(); i++) run(10000);
  ASSERT_EQ(bridge.lastUpload()->state, UploadState::Started) << bridge.lastUpload()->message;
  EXPECT_EQ(m.mega.sd.contents("JOB21.UVJ"), want);
  EXPECT_EQ(bridge.lastUpload()->bytesVerified, want.size());
}
