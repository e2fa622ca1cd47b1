// Host tests of the scan planner against the printhead link (planner.md "The printhead link"): every
// pass of the golden scan jobs, cut into the lines the Mega sends, loads each program after the first
// two while the one before it plays, with the relay and a fifth to spare. The rule's arithmetic is
// the test's own, not uv::LinkLoad's, which the planner asks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
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

// Each golden scan case (scan-cpp.json): its name, rows, job and machine.
template <class F>
void forEachScanCase(F f) {
  const json v = loadVectors("scan-cpp.json");
  for (const json& c : v["cases"]) {
    std::vector<std::vector<uint8_t>> rows;
    for (const auto& r : c["job"]["gridData"]) rows.emplace_back(r.begin(), r.end());
    f(c["name"].get<std::string>(), rows, headerFrom(c["job"]), machineFrom(c["machine"]));
  }
}

}  // namespace

TEST(ScanLink, EveryProgramAfterTheFirstTwoLoadsWhileTheOneBeforeItPlays) {
  size_t chains = 0, programs = 0;
  forEachScanCase([&](const std::string& name, const std::vector<std::vector<uint8_t>>& rows, const JobHeader& h, const MotionModel& m) {
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
      EXPECT_EQ(planner.chainBytes(), bytes) << name << " pass " << pass.hy;
      EXPECT_EQ(planner.chainAheadBytes(), p.size() > 1 ? p[0].bytes + p[1].bytes : bytes) << name << " pass " << pass.hy;
      if (p.size() > 2) chains++;
      for (size_t k = 2; k < p.size(); k++, programs++)
        EXPECT_LE(5 * sendingUs(p[k].bytes, p[k].events, m.linkBaud) + 4ull * kProgramRelayUs, 4ull * (p[k - 1].endUs - p[k - 2].endUs))
            << name << " pass " << pass.hy << " program " << k + 1;
    }
  });
  EXPECT_GT(chains, 0u);
  std::printf("[scan link] %zu chains of three programs or more, %zu programs loaded while another plays\n", chains, programs);
}

// A card job's passes are planned again as they run from what planning kept of each at M29
// (KeptPass, in the job's index file): given those, the plan is the searched plan to the last event
// and µs, no link check runs (its chain count stays unset), and no cell is read to open a pass: each
// of its rows is opened once, for its events. And as the Mega runs them, unpriced: the same passes
// and events.
TEST(ScanLink, APassOpenedFromWhatPlanningKeptIsThatPassWithoutReadingItsCells) {
  size_t passes = 0, capped = 0, flying = 0;
  forEachScanCase([&](const std::string& name, const std::vector<std::vector<uint8_t>>& rows, const JobHeader& h, const MotionModel& machine) {
    if (h.strategy == Strategy::Mixed) return;  // a mixed job's passes are always searched
    for (uint32_t baud : {kNanoBaud, 57600u}) {  // 57600: more passes capped, some more than once
      MotionModel m = machine;
      m.linkBaud = baud;
      auto plan = [&](const std::vector<KeptPass>* given, std::vector<KeptPass>& kept, bool priced = true) {
        GridCells cells(rows);
        ScanPlanner planner(h, cells, m);
        if (!priced) planner.unpriced();
        std::vector<std::vector<uint64_t>> out;
        ScanPass p;
        for (size_t k = 0;; k++) {
          const int opened = cells.rowsOpened;
          if (!planner.nextPass(p, given && k < given->size() ? &(*given)[k] : nullptr)) break;
          kept.emplace_back();
          planner.keep(p, kept.back());
          std::vector<uint64_t> pass{static_cast<uint64_t>(p.hy), p.descending, static_cast<uint64_t>(p.first), static_cast<uint64_t>(p.last),
                                     static_cast<uint64_t>(p.runUpUm), static_cast<uint64_t>(p.runOutUm), planner.jumps()};
          if (priced) pass.insert(pass.end(), {p.moveUs, p.strokeUs, p.scanUs, static_cast<uint64_t>(p.startSteps)});
          uint32_t t;
          uint8_t state;
          while (planner.nextEvent(t, state)) pass.insert(pass.end(), {t, state});
          if (given) {
            EXPECT_EQ(planner.chainBytes(), 0u) << "a link check ran";
            EXPECT_LE(cells.rowsOpened - opened, 4) << "a layout read the pass's cells";
          }
          out.push_back(pass);
        }
        out.push_back({priced ? planner.estimateUs() : 0, planner.passes()});
        return out;
      };
      std::vector<KeptPass> found, again, run;
      const auto searched = plan(nullptr, found);
      EXPECT_EQ(plan(&found, again), searched) << name << " at " << baud;
      // Unpriced, searched or from what was kept, the same passes and events, and the same kept.
      auto shapes = searched;
      for (size_t k = 0; k + 1 < shapes.size(); k++) shapes[k].erase(shapes[k].begin() + 7, shapes[k].begin() + 11);  // its price
      shapes.back()[0] = 0;  // the estimate
      std::vector<KeptPass> unpricedFound;
      EXPECT_EQ(plan(nullptr, unpricedFound, false), shapes) << name << " at " << baud;
      EXPECT_EQ(plan(&found, run, false), shapes) << name << " at " << baud;
      ASSERT_EQ(unpricedFound.size(), found.size());
      for (size_t k = 0; k < found.size(); k++) EXPECT_EQ(std::memcmp(&unpricedFound[k], &found[k], sizeof(KeptPass)), 0) << "pass " << k;
      ASSERT_EQ(again.size(), found.size());
      for (size_t k = 0; k < found.size(); k++) EXPECT_EQ(std::memcmp(&again[k], &found[k], sizeof(KeptPass)), 0) << "pass " << k;
      GridCells cells(rows);
      const uint32_t jobWindow = ScanPlanner(h, cells, m).motion().windowUs;
      passes += found.size();
      for (const KeptPass& k : found) {
        capped += k.windowUs > jobWindow;
        flying += k.jumpG[0] > 0;
      }
    }
  });
  EXPECT_GT(capped, 0u);
  EXPECT_GT(flying, 0u);
  std::printf("[scan link] %zu passes planned again from what planning kept, %zu of them capped for the link and %zu flying a stretch: the same plans\n", passes, capped, flying);
}

