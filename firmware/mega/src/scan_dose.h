// Test support: the dose each cell received in a scan job, measured from what the machine did (the
// LEDs' on/off times and the head's steps over time), against what the job asked for. Shared by the
// host test (scan_run_test.cpp) and the simavr test of the real images (sim/scan_sim_test.cpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "grid_cells.h"
#include "job_types.h"
#include "planner.h"
#include "scan.h"

namespace scandose {

// The cell window of the pass that exposes each row, as the scan planner lays the job out on `m`
// (each pass at the job's window, or slower where the printhead link caps it).
inline std::vector<double> passWindows(const uv::JobHeader& h, const std::vector<std::vector<uint8_t>>& grid, const uv::MotionModel& m) {
  std::vector<double> out(h.rows, 0);
  uvtest::GridCells cells(grid);
  uv::ScanPlanner plan(h, cells, m);
  uv::ScanPass p;
  while (plan.nextPass(p))
    for (uint8_t k = 0; k < 4; k++) {
      const int32_t r = p.hy + h.offsets[k][1];
      if (r >= 0 && r < h.rows && out[r] == 0) out[r] = plan.passMotion().windowUs;
    }
  return out;
}

// The scan tests' job: 1-cell lines (rows 0, 3, …), runs of four full cells (rows 1, 4, …) and a
// different gray in every cell (rows 2, 5, …).
inline std::vector<std::vector<uint8_t>> testPattern(uint16_t cols, uint16_t rows) {
  std::vector<std::vector<uint8_t>> g(rows, std::vector<uint8_t>(cols, 0));
  for (uint16_t r = 0; r < rows; r++)
    for (uint16_t c = 0; c < cols; c++) {
      if (r % 3 == 0) g[r][c] = (c % 2) ? 255 : 0;
      else if (r % 3 == 1) g[r][c] = (c / 4) % 2 ? 255 : 0;
      else g[r][c] = static_cast<uint8_t>((c * 41 + r * 13) % 256);
    }
  return g;
}

// A job with blank stretches a pass flies: in every row, islands of lit cells (full, gray and
// 1-cell features) far apart, at columns that shift from one four rows to the next.
inline std::vector<std::vector<uint8_t>> gapPattern(uint16_t cols, uint16_t rows) {
  std::vector<std::vector<uint8_t>> g(rows, std::vector<uint8_t>(cols, 0));
  for (uint16_t r = 0; r < rows; r++)
    for (uint16_t c = 0; c < cols; c++) {
      const uint16_t island = static_cast<uint16_t>((c + 13 * (r / 4)) % 60);
      if (island < 4) g[r][c] = 255;
      else if (island < 6) g[r][c] = static_cast<uint8_t>(60 + (c * 37 + r * 11) % 190);
      else if (island == 20 && r % 2 == 0) g[r][c] = 255;
    }
  return g;
}

// A job whose passes take both ways in mixed mode (planner.md "Mixed mode"): bands of four rows (one
// pass of four LEDs a row apart), in turn testPattern's first four rows and a pad of two cells, full
// or gray.
inline std::vector<std::vector<uint8_t>> mixedPattern(uint16_t cols, uint16_t rows) {
  const std::vector<std::vector<uint8_t>> dense = testPattern(cols, 4);
  std::vector<std::vector<uint8_t>> g(rows);
  for (uint16_t r = 0; r < rows; r++) {
    g[r] = dense[r % 4];
    if ((r / 4) % 2 == 0) continue;
    g[r].assign(cols, 0);
    const uint16_t c = static_cast<uint16_t>((r * 7) % (cols - 1));
    if (r % 4 == 0) g[r][c] = g[r][c + 1] = static_cast<uint8_t>(r % 16 == 4 ? 255 : 140);
  }
  return g;
}

// A mixed job with a band of stops (planner.md "Bands"): mixedPattern's rows up to `dense`, then a
// cell near one end or the other of every other row. Its passes from `dense` up, two cells far apart
// each, are cheaper as one band of stops, column by column (two columns), than pass by pass.
inline std::vector<std::vector<uint8_t>> bandedPattern(uint16_t cols, uint16_t rows, uint16_t dense) {
  std::vector<std::vector<uint8_t>> g = mixedPattern(cols, rows);
  for (uint16_t r = dense; r < rows; r++) {
    g[r].assign(cols, 0);
    if (r % 2) continue;
    g[r][r % 4 ? 1 : cols - 3] = static_cast<uint8_t>(r % 8 ? 255 : 150);
  }
  return g;
}

struct Light {
  uint8_t led;
  double onUs, offUs;
};

// The head's X and Y in steps after each step, with its time (µs).
struct Track {
  std::vector<double> t;
  std::vector<int32_t> x, y;
  void add(double us, int32_t xs, int32_t ys) {
    t.push_back(us);
    x.push_back(xs);
    y.push_back(ys);
  }
  size_t at(double us) const { return static_cast<size_t>(std::upper_bound(t.begin(), t.end(), us) - t.begin()); }
  // X in steps at `us`: linear between the step before and the step after (the rotor's travel).
  double xAt(double us) const {
    size_t i = at(us);
    if (i == 0) return x.front();
    if (i == t.size()) return x.back();
    return x[i - 1] + (x[i] - x[i - 1]) * (us - t[i - 1]) / (t[i] - t[i - 1]);
  }
  // A stop's light (a mixed job's stop pass): no step from `leadUs` before `from` until `to`, so the
  // head stood, at its last step's X (xAt would slide it towards the next move's first step).
  static constexpr double kStillLeadUs = 1000;
  bool stoodStill(double from, double to) const { return at(from - kStillLeadUs) == at(to); }
  double xHeld(double us) const {
    size_t i = at(us);
    return i == 0 ? x.front() : x[i - 1];
  }
  int32_t yAt(double us) const {
    size_t i = at(us);
    return i == 0 ? y.front() : y[i - 1];
  }
};

// Adds a step log to the track, from (0, 0): any log with each step's time in half-µs ticks
// (`us2`), the axes it stepped (`axes`, bit 0 X, bit 1 Y) and their directions (`dirNeg`).
template <class Steps>
void addSteps(Track& track, const Steps& steps) {
  int32_t x = 0, y = 0;
  for (const auto& e : steps) {
    if (e.axes & 1) x += (e.dirNeg & 1) ? -1 : 1;
    if (e.axes & 2) y += (e.dirNeg & 2) ? -1 : 1;
    track.add(e.us2 / 2.0, x, y);
  }
}

// The light from a log of on/off intervals with `led`, `onUs` and `offUs`.
template <class Log>
std::vector<Light> lightsOf(const Log& log) {
  std::vector<Light> out;
  for (const auto& l : log) out.push_back({l.led, static_cast<double>(l.onUs), static_cast<double>(l.offUs)});
  return out;
}

struct Figures {
  double worstDosePct = 0;   // of the full dose (the longest on-time), over every cell
  double worstCentreUm = 0;  // a cell's light's centroid from the cell's centre
  double worstEdgeUm = 0;    // an LED's switching from where the plan puts that edge on the bed
  int cells = 0, lit = 0;    // cells checked (the job's and a margin round it), cells that should have light
  int stray = 0;             // samples of light beyond the margin
  std::vector<std::vector<double>> dose;  // µs each of the job's cells received, [row][col]
};

// `stepsPerMm`: X and Y; `windowOfRow`: the cell window of the pass that exposes each row (the link
// cap may slow a pass, planner.md "The printhead link"). Every sample of light falls on the cell
// under its LED at that moment. The jobs measured give every LED the same gain.
inline Figures measure(const uv::JobHeader& h, const std::vector<std::vector<uint8_t>>& grid, const std::vector<Light>& lights,
                       const Track& track, const double stepsPerMm[2], const std::vector<double>& windowOfRow, double sampleUs = 0.25) {
  const uv::Durations dose(h);
  double full = 0;
  for (uint8_t k = 0; k < 4; k++) full = std::max(full, static_cast<double>(dose.us(k, 255)));
  const double px = h.pitchUm[0], py = h.pitchUm[1];
  // The job's cells and a margin of kMargin around them, where no light is wanted.
  constexpr int kMargin = 2;
  const int rowsM = h.rows + 2 * kMargin, colsM = h.cols + 2 * kMargin;
  std::vector<std::vector<double>> got(rowsM, std::vector<double>(colsM, 0)), xsum(rowsM, std::vector<double>(colsM, 0));
  auto want = [&](int r, int c) -> double {
    return r < 0 || r >= h.rows || c < 0 || c >= h.cols ? 0 : dose.us(0, grid[r][c]);  // every LED's gain is 1 here
  };
  Figures f;
  auto headCol = [&](double xSteps) { return (xSteps * 1000.0 / stepsPerMm[0] - h.originUm[0]) / px; };
  auto headRow = [&](int32_t ySteps) { return static_cast<int>(std::lround((ySteps * 1000.0 / stepsPerMm[1] - h.originUm[1]) / py)); };
  for (const Light& l : lights) {
    const int row = headRow(track.yAt(l.onUs)) + h.offsets[l.led][1];
    const bool still = track.stoodStill(l.onUs, l.offUs);
    auto xAt = [&](double t) { return still ? track.xHeld(t) : track.xAt(t); };
    for (double t = l.onUs + sampleUs / 2; t < l.offUs; t += sampleUs) {
      const double col = headCol(xAt(t)) + h.offsets[l.led][0];
      const int c = static_cast<int>(std::floor(col + 0.5));
      if (row < -kMargin || row >= h.rows + kMargin || c < -kMargin || c >= h.cols + kMargin) {
        f.stray++;
        continue;
      }
      got[row + kMargin][c + kMargin] += sampleUs;
      xsum[row + kMargin][c + kMargin] += (col - c) * px * sampleUs;
    }
    // The edges: on where the first cell's light should begin, off where the last's should end.
    const double on = headCol(xAt(l.onUs)) + h.offsets[l.led][0], off = headCol(xAt(l.offUs)) + h.offsets[l.led][0];
    const double dir = off >= on ? 1 : -1;
    // Each end's cell: the middle of that cell's own light, half of it (at most half a cell) in.
    const double half = std::min(std::fabs(off - on), 1.0) / 2;
    const int c0 = static_cast<int>(std::floor(on + dir * half + 0.5)), c1 = static_cast<int>(std::floor(off - dir * half + 0.5));
    if (still) {
      // A stop's light (a mixed job's stop pass, planner.md "Mixed mode"): the head stood still, so
      // the spot's edges are the cell's own, off by as much as the head stands off the cell's centre.
      const int c = static_cast<int>(std::floor(on + 0.5));
      if (row >= 0 && row < h.rows && c >= 0 && c < h.cols) f.worstEdgeUm = std::max(f.worstEdgeUm, std::fabs((on - c) * px));
    } else if (row >= 0 && row < h.rows && c0 >= 0 && c0 < h.cols && c1 >= 0 && c1 < h.cols) {
      const double t0 = dose.us(l.led, grid[row][c0]), t1 = dose.us(l.led, grid[row][c1]), windowUs = windowOfRow[row];
      // Centred in its window: half its on-time either side of the centre, one pitch a window.
      f.worstEdgeUm = std::max(f.worstEdgeUm, std::fabs((on - (c0 - dir * t0 / (2 * windowUs))) * px));
      f.worstEdgeUm = std::max(f.worstEdgeUm, std::fabs((off - (c1 + dir * t1 / (2 * windowUs))) * px));
    }
  }
  f.dose.assign(h.rows, std::vector<double>(h.cols, 0));
  for (int r = 0; r < h.rows; r++)
    for (int c = 0; c < h.cols; c++) f.dose[r][c] = got[r + kMargin][c + kMargin];
  for (int r = -kMargin; r < h.rows + kMargin; r++)
    for (int c = -kMargin; c < h.cols + kMargin; c++) {
      const double w = want(r, c), g = got[r + kMargin][c + kMargin];
      f.cells++;
      f.worstDosePct = std::max(f.worstDosePct, std::fabs(g - w) * 100 / full);
      if (w <= 0) continue;
      f.lit++;
      // Where a cell's own light is centred (slivers of a neighbour's at its edge count in the dose).
      if (g > 0) f.worstCentreUm = std::max(f.worstCentreUm, std::fabs(xsum[r + kMargin][c + kMargin] / g));
    }
  return f;
}

// Every pass at the one window `windowUs`.
inline Figures measure(const uv::JobHeader& h, const std::vector<std::vector<uint8_t>>& grid, const std::vector<Light>& lights,
                       const Track& track, const double stepsPerMm[2], double windowUs, double sampleUs = 0.25) {
  return measure(h, grid, lights, track, stepsPerMm, std::vector<double>(h.rows, windowUs), sampleUs);
}

}  // namespace scandose
