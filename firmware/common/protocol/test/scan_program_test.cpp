// Host tests of the scan-program lines against protocol/vectors/nano-program.json: the writer cuts
// a pass's events into the chain's B and K lines byte for byte, A and B lines parse back to the
// events, and every bad line is refused.
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
  for (const json& c : V["programs"])
    for (const char* form : {"lines", "appendLines"}) {
    SCOPED_TRACE(form);
    std::vector<std::pair<uint32_t, uint8_t>> got;
    uint32_t t = 0;
    uint16_t check = kCheckInit;
    size_t programEvents = 0;
    for (const json& l : c[form]) {
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

TEST(ProgramVectors, PackedWordsAtTheEdges) {
  for (const json& c : V["packedWords"]) {
    const uint32_t w = c[0];
    const std::string line = c[1];
    char out[kPackMaxChars];
    EXPECT_EQ("B:0," + std::string(out, packWord(w, out)), line);
    AppendLine a;
    ASSERT_TRUE(a.begin(line.data(), static_cast<uint8_t>(line.size())));
    EXPECT_TRUE(a.packed());
    uint32_t got = 0;
    EXPECT_TRUE(a.nextWord(got));
    EXPECT_EQ(got, w);
    EXPECT_FALSE(a.nextWord(got));
    EXPECT_FALSE(a.malformed());
    EXPECT_EQ(checkWord(kCheckInit, w), checkEvent(kCheckInit, w >> 4, w & 15));
    counted();
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

// Three programs of 64 events `spacing` µs apart, through LinkLoad as the planner and M29 feed it.
static bool chainFits(uint32_t spacing, uint64_t& need, uint64_t& have, uint32_t& thirdBytes, uint32_t baud = kNanoBaud) {
  Events events;
  for (uint32_t i = 1; i <= 3u * kProgramEvents; i++) events.list.push_back({i * spacing, static_cast<uint8_t>(i % 2)});
  ProgramLines writer(Events::take, &events);
  LinkLoad load(baud);
  char out[kNanoMaxLine + 2];
  uint16_t sealed = 0;
  thirdBytes = 0;
  while (uint8_t n = writer.next(out)) {
    load.add(out, n, writer.lastUs());
    if (sealed == 2) thirdBytes += n;
    if (out[0] == 'K') sealed++;
  }
  return load.fits(events.list.back().first, need, have);
}

TEST(LinkLoad, EachProgramAfterTheFirstTwoMustFitTheTimeTheOneBeforeItPlays) {
  uint64_t need = 0, have = 0;
  uint32_t third = 0;
  // At 300 µs an event the whole chain fits the link (its third program's 20 ms within four fifths
  // of 58 ms), but the third program has only the second's 19 ms, less the relay, and needs 5/4 of
  // its 20.
  EXPECT_FALSE(chainFits(300, need, have, third));
  EXPECT_EQ(need, 5 * sendUs(third, kProgramEvents, kNanoBaud) + 4 * kProgramRelayUs);
  EXPECT_EQ(have, 4u * 64 * 300);
  EXPECT_LE(5 * sendUs(third, kProgramEvents, kNanoBaud), 4u * 192 * 300);
  EXPECT_TRUE(chainFits(2000, need, have, third));
}

TEST(LinkLoad, ARaisedLinkCarriesWhatTheMegaMakes) {
  uint64_t need = 0, have = 0;
  uint32_t third = 0;
  // Events 535 µs apart: at 115200 the third program's lines take a little longer on the wire than
  // the Mega takes to make their 64 events, and come too late; at 250000 the making sets the pace.
  EXPECT_FALSE(chainFits(535, need, have, third, kNanoBaud));
  EXPECT_GT(linkUs(third, kNanoBaud), 64u * kProgramEventUs);
  EXPECT_EQ(need, 5 * linkUs(third, kNanoBaud) + 4 * kProgramRelayUs);
  EXPECT_TRUE(chainFits(535, need, have, third, 250000));
  EXPECT_EQ(linkUs(third, 250000), third * 40u);  // ten bits a byte at 250000: 40 µs
  EXPECT_LT(linkUs(third, 250000), 64u * kProgramEventUs);
}

TEST(LinkLoad, AProgramGoesOutNoFasterThanTheMegaMakesItsEvents) {
  EXPECT_EQ(sendUs(100, 64, kNanoBaud), 64u * kProgramEventUs);  // 8.7 ms on the wire, 64 events to make
  EXPECT_EQ(sendUs(1000, 1, kNanoBaud), linkUs(1000, kNanoBaud));
  EXPECT_EQ(sendUs(1000, 1, 250000), 40000u);  // the same lines at 250000: 40 ms
}
