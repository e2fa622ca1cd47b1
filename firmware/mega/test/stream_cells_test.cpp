// Stream mode's buffer: the planner reading arrived rows through it plans exactly what it plans
// from the whole grid, while rows below the ones it still needs are freed.
#include "stream_cells.h"

#include <gtest/gtest.h>

#include <vector>

#include "grid_cells.h"

using namespace mega;

TEST(StreamCells, ThePlannerReadsItLikeTheWholeGridWhileItFreesRowsBehind) {
  uint32_t seed = 99;
  auto rnd = [&seed](uint32_t n) {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) % n;
  };
  for (int trial = 0; trial < 40; trial++) {
    uint16_t rows = static_cast<uint16_t>(4 + rnd(40)), cols = static_cast<uint16_t>(1 + rnd(40));
    std::vector<std::vector<uint8_t>> grid(rows, std::vector<uint8_t>(cols, 0));
    for (auto& r : grid)
      for (auto& v : r)
        if (rnd(3) == 0) v = static_cast<uint8_t>(1 + rnd(255));
    uv::JobHeader h{};
    h.cols = cols;
    h.rows = rows;
    h.pitchUm[0] = h.pitchUm[1] = 50;
    h.map = uv::DoseMap::Linear;
    h.fullUs = 1000;
    h.strategy = static_cast<uv::Strategy>(trial % 4);
    for (int k = 0; k < 4; k++) {
      h.gainPermille[k] = 1000;
      h.offsets[k][1] = static_cast<int16_t>(k);
    }
    const uv::MotionModel m{{100000, 100000}, {2000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};
    uvtest::GridCells all(grid);
    uv::Planner whole(h, all, m);
    std::vector<uv::Stop> expected;
    uv::Stop s;
    while (whole.next(s)) expected.push_back(s);

    uint8_t buffer[4096];
    StreamCells cells(buffer, sizeof buffer);
    uv::Planner streaming(h, cells, m);
    std::vector<uv::Stop> got;
    uint16_t peak = 0;
    for (uint16_t r = 0; r <= rows; r++) {
      if (r < rows) {  // the row arrives as records of up to 32 cells, zeros and all
        for (uint16_t c = 0; c < cols; c += 32) {
          uint8_t n = static_cast<uint8_t>(cols - c < 32 ? cols - c : 32);
          ASSERT_TRUE(cells.add(r, c, &grid[r][c], n));
        }
      }
      streaming.setKnownRows(static_cast<uint16_t>(r + 1 > rows ? rows : r + 1));
      while (streaming.next(s)) got.push_back(s);
      cells.freeBelow(static_cast<uint16_t>(streaming.lowestRowNeeded()));
      if (cells.cells() > peak) peak = cells.cells();
    }
    ASSERT_EQ(got.size(), expected.size()) << "trial " << trial;
    for (size_t i = 0; i < got.size(); i++) {
      ASSERT_EQ(got[i].hx, expected[i].hx) << "trial " << trial << " stop " << i;
      ASSERT_EQ(got[i].hy, expected[i].hy) << "trial " << trial << " stop " << i;
      for (int k = 0; k < 4; k++) ASSERT_EQ(got[i].us[k], expected[i].us[k]);
    }
    // It holds a band's worth of rows, not the job: 8 passes of 4 rows for `shortest`, else one pass.
    uint16_t band = static_cast<uint16_t>((h.strategy == uv::Strategy::Shortest ? 8 * 4 : 4) + 4);
    EXPECT_LE(peak, band * cols) << "trial " << trial;
  }
}

TEST(StreamCells, ASegmentThatDoesNotFitIsRefusedAndNothingChanges) {
  uint8_t buffer[20];
  StreamCells cells(buffer, sizeof buffer);
  const uint8_t a[8] = {1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_TRUE(cells.add(0, 0, a, 8));
  EXPECT_FALSE(cells.add(1, 0, a, 8));  // 13 + 13 > 20
  EXPECT_EQ(cells.used(), 13u);
  cells.freeBelow(1);
  EXPECT_EQ(cells.used(), 0u);
  EXPECT_TRUE(cells.add(1, 0, a, 8));
}
