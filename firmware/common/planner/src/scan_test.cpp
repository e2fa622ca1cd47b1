// Host tests of the C++ scan planner: golden scan plans from both implementations, switch times of
// small features, and a pass at a time without the heap.
#include "scan.h"

#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "grid_cells.h"
#include "job_json_fixture.h"
#include "scan_json_fixture.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace uvtest {
extern std::atomic<long> allocations;  // counted by planner_test.cpp's operator new
}

namespace {

Machine scanMachineFrom(const json& m) {
  Machine out{};
  for (int a = 0; a < 2; a++) {
    out.vmaxUmS[a] = m["vmaxUmS"][a];
    out.accelUmS2[a] = m["accelUmS2"][a];
    out.startUm[a] = m["startUm"][a];
  }
  out.settleUs = m["settleUs"];
  out.overheadUs = m["overheadUs"];
  return out;
}

void checkScanGolden(const char* file) {
  const json v = loadVectors(file);
  ASSERT_GT(v["cases"].size(), 10u) << file;
  for (const json& c : v["cases"]) {
    std::vector<std::vector<uint8_t>> rows;
    for (const auto& r : c["job"]["gridData"]) rows.emplace_back(r.begin(), r.end());
    const JobHeader h = headerFrom(c["job"]);
    EXPECT_EQ(scanPlanJson(h, rows, scanMachineFrom(c["machine"])), c["scan"]) << c["name"];
  }
  std::printf("[vectors] %s: %zu scan plans checked (C++)\n", file, v["cases"].size());
}

const Machine kMachine{{150000, 100000}, {3000000, 2000000}, 2000, 1500, {0, 0}};

JobHeader smallJob(uint16_t cols, uint16_t rows) {
  JobHeader h{};
  h.cols = cols;
  h.rows = rows;
  h.pitchUm[0] = h.pitchUm[1] = 50;
  h.originUm[0] = 1000;
  h.originUm[1] = 2000;
  h.map = DoseMap::Linear;
  h.fullUs = 2000;
  for (int k = 0; k < 4; k++) {
    h.gainPermille[k] = 1000;
    h.offsets[k][1] = static_cast<int16_t>(k);
  }
  return h;
}

std::vector<std::vector<uint32_t>> switchesOf(ScanPlanner& planner, uint8_t led) {
  std::vector<std::vector<uint32_t>> out;
  uint32_t on, off;
  while (planner.nextSwitch(led, on, off)) out.push_back({on, off});
  return out;
}

}  // namespace

TEST(ScanGolden, ReproducesTypeScriptScans) { checkScanGolden("scan-ts.json"); }
TEST(ScanGolden, ReproducesItsOwnScans) { checkScanGolden("scan-cpp.json"); }

TEST(ScanPlanner, CentresGrayCellsMergesFullRunsAndReversesTheSecondPass) {
  JobHeader h = smallJob(12, 8);
  std::vector<std::vector<uint8_t>> rows(8, std::vector<uint8_t>(12, 0));
  rows[0][2] = rows[0][3] = rows[0][5] = 255;
  rows[0][4] = 128;  // t = 1004 µs, 498 µs into its window
  rows[4][3] = 51;   // t = 400 µs
  rows[4][9] = 255;
  GridCells cells(rows);
  ScanPlanner planner(h, cells, kMachine);
  EXPECT_EQ(planner.motion().windowUs, 2000u);
  EXPECT_EQ(planner.motion().speedUmS, 25000u);
  EXPECT_EQ(planner.motion().accelUs, 8334u);
  EXPECT_EQ(planner.motion().overscanUm, 105u);
  ScanPass p;
  ASSERT_TRUE(planner.nextPass(p));
  EXPECT_FALSE(p.descending);
  EXPECT_EQ(p.first, 2);
  EXPECT_EQ(p.last, 5);
  EXPECT_EQ(p.runUpUm, 1000 + 100 - 25 - 105);
  EXPECT_EQ(switchesOf(planner, 0), (std::vector<std::vector<uint32_t>>{{0, 4000}, {4498, 5502}, {6000, 8000}}));
  ASSERT_TRUE(planner.nextPass(p));
  EXPECT_TRUE(p.descending);
  EXPECT_EQ(p.hy, 4);
  EXPECT_EQ(p.first, 3);
  EXPECT_EQ(p.last, 9);
  EXPECT_EQ(p.runUpUm, 1000 + 450 + 25 + 105);
  EXPECT_EQ(switchesOf(planner, 0), (std::vector<std::vector<uint32_t>>{{0, 2000}, {12800, 13200}}));
  EXPECT_FALSE(planner.nextPass(p));
}

TEST(ScanPlanner, NegativeOffsetsAndTheSpeedCap) {
  JobHeader h = smallJob(12, 4);
  const int16_t dx[4] = {0, -3, 4, -1};
  for (int k = 0; k < 4; k++) h.offsets[k][0] = dx[k];
  std::vector<std::vector<uint8_t>> rows(4, std::vector<uint8_t>(12, 0));
  for (auto& r : rows) r[5] = 255;
  GridCells cells(rows);
  ScanPlanner planner(h, cells, kMachine);
  ScanPass p;
  ASSERT_TRUE(planner.nextPass(p));
  EXPECT_EQ(p.first, 1);
  EXPECT_EQ(p.last, 8);
  const uint32_t on[4] = {8000, 14000, 0, 10000};
  for (uint8_t k = 0; k < 4; k++) EXPECT_EQ(switchesOf(planner, k), (std::vector<std::vector<uint32_t>>{{on[k], on[k] + 2000}}));

  Machine slow = kMachine;
  slow.vmaxUmS[0] = 10000;  // 5000 µs windows: full cells no longer touch
  std::vector<std::vector<uint8_t>> run(4, std::vector<uint8_t>(12, 0));
  run[0][2] = run[0][3] = 255;
  GridCells runCells(run);
  ScanPlanner capped(smallJob(12, 4), runCells, slow);
  EXPECT_EQ(capped.motion().windowUs, 5000u);
  EXPECT_EQ(capped.motion().speedUmS, 10000u);
  ASSERT_TRUE(capped.nextPass(p));
  EXPECT_EQ(switchesOf(capped, 0), (std::vector<std::vector<uint32_t>>{{1500, 3500}, {6500, 8500}}));
}

TEST(ScanPlanner, PlansAPassAtATimeWithoutTheHeap) {
  std::vector<std::vector<uint8_t>> rows(64, std::vector<uint8_t>(4096, 0));
  for (size_t y = 0; y < rows.size(); y++)
    for (size_t x = y % 7; x < 4096; x += 3) rows[y][x] = static_cast<uint8_t>(1 + (x * y) % 255);
  JobHeader h = smallJob(4096, 64);
  GridCells cells(rows);
  const long before = allocations;
  ScanPlanner planner(h, cells, kMachine);
  ScanPass p;
  int passes = 0;
  while (planner.nextPass(p)) {
    uint32_t on, off;
    for (uint8_t k = 0; k < 4; k++)
      while (planner.nextSwitch(k, on, off)) {
      }
    passes++;
  }
  EXPECT_EQ(allocations - before, 0) << "the scan planner allocated";
  EXPECT_EQ(passes, 16);
  // Each LED's row is read three times: for the first lit cell, the last, and the switch times.
  EXPECT_EQ(cells.rowsOpened, 3 * 64);
  std::printf("[scan memory] sizeof(ScanPlanner) = %zu bytes\n", sizeof(ScanPlanner));
}
