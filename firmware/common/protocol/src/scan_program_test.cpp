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

// A pass's events, handed out one at a time as the Mega's planner does.
struct Events {
  std::vector<std::pair<uint32_t, uint8_t>> list;
  size_t next = 0;
  static bool take(void* ctx, uint32_t& t, uint8_t& m) {
    auto* e = static_cast<Events*>(ctx);
    if (e->next == e->list.size()) return false;
    t = e->list[e->next].first;
    m = e->list[e->next++].second;
    return true;
  }
};

// Every line the chain has, without its '\n'.
std::vector<std::string> linesOf(Events& events, bool* failed = nullptr) {
  ProgramLines writer(Events::take, &events);
  std::vector<std::string> lines;
  char out[kNanoMaxLine + 2];
  while (uint8_t n = writer.next(out)) {
    EXPECT_EQ(out[n - 1], '\n');
    EXPECT_LE(n - 1, kNanoMaxLine);
    lines.emplace_back(out, n - 1);
  }
  if (failed) *failed = writer.failed();
  return lines;
}

}  // namespace

TEST(ProgramVectors, TheWriterCutsEventsIntoTheChainsLines) {
  EXPECT_EQ(V["maxEvents"].get<int>(), kProgramEvents);
  EXPECT_EQ(V["startLeadUs"].get<uint32_t>(), kProgramStartLeadUs);
  for (const json& c : V["programs"]) {
    Events events;
    for (const json& e : c["events"]) events.list.push_back({e[0], e[1]});
    EXPECT_EQ(json(linesOf(events)), c["lines"]) << c["name"];
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

TEST(ProgramLines, StopsUnsealedAtAnEventOutOfOrderOrTooFarApart) {
  const std::vector<std::vector<std::pair<uint32_t, uint8_t>>> bad = {
      {{10, 1}, {10, 0}},                          // the same time twice
      {{10, 1}, {5, 0}},                           // backwards
      {{10, 1}, {10 + kProgramMaxDelta + 1, 0}},   // a gap of 2²⁸ µs
      {{10, 1}, {20, 16}},                         // no such LEDs
  };
  for (const auto& list : bad) {
    Events events{list};
    bool failed = false;
    std::vector<std::string> lines = linesOf(events, &failed);
    EXPECT_TRUE(failed);
    for (const std::string& l : lines) EXPECT_NE(l[0], 'K') << "a program sealed around a bad event";
  }
  Events none;
  EXPECT_TRUE(linesOf(none).empty());
  Events far{{{10, 1}, {10 + kProgramMaxDelta, 0}}};
  bool failed = true;
  EXPECT_EQ(linesOf(far, &failed).size(), 2u);
  EXPECT_FALSE(failed);
}
