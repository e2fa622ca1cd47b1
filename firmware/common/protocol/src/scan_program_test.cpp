// Host tests of the scan-program lines against protocol/vectors/nano-program.json: the writer cuts
// a pass's events into the chain's A and K lines byte for byte, and every bad line is refused.
#include "scan_program.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace {

const json V = loadVectors("nano-program.json");
VectorCounter counted("nano-program.json");

void collect(void* ctx, const char* line, size_t len) {
  auto* out = static_cast<std::vector<std::string>*>(ctx);
  ASSERT_EQ(line[len - 1], '\n');
  out->emplace_back(line, len - 1);
}

}  // namespace

TEST(ProgramVectors, TheWriterCutsEventsIntoTheChainsLines) {
  EXPECT_EQ(V["maxEvents"].get<int>(), kProgramEvents);
  EXPECT_EQ(V["startLeadUs"].get<uint32_t>(), kProgramStartLeadUs);
  for (const json& c : V["programs"]) {
    std::vector<std::string> lines;
    ProgramWriter w(collect, &lines);
    for (const json& e : c["events"]) ASSERT_TRUE(w.add(e[0], e[1])) << c["name"];
    ASSERT_TRUE(w.finish());
    EXPECT_EQ(json(lines), c["lines"]) << c["name"];
    counted();
  }
}

TEST(ProgramVectors, EveryLineParsesBackToItsEvents) {
  for (const json& c : V["programs"]) {
    std::vector<std::pair<uint32_t, uint8_t>> got;
    uint32_t t = 0;
    uint16_t check = kCheckInit;
    size_t programEvents = 0;
    for (const json& l : c["lines"]) {
      std::string line = l;
      if (line[0] == 'K') {
        Seal s;
        ASSERT_TRUE(parseSeal(line.data(), static_cast<uint8_t>(line.size()), s)) << line;
        EXPECT_EQ(s.events, programEvents);
        EXPECT_EQ(s.check, check);
        char out[24];
        EXPECT_EQ(std::string(out, formatSeal(s, out)), line + "\n");
        check = kCheckInit;
        programEvents = 0;
        continue;
      }
      AppendLine a;
      ASSERT_TRUE(a.begin(line.data(), static_cast<uint8_t>(line.size())));
      uint32_t d;
      uint8_t m;
      while (a.next(d, m)) {
        t += d;
        got.push_back({t, m});
        check = checkEvent(check, d, m);
        programEvents++;
      }
      EXPECT_FALSE(a.malformed()) << line;
    }
    ASSERT_EQ(got.size(), c["events"].size());
    for (size_t i = 0; i < got.size(); i++) {
      EXPECT_EQ(got[i].first, c["events"][i][0].get<uint32_t>());
      EXPECT_EQ(got[i].second, c["events"][i][1].get<uint8_t>());
    }
  }
}

TEST(ProgramVectors, BadLinesAreRefused) {
  for (const json& c : V["bad"]) {
    std::string line = c["line"];
    bool ok;
    if (line[0] == 'K') {
      Seal s;
      ok = parseSeal(line.data(), static_cast<uint8_t>(line.size()), s);
    } else {
      AppendLine a;
      ok = a.begin(line.data(), static_cast<uint8_t>(line.size()));
      uint32_t d;
      uint8_t m;
      while (ok && a.next(d, m)) {
      }
      ok = ok && !a.malformed();
    }
    EXPECT_FALSE(ok) << c["why"];
    counted();
  }
}

TEST(ProgramWriter, RefusesEventsOutOfOrderOrTooFarApart) {
  std::vector<std::string> lines;
  ProgramWriter w(collect, &lines);
  EXPECT_FALSE(w.finish());  // nothing to seal
  EXPECT_TRUE(w.add(10, 1));
  EXPECT_FALSE(w.add(10, 0));                     // the same time twice
  EXPECT_FALSE(w.add(5, 0));                      // backwards
  EXPECT_FALSE(w.add(10 + kProgramMaxDelta + 1, 0));  // a gap of 2²⁸ µs
  EXPECT_FALSE(w.add(20, 16));                    // no such LEDs
  EXPECT_TRUE(w.add(10 + kProgramMaxDelta, 0));
  EXPECT_TRUE(w.finish());
  EXPECT_EQ(lines.size(), 2u);
}
