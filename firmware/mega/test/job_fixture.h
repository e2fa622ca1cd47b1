// Host tests' jobs: a header, a seeded pattern of cells, the job text the app would send, and
// the plan the firmware must follow (the shared planner over the same cells).
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "grid_cells.h"
#include "job_encoder.h"
#include "planner.h"

namespace mega {
namespace jobs {

using Lines = std::vector<std::string>;
using Grid = std::vector<std::vector<uint8_t>>;

struct Records : uv::RecordSink {
  Lines lines;
  void record(const char* text, uint8_t len) override { lines.emplace_back(text, len); }
};

// Cells of 0.1 mm from (5 mm, 4 mm), a linear 2 ms dose, LEDs a row apart with gains a little apart.
inline uv::JobHeader header(uint16_t cols, uint16_t rows, uv::Strategy strategy) {
  uv::JobHeader h{};
  h.cols = cols;
  h.rows = rows;
  h.pitchUm[0] = h.pitchUm[1] = 100;
  h.originUm[0] = 5000;
  h.originUm[1] = 4000;
  h.map = uv::DoseMap::Linear;
  h.fullUs = 2000;
  h.thermalRefDeciC = 250;
  for (int k = 0; k < 4; k++) {
    h.gainPermille[k] = static_cast<uint16_t>(1000 + 50 * k);
    h.offsets[k][1] = static_cast<int16_t>(k);
  }
  h.strategy = strategy;
  return h;
}

// About a third of the cells lit, at seeded values.
inline Grid pattern(uint16_t cols, uint16_t rows, uint32_t seed) {
  Grid g(rows, std::vector<uint8_t>(cols, 0));
  for (uint16_t r = 0; r < rows; r++)
    for (uint16_t c = 0; c < cols; c++) {
      seed = seed * 1103515245u + 12345u;
      if ((seed >> 16) % 3 == 0) g[r][c] = static_cast<uint8_t>(1 + (seed >> 8) % 255);
    }
  return g;
}

// Bands of equal cells, gaps of zeros and a few short runs: rows that format 2 writes as `rl` records.
inline Grid runs(uint16_t cols, uint16_t rows, uint32_t seed) {
  Grid g(rows, std::vector<uint8_t>(cols, 0));
  for (uint16_t r = 0; r < rows; r++)
    for (uint16_t c = 0; c < cols;) {
      seed = seed * 1103515245u + 12345u;
      uint16_t n = static_cast<uint16_t>(1 + (seed >> 16) % 12);
      uint8_t v = (seed >> 8) % 3 == 0 ? 0 : static_cast<uint8_t>((seed >> 4) % 2 ? 255 : 90);
      for (uint16_t i = 0; i < n && c < cols; i++) g[r][c++] = v;
    }
  return g;
}

inline Lines encode(const uv::JobHeader& h, const Grid& g, uint8_t format = 1) {
  Records out;
  uv::JobEncoder enc(out, format);
  enc.header(h);
  for (uint16_t r = 0; r < h.rows; r++) enc.row(r, g[r].data(), h.cols);
  enc.finish();
  return out.lines;
}

// What the firmware must expose: the shared planner over the same cells, from the origin, with
// the default settings' machine.
inline std::vector<uv::Stop> plan(const uv::JobHeader& h, const Grid& g) {
  uvtest::GridCells cells(g);
  const uv::MotionModel m{{100000, 100000}, {2000000, 1500000}, 2000, 1500, {0, 0}, {80000, 80000}};
  uv::Planner p(h, cells, m);
  std::vector<uv::Stop> out;
  uv::Stop s;
  while (p.next(s)) out.push_back(s);
  return out;
}

inline bool has(const Lines& lines, const std::string& prefix) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(prefix, 0) == 0; });
}

}  // namespace jobs
}  // namespace mega