// A kept pass that planning could not have kept (the card's file is not what M29 wrote) is laid out
// and searched for as without one: the same plan. One kept for another head row passes over the
// passes before it, so the run ends short (the Mega then fails the job E22: card_scan.cpp).
TEST(ScanLink, AKeptPassPlanningCouldNotHaveKeptIsLaidOutAgain) {
  size_t mangled = 0;
  forEachScanCase([&](const std::string& name, const std::vector<std::vector<uint8_t>>& rows, const JobHeader& h, const MotionModel& m) {
    if (h.strategy == Strategy::Mixed) return;
    auto plan = [&](std::vector<KeptPass>* kept, bool keep) {
      GridCells cells(rows);
      ScanPlanner planner(h, cells, m);
      std::vector<uint64_t> out;
      ScanPass p;
      for (size_t k = 0; planner.nextPass(p, !keep && k < kept->size() ? &(*kept)[k] : nullptr); k++) {
        if (keep) {
          kept->emplace_back();
          planner.keep(p, kept->back());
        }
        out.insert(out.end(), {static_cast<uint64_t>(p.hy), static_cast<uint64_t>(p.first), static_cast<uint64_t>(p.last), p.scanUs, planner.jumps()});
        uint32_t t;
        uint8_t state;
        while (planner.nextEvent(t, state)) out.insert(out.end(), {t, state});
      }
      out.push_back(planner.estimateUs());
      return out;
    };
    std::vector<KeptPass> found;
    const auto searched = plan(&found, true);
    GridCells cells(rows);
    const uint32_t jobWindow = ScanPlanner(h, cells, m).motion().windowUs;
    for (int how = 0; how < 4; how++) {
      std::vector<KeptPass> bad = found;
      for (KeptPass& k : bad) {
        if (how == 0) k.windowUs = jobWindow - 1;  // faster than the light allows
        if (how == 1) std::swap(k.first, k.last), k.first += k.first == k.last;  // no pass
        if (how == 2) k.jumpG[0] = static_cast<uint16_t>(k.last - k.first + 1);  // a stretch past the pass's end
        if (how == 3) k.jumpCol[0] = 0, k.jumpG[0] = k.jumpG[0] ? k.jumpG[0] : 1;  // a stretch from its first lit window
      }
      EXPECT_EQ(plan(&bad, false), searched) << name << " mangled " << how;
      mangled += bad.size();
    }
    if (found.size() > 1) {
      std::vector<KeptPass> later(found.begin() + 1, found.end());
      std::vector<uint64_t> shorter = plan(&later, false);
      EXPECT_LT(shorter.size(), searched.size()) << name;
    }
  });
  EXPECT_GT(mangled, 0u);
}
