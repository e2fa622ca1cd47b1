// Host tests of the job encoder and verifier against protocol/vectors/job.json.
#include <gtest/gtest.h>

#include <vector>

#include "job_encoder.h"
#include "job_verifier.h"
#include "job_json_fixture.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace {

const json V = loadVectors("job.json");
VectorCounter counted("job.json");

struct Text : RecordSink {
  std::string text;
  void record(const char* t, uint8_t len) override { text += std::string(t, len) + "\n"; }
};

struct Cells : SegmentSink {
  std::vector<std::vector<int>> grid;
  void segment(uint16_t row, uint16_t col, const uint8_t* cells, uint8_t n) override {
    for (uint8_t i = 0; i < n; i++) grid[row][col + i] = cells[i];
  }
};

uint8_t verify(const std::string& text, SegmentSink* sink) {
  JobVerifier v(sink);
  size_t start = 0;
  for (;;) {
    size_t nl = text.find('\n', start);
    if (nl == std::string::npos) break;
    if (v.push(text.data() + start, static_cast<uint8_t>(nl - start))) return v.error();
    start = nl + 1;
  }
  if (start != text.size()) return 25;  // last line has no newline
  return v.finish();
}

}  // namespace

TEST(JobVectors, EncodeByteExactAndVerify) {
  for (const json& c : V["jobs"]) {
    const json& job = c["job"];
    Text out;
    JobEncoder enc(out, c.value("format", 1));
    enc.header(headerFrom(job));
    std::vector<uint8_t> row;
    for (size_t r = 0; r < job["gridData"].size(); r++) {
      row.assign(job["gridData"][r].begin(), job["gridData"][r].end());
      enc.row(static_cast<uint16_t>(r), row.data(), static_cast<uint16_t>(row.size()));
    }
    enc.finish();
    EXPECT_EQ(out.text, c["text"].get<std::string>()) << c["name"];

    Cells cells;
    cells.grid.assign(job["grid"]["rows"].get<size_t>(), std::vector<int>(job["grid"]["cols"].get<size_t>(), 0));
    EXPECT_EQ(verify(c["text"], &cells), 0) << c["name"];
    EXPECT_EQ(json(cells.grid), job["gridData"]) << c["name"];
    counted();
  }
}

// A job cut short anywhere is refused, never taken for a smaller job: the text before any cut lacks
// its `end` line, or its CRC, or a whole last line (some 300 cuts a job, every byte of a short one).
TEST(JobVectors, EveryJobCutShortIsRefused) {
  size_t cuts = 0;
  for (const json& c : V["jobs"]) {
    const std::string text = c["text"];
    const size_t step = text.size() / 300 + 1;
    for (size_t at = 0; at < text.size(); at += step, cuts++)
      ASSERT_NE(verify(text.substr(0, at), nullptr), 0) << c["name"] << " cut at " << at;
  }
  EXPECT_GT(cuts, 5000u);
}

TEST(JobVectors, InvalidJobsRefused) {
  for (const json& c : V["invalid"]) {
    EXPECT_EQ(verify(bytes(c["text"]), nullptr), c["error"].get<int>()) << c["why"];
    counted();
  }
}

TEST(JobVerifierMemory, StaysSmallForTheMega) {
  // The Mega verifies a spooled job with one of these and one 97-byte line buffer; 128 bytes is 1.6 % of its RAM.
  EXPECT_LE(sizeof(JobVerifier), 128u);
}
