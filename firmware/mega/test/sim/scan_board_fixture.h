// The simavr scan tests' fixture (scan_sim_test.cpp, mixed_sim_test.cpp): streams a job to the real
// Mega image, runs it to its end, and measures each cell's dose and each LED edge from the head's
// steps and the Nano image's LED pins (scan_dose.h).
#pragma once
#include "dialect_reply.h"
#include <map>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <regex>
#include <string>
#include <vector>

#include "board_fixture.h"
#include "job_fixture.h"
#include "scan_dose.h"
#include "scan_program.h"

using namespace mega::jobs;

// Streams a scan job to the Mega image, runs it to its end, and measures the light the Nano image
// gave against the head's steps. `passes`: how many the job has.
class ScanOnBoard : public BoardTest {
 protected:
  // A scan job of the grid's size at `fullUs` a full cell, every LED at the same gain.
  static uv::JobHeader scanJob(const Grid& g, uint32_t fullUs) {
    uv::JobHeader h = header(static_cast<uint16_t>(g[0].size()), static_cast<uint16_t>(g.size()), uv::Strategy::Scan);
    h.fullUs = fullUs;
    for (int k = 0; k < 4; k++) h.gainPermille[k] = 1000;
    return h;
  }
  // Both host ports poll the temperatures and the job while it runs (the stack's heaviest run).
  bool pollBothHosts = false;
  int espHeard = 0;  // the ESP port's temperature reports
  double jobUs = 0;  // expose(): from the M29's ok to the job's end, on the Mega's clock
  scandose::Figures expose(const uv::JobHeader& h, const Grid& g, int passes) { return expose(h, g, passes, passes, std::vector<double>(h.rows, h.fullUs)); }
  // `steps`: the job's progress count (a mixed job's stops count one each); `strokes`: its passes on
  // the move (one G each); `windowOfRow`: the window of the pass on the move that exposes each row.
  scandose::Figures expose(const uv::JobHeader& h, const Grid& g, int steps, int strokes, const std::vector<double>& windowOfRow) {
    const int passes = strokes;
    EXPECT_TRUE(said(cmd("G28", 8e6), "ok"));
    const int32_t home[2] = {sim.pos[0], sim.pos[1]};  // the Mega's 0 in the rig's count
    sim.logging = true;
    EXPECT_TRUE(said(numbered("M828"), "ok"));
    for (const std::string& r : encode(h, g)) EXPECT_TRUE(said(numbered(r), "ok")) << r;
    EXPECT_TRUE(said(numbered("M29"), "ok"));
    const uint64_t started = sim.megaCycle();
    std::string end;
    bool reset = passes < 2;
    uint64_t nextPoll = sim.megaCycle();
    EXPECT_TRUE(sim.runUntil([&] {
      if (pollBothHosts && sim.megaCycle() >= nextPoll) {
        // Both hosts ask what a dashboard asks, every 100 ms, each within its window (mega.md §3).
        sim.send("M105\nM114\nM27\n");
        sim.sendEsp("M105\nM27\n");
        nextPoll = sim.megaCycle() + static_cast<uint64_t>(100e3 * BoardSim::kCyclesPerUs);
      }
      for (std::string& l : sim.takeEspLines()) espHeard += l.rfind("T:", 0) == 0;
      if (!reset && std::count(sim.nanoLines.begin(), sim.nanoLines.end(), "G") == 2) {
        sim.send("M821 R\n");  // the main loop's longest pass, from the second pass's G on
        reset = true;
      }
      for (std::string& l : sim.takeLines()) {
        seen.push_back(l);
        if (l.rfind("JOB:done", 0) == 0 || l.rfind("JOB:failed", 0) == 0 || l.rfind("JOB:paused", 0) == 0) end = l;
      }
      return !end.empty();
    }, 20e6));
    sim.logging = false;
    jobUs = (sim.megaCycle() - started) / BoardSim::kCyclesPerUs;
    std::string replies;
    for (const std::string& l : sim.nanoReplies) replies += l + " ";
    EXPECT_EQ(end.rfind("JOB:done", 0), 0u) << end << "\nthe Nano said: " << replies;
    const std::string all = std::to_string(steps);
    EXPECT_NE(end.find("stop=" + all + "/" + all), std::string::npos) << end;
    int gs = 0;
    for (const std::string& l : sim.nanoLines) gs += l == "G";
    EXPECT_EQ(gs, passes);

    scandose::Track track;
    track.add(0, 0, 0);
    for (const BoardSim::HeadStep& s : sim.headSteps) track.add(s.cycle / BoardSim::kCyclesPerUs, s.x - home[0], s.y - home[1]);
    // simavr sends a UART frame in 11 bit-times where the chip takes 10 (93.5 µs against 85.0 at the
    // Mega's divisor, ../shared/TOOLCHAIN.md): the G and its newline reach the simulated Nano 2
    // bit-times (17 µs) later than on the machine, and every edge of the chain with them. The light
    // is measured as the chip would give it.
    constexpr double kSimUartLagUs = 2 * 8.5;
    std::vector<scandose::Light> lights;
    double onAt[4] = {};
    for (const BoardSim::LedEdge& e : sim.ledEdges) {
      const double t = e.cycle / BoardSim::kCyclesPerUs - kSimUartLagUs;
      if (e.on) onAt[e.led] = t;
      else lights.push_back({static_cast<uint8_t>(e.led), onAt[e.led], t});
    }
    EXPECT_FALSE(lights.empty());
    const double spm[2] = {80, 80};
    return scandose::measure(h, g, lights, track, spm, windowOfRow);
  }
  // The DOSE: lines the USB host read (protocol/mega.md "Dose reports") against the Nano image's LED
  // pins: per LED, the on-times reported and the light the pins gave, in µs; the lines, and whether
  // each pass's programs came in order from 0, each once.
  struct DoseFigures {
    double reportedUs[4] = {}, pinUs[4] = {};
    int stretches[4] = {};
    int lines = 0;
    bool inOrder = true;
  };
  DoseFigures doseAgainstPins() const {
    DoseFigures d;
    std::map<uint32_t, uint16_t> next;  // per pass, the program that comes next
    for (const std::string& l : seen) {
      if (l.rfind("DOSE:", 0) != 0) continue;
      uv::Reply r{};
      if (!uv::parseReply(l.data(), static_cast<uint8_t>(l.size()), r) || r.kind != uv::ReplyKind::Dose) {
        d.inOrder = false;
        continue;
      }
      d.inOrder = d.inOrder && r.dose.program == next[r.dose.stop]++ && !r.dose.cut && !r.dose.again;
      d.lines++;
      for (int k = 0; k < 4; k++) d.reportedUs[k] += r.dose.onUs[k];
    }
    double onAt[4] = {};
    for (const BoardSim::LedEdge& e : sim.ledEdges) {
      const double t = e.cycle / BoardSim::kCyclesPerUs;
      if (e.on) onAt[e.led] = t;
      else {
        d.pinUs[e.led] += t - onAt[e.led];
        d.stretches[e.led]++;
      }
    }
    return d;
  }
  // M821's longest main-loop pass (µs) since the second pass's G (the pass that follows flying, and
  // not the opening of the next, 18 ms at rest), and the step underruns.
  void diagnostics(unsigned& loopMaxUs, unsigned& underruns) {
    // The polls' last lines may still fill the USB port's window of 3 (mega.md §3), and a line past
    // it is lost: their replies come first, then M821 goes, and its answer is the DIAG line.
    sim.runUntil([] { return false; }, 200e3);
    sim.takeLines();
    std::string line;
    for (const std::string& l : cmd("M821"))
      if (l.rfind("echo:DIAG", 0) == 0) line = l;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(line, m, std::regex(R"(loop_max_us=(\d+) step_isr_max_us=\d+ underruns=(\d+))"))) << line;
    loopMaxUs = std::stoul(m[1]);
    underruns = std::stoul(m[2]);
  }
  // The printhead link in the last pass on the move (planner.md "The printhead link"): for each
  // program k >= 3 of its chain, the relay (from program k - 2's last event on the Nano's pins, when
  // its buffer frees, to program k's first byte leaving the Mega) and the slack (from its K line's
  // newline leaving the Mega to program k - 1's last event, by when it must be armed); the worst of
  // each, in µs, and how many programs waited for a buffer.
  struct LinkFigures {
    int waited = 0;
    double relayMaxUs = 0, slackMinUs = 1e9;
  };
  LinkFigures linkFigures() const {
    struct Program {
      size_t first, seal;
      int events;
    };
    std::vector<Program> programs;
    size_t lastG = 0, first = SIZE_MAX, chain = 0;  // the last G; the last chain's first program
    for (size_t i = 0; i < sim.nanoLines.size(); i++)
      if (sim.nanoLines[i] == "G") lastG = i;
    for (size_t i = 0; i < sim.nanoLines.size(); i++) {
      const std::string& l = sim.nanoLines[i];
      if ((l.rfind("B:0,", 0) == 0 || l.rfind("A:0,", 0) == 0)) first = i;
      if (l.rfind("K:", 0) != 0 || first == SIZE_MAX) continue;
      if (!((l[2] - '0') & uv::kSealContinuation) && first < lastG) chain = programs.size();
      programs.push_back({first, i, std::stoi(l.substr(l.find(',') + 1))});
    }
    const std::vector<Program> pass(programs.begin() + static_cast<long>(chain), programs.end());
    std::vector<uint64_t> events;  // the distinct edge times after the G: one port write an event
    const uint64_t g = sim.nanoLineLast.at(lastG);
    for (const BoardSim::LedEdge& e : sim.ledEdges)
      if (e.cycle > g && (events.empty() || events.back() != e.cycle)) events.push_back(e.cycle);
    LinkFigures f;
    std::vector<uint64_t> ends;
    size_t n = 0;
    for (const Program& p : pass) {
      n += p.events;
      ends.push_back(events.at(std::min(n, events.size()) - 1));
    }
    for (size_t k = 2; k < pass.size(); k++) {
      if (getenv("SCAN_LINK_VERBOSE"))
        for (size_t i = pass[k - 1].seal; i <= pass[k].seal; i++)
          std::printf("program %zu: %+.0f us .. %+.0f us %s (program k-1 ends %+.0f us)\n", k, (static_cast<double>(sim.nanoLineFirst.at(i)) - ends[k - 2]) / BoardSim::kCyclesPerUs, (static_cast<double>(sim.nanoLineLast.at(i)) - ends[k - 2]) / BoardSim::kCyclesPerUs, sim.nanoLines[i].substr(0, 12).c_str(), (static_cast<double>(ends[k - 1]) - ends[k - 2]) / BoardSim::kCyclesPerUs);
      f.waited++;
      f.relayMaxUs = std::max(f.relayMaxUs, (static_cast<double>(sim.nanoLineFirst.at(pass[k].first)) - ends[k - 2]) / BoardSim::kCyclesPerUs);
      f.slackMinUs = std::min(f.slackMinUs, (static_cast<double>(ends[k - 1]) - sim.nanoLineLast.at(pass[k].seal)) / BoardSim::kCyclesPerUs);
    }
    return f;
  }
  // Between passes, from each pass's last light to the first step of the hop to the next (which
  // glides once the next pass has opened: the Mega plans it then, its link check walking every event
  // of it), ms, comma-separated.
  std::string turnsMs() const {
    std::string out;
    int32_t y = INT32_MIN;
    uint64_t hopAfter = 0;  // the light the last hop followed
    for (const BoardSim::HeadStep& e : sim.headSteps) {
      if (y != INT32_MIN && e.y != y) {
        uint64_t lastOff = 0;
        for (const BoardSim::LedEdge& l : sim.ledEdges)
          if (l.cycle < e.cycle && !l.on) lastOff = l.cycle;
        if (lastOff > hopAfter) {  // the first step after a pass's light: a hop begins
          char b[32];
          std::snprintf(b, sizeof b, "%s%.1f", out.empty() ? "" : ", ", static_cast<double>(e.cycle - lastOff) / BoardSim::kCyclesPerUs / 1e3);
          out += b;
          hopAfter = lastOff;
        }
      }
      y = e.y;
    }
    return out;
  }
  // The head's fastest X step, in steps/s.
  double fastestX() const {
    double best = 0;
    for (size_t i = 1; i < sim.headSteps.size(); i++)
      if (sim.headSteps[i].x != sim.headSteps[i - 1].x)
        best = std::max(best, BoardSim::kCyclesPerUs * 1e6 / static_cast<double>(sim.headSteps[i].cycle - sim.headSteps[i - 1].cycle));
    return best;
  }
};

