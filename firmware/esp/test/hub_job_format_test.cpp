// The hub's job text in each job format against protocol/vectors/job.json: every job there, posted
// as a body, is counted and streamed to the Mega as the same bytes as the app's and the C++
// encoder's; format 2's rows come out one record at a time, the same as a whole row's.
#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "job_conversion.h"
#include "nlohmann_view.h"
#include "streamed_job_text.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uv::esp;
using namespace uvtest;

namespace {

struct Text : RecordSink {
  std::string text;
  void record(const char* t, uint8_t len) override { text += std::string(t, len) + "\n"; }
};

// What accepting the body does (the whole conversion, its bytes counted), then what the upload
// pulls from the spool, record by record, twice (a retry rewinds it).
struct HubText {
  std::string counted, streamed, again;
  uint32_t bytes = 0;
  size_t longest = 0;
};

HubText throughTheHub(const std::string& body, uint8_t format) {
  HubText out;
  json header = parseWithoutGridData(body);
  std::istringstream in(body);
  StreamReader reader{in};
  std::vector<uint8_t> cells(kJobMaxSide);
  Text sink;
  JobConversion<StreamReader> c(reader, sink, cells.data(), format);
  EXPECT_TRUE(c.begin(View{&header})) << c.error().message;
  ConversionStep s;
  while ((s = c.step()) == ConversionStep::More) {
  }
  EXPECT_EQ(s, ConversionStep::Done) << c.error().message;
  out.counted = sink.text;
  out.bytes = c.textBytes();
  std::istringstream spool(body);
  StreamReader spoolReader{spool};
  StreamedJobText<StreamReader> text(spoolReader, c.header(), cells.data(), format);
  for (std::string* to : {&out.streamed, &out.again}) {
    EXPECT_TRUE(text.rewind());
    char buf[100];
    for (int n; (n = text.next(buf, sizeof buf)) >= 0;) {
      *to += std::string(buf, static_cast<size_t>(n)) + "\n";
      out.longest = std::max(out.longest, static_cast<size_t>(n));
    }
    EXPECT_TRUE(text.ok());
  }
  return out;
}

}  // namespace

TEST(HubJobFormat, EveryJobVectorIsTheSameTextThroughTheHub) {
  const json v = loadVectors("job.json");
  VectorCounter counted("job.json (the hub's path)");
  int format2 = 0;
  for (const json& c : v["jobs"]) {
    const std::string name = c["name"];
    const uint8_t format = static_cast<uint8_t>(c.value("format", 1));
    format2 += format == 2;
    HubText t = throughTheHub(c["job"].dump(), format);
    const std::string want = bytes(c["text"]);
    EXPECT_EQ(t.counted, want) << name;
    EXPECT_EQ(t.bytes, want.size()) << name;  // bytesTotal of the upload
    EXPECT_EQ(t.streamed, want) << name;
    EXPECT_EQ(t.again, want) << name;
    counted();
  }
  EXPECT_GE(format2, 3);
}

// Rows of runs, literals and zeros, some too long for one record: the streamed format 2 text is
// the whole-row encoder's, and no record is longer than job.md allows.
TEST(HubJobFormat, Format2StreamsRecordByRecordAsTheWholeRowEncoder) {
  std::mt19937 rng(41);
  for (int i = 0; i < 80; i++) {
    unsigned cols = 1 + rng() % 700, rows = 1 + rng() % 12;
    json g = json::array();
    for (unsigned r = 0; r < rows; r++) {
      json row = json::array();
      while (row.size() < cols) {
        unsigned len = 1 + rng() % (rng() % 3 == 0 ? 3 : 90);
        int value = rng() % 3 == 0 ? 0 : rng() % 2 ? 255 : static_cast<int>(rng() % 256);
        bool literal = rng() % 4 == 0;
        for (unsigned k = 0; k < len && row.size() < cols; k++) row.push_back(literal ? static_cast<int>(rng() % 256) : value);
      }
      g.push_back(row);
    }
    json j = {{"grid", {{"cols", cols}, {"rows", rows}}},
              {"pitchUm", {{"x", 50}, {"y", 50}}},
              {"originUm", {{"x", 5000}, {"y", 5000}}},
              {"dose", {{"map", "linear"}, {"fullUs", 3000}}},
              {"leds", {{"offsets", {{0, 0}, {0, 1}, {0, 2}, {0, 3}}}}},
              {"strategy", {{"name", "serpentine"}}},
              {"gridData", g}};
    HubText t = throughTheHub(j.dump(), 2);
    ASSERT_EQ(t.counted.rfind("uvj 2\n", 0), 0u);
    ASSERT_EQ(t.streamed, t.counted) << cols << "x" << rows;
    ASSERT_EQ(t.again, t.counted);
    EXPECT_LE(t.longest, kJobMaxRecordBytes);
    HubText one = throughTheHub(j.dump(), 1);
    EXPECT_EQ(one.streamed.find("\nrl "), std::string::npos);
    EXPECT_LE(t.bytes, one.bytes);  // a row goes as `rl` only where that is shorter
  }
}
