// Host tests of the scan planner against the printhead link (planner.md "The printhead link"): every
// pass of the golden scan jobs, cut into the lines the Mega sends, loads each program after the first
// two while the one before it plays, with the relay and a fifth to spare. The rule's arithmetic is
// the test's own, not uv::LinkLoad's, which the planner asks.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "grid_cells.h"
#include "job_json_fixture.h"
#include "machine_json_fixture.h"
#include "scan.h"
#include "scan_program.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace {

struct Program {
  uint32_t bytes = 0, events = 0, endUs = 0;
};

struct Events {
  const std::vector<std::pair<uint32_t, uint8_t>>* list;
  size_t next = 0;
  static bool take(void* ctx, uint32_t& t, uint8_t& m) {
    Events& e = *static_cast<Events*>(ctx);
    if (e.next == e.list->size()) return false;
    t = (*e.list)[e.next].first;
    m = (*e.list)[e.next++].second;
    return true;
  }
};

// The programs of a pass's chain: each one's bytes (its B lines and its K line), events (its K line's
// count) and last event.
std::vector<Program> programsOf(const std::vector<std::pair<uint32_t, uint8_t>>& events, uint32_t& bytes) {
  Events source{&events};
  ProgramLines lines(Events::take, &source);
  std::vector<Program> out(1);
  char line[kNanoMaxLine + 2];
  bytes = 0;
  for (uint8_t n; (n = lines.next(line)) != 0;) {
    bytes += n;
    out.back().bytes += n;
    Seal seal;
    if (line[0] != 'K' || !parseSeal(line, static_cast<uint8_t>(n - 1), seal)) continue;
    out.back().events = seal.events;
    out.back().endUs = lines.lastUs();
    out.emplace_back();
  }
  EXPECT_FALSE(lines.failed());
  out.pop_back();
  return out;
}

// What a program's lines take to go out: the wire's time at ten bits a byte, or the Mega's making of
// its events (kProgramEventUs each) if longer.
uint64_t sendingUs(uint32_t bytes, uint32_t events, uint32_t baud) {
  return std::max<uint64_t>(static_cast<uint64_t>(bytes) * 10000000ull / baud, static_cast<uint64_t>(events) * kProgramEventUs);
}

}  // namespace

TEST(ScanLink, EveryProgramAfterTheFirstTwoLoadsWhileTheOneBeforeItPlays) {
  const json v = loadVectors("scan-cpp.json");
  size_t chains = 0, programs = 0;
  for (const json& c : v["cases"]) {
    std::vector<std::vector<uint8_t>> rows;
    for (const auto& r : c["job"]["gridData"]) rows.emplace_back(r.begin(), r.end());
    const JobHeader h = headerFrom(c["job"]);
    const MotionModel m = machineFrom(c["machine"]);
    GridCells cells(rows);
    ScanPlanner planner(h, cells, m);
    ScanPass pass;
    while (planner.nextPass(pass)) {
      std::vector<std::pair<uint32_t, uint8_t>> events;
      uint32_t t;
      uint8_t state;
      while (planner.nextEvent(t, state)) events.emplace_back(t, state);
      if (events.empty()) continue;
      uint32_t bytes;
      const std::vector<Program> p = programsOf(events, bytes);
      // The planner's own count of the chain it checked, at the window it kept (the bench's P11 reads it).
      EXPECT_EQ(planner.chainBytes(), bytes) << c["name"] << " pass " << pass.hy;
      EXPECT_EQ(planner.chainAheadBytes(), p.size() > 1 ? p[0].bytes + p[1].bytes : bytes) << c["name"] << " pass " << pass.hy;
      if (p.size() > 2) chains++;
      for (size_t k = 2; k < p.size(); k++, programs++)
        EXPECT_LE(5 * sendingUs(p[k].bytes, p[k].events, m.linkBaud) + 4ull * kProgramRelayUs, 4ull * (p[k - 1].endUs - p[k - 2].endUs))
            << c["name"] << " pass " << pass.hy << " program " << k + 1;
    }
  }
  EXPECT_GT(chains, 0u);
  std::printf("[scan link] %zu chains of three programs or more, %zu programs loaded while another plays\n", chains, programs);
}

// A card job's passes are planned again as they run at the windows the link check found at M29
// (nextPass's windowUs, kept in the job's index file): given those, the plan is the searched plan to
// the last event and µs, and no link check runs (its chain count stays unset).
TEST(ScanLink, APassGivenTheWindowItsSearchFoundIsThatPassWithoutTheSearch) {
  const json v = loadVectors("scan-cpp.json");
  size_t passes = 0, capped = 0;
  for (const json& c : v["cases"]) {
    std::vector<std::vector<uint8_t>> rows;
    for (const auto& r : c["job"]["gridData"]) rows.emplace_back(r.begin(), r.end());
    JobHeader h = headerFrom(c["job"]);
    if (h.strategy == Strategy::Mixed) continue;  // a mixed job's passes are always searched
    for (uint32_t baud : {kNanoBaud, 57600u}) {  // 57600: more passes capped, some more than once
      MotionModel m = machineFrom(c["machine"]);
      m.linkBaud = baud;
      auto plan = [&](const std::vector<uint32_t>* given, std::vector<uint32_t>& windows) {
        GridCells cells(rows);
        ScanPlanner planner(h, cells, m);
        std::vector<std::vector<uint64_t>> out;
        ScanPass p;
        for (size_t k = 0; planner.nextPass(p, given && k < given->size() ? (*given)[k] : 0); k++) {
          windows.push_back(planner.passMotion().windowUs);
          std::vector<uint64_t> pass{static_cast<uint64_t>(p.hy), p.descending, static_cast<uint64_t>(p.first), static_cast<uint64_t>(p.last),
                                     p.moveUs, p.strokeUs, p.scanUs, static_cast<uint64_t>(p.startSteps), planner.jumps()};
          uint32_t t;
          uint8_t state;
          while (planner.nextEvent(t, state)) pass.insert(pass.end(), {t, state});
          if (given) {
            EXPECT_EQ(planner.chainBytes(), 0u) << "a link check ran";
          }
          out.push_back(pass);
        }
        out.push_back({planner.estimateUs(), planner.passes()});
        return out;
      };
      std::vector<uint32_t> found, kept;
      const auto searched = plan(nullptr, found);
      EXPECT_EQ(plan(&found, kept), searched) << c["name"] << " at " << baud;
      EXPECT_EQ(kept, found);
      GridCells cells(rows);
      const uint32_t jobWindow = ScanPlanner(h, cells, m).motion().windowUs;
      passes += found.size();
      for (uint32_t w : found) capped += w > jobWindow;
    }
  }
  EXPECT_GT(capped, 0u);
  std::printf("[scan link] %zu passes planned again at the windows found, %zu of them capped for the link: the same plans\n", passes, capped);
}
