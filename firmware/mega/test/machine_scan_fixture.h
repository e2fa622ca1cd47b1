// The machine tests' scan jobs (machine_scan_card_test.cpp, machine_scan_stream_test.cpp, machine_scan_link_test.cpp): a job of
// scandose::testPattern, every LED at the same gain, and each cell's dose measured from the light
// and the head's steps.
#pragma once
#include <string>
#include <vector>

#include "machine_job_fixture.h"
#include "scan_dose.h"

namespace mega {

struct ScanMachineTest : JobTest {
  uv::JobHeader h;
  jobs::Grid g;
  // Steps of the rig a reset replaced, from the origin: the rig has no switches, so each homing
  // sets the origin where its seek ends, and the track starts again at it after the next.
  std::vector<StepEvent> before;

  void job(uint16_t cols, uint16_t rows, uint32_t fullUs) {
    h = jobs::header(cols, rows, uv::Strategy::Scan);
    h.fullUs = fullUs;
    for (int k = 0; k < 4; k++) h.gainPermille[k] = 1000;
    g = scandose::testPattern(cols, rows);
  }
  // A photo: every cell a different gray, so each LED switches twice a window.
  void photo(uint16_t cols, uint16_t rows, uint32_t fullUs) {
    job(cols, rows, fullUs);
    for (uint16_t r = 0; r < h.rows; r++)
      for (uint16_t c = 0; c < h.cols; c++) g[r][c] = static_cast<uint8_t>(1 + (c * 97 + r * 31) % 253);
  }
  // Selects the uploaded job, homes, and starts it; the track starts at the origin.
  void start(const std::string& name) {
    m.cmd("M23 " + name);
    m.cmd("G28");
    m.rig.steps.clear();
    m.cmd("M24");
  }
  // Starts the uploaded job and runs it to its end: "JOB:done".
  void runToDone(const std::string& name) {
    start(name);
    const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 120000000);
    ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  }
  // No light outside the cells, every cell within 2 % of its dose, every edge within a quarter cell.
  static void expectEveryCellItsDose(const scandose::Figures& f) {
    EXPECT_EQ(f.stray, 0);
    EXPECT_LE(f.worstDosePct, 2.0);
    EXPECT_LE(f.worstEdgeUm, 100 / 4.0);
  }
  // Homes, then streams the job (M828 … M29); the track starts at the origin.
  void stream() {
    ASSERT_TRUE(jobs::has(m.cmd("G28"), "ok"));
    m.rig.steps.clear();
    m.cmd("M828");
    for (const std::string& r : jobs::encode(h, g)) m.cmd(r);
    m.cmd("M29");
  }
  // Runs until an LED is lit.
  bool lightOn() {
    for (int i = 0; i < 400000 && m.nano.lit() == 0; i++) m.run(100);
    return m.nano.lit() != 0;
  }
  scandose::Figures measure(uint32_t windowUs) { return measure(std::vector<double>(h.rows, windowUs)); }
  scandose::Figures measure(const std::vector<double>& windowOfRow) {
    scandose::Track track;
    track.add(0, 0, 0);
    scandose::addSteps(track, before);
    scandose::addSteps(track, m.rig.steps);
    const double spm[2] = {80, 80};
    return scandose::measure(h, g, scandose::lightsOf(m.nano.scanLight), track, spm, windowOfRow);
  }
};

}  // namespace mega
