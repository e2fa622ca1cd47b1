// Host tests of the C++ planner: its golden plans, exactness on random jobs,
// and the RAM bound with no heap use.
#include "planner.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include "grid_cells.h"
#include "job_json_fixture.h"
#include "machine_json_fixture.h"
#include "mesh.h"
#include "time_model.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace uvtest {
// Heap allocations so far: scan_test.cpp counts them too.
std::atomic<long> allocations{0};
}  // namespace uvtest

namespace {

// The random jobs' source: xorshift32, a number below n each call.
struct Xorshift {
  uint32_t seed;
  uint32_t operator()(uint32_t n) {
    seed ^= seed << 13;
    seed ^= seed >> 17;
    seed ^= seed << 5;
    return seed % n;
  }
};
}  // namespace

void* operator new(size_t n) {
  allocations++;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }

namespace {

struct Planned {
  std::vector<std::vector<int64_t>> stops;
  uint16_t passes;
  uint64_t estimate;
  uint64_t travel[2];
};

std::vector<std::vector<uint8_t>> gridFrom(const json& job) {
  std::vector<std::vector<uint8_t>> rows;
  for (const auto& r : job["gridData"]) rows.emplace_back(r.begin(), r.end());
  return rows;
}

Planned planOf(const JobHeader& h, const std::vector<std::vector<uint8_t>>& rows, const MotionModel& m) {
  GridCells cells(rows);
  Planner planner(h, cells, m);
  PlanClock clock(h, m);
  Planned out{};
  Stop s;
  while (planner.next(s)) {
    clock.add(s);
    out.stops.push_back({s.hx, s.hy, s.us[0], s.us[1], s.us[2], s.us[3]});
  }
  out.passes = planner.passes();
  out.estimate = clock.totalUs();
  out.travel[0] = clock.travelUm(0);
  out.travel[1] = clock.travelUm(1);
  return out;
}

void checkGolden(const char* file) {
  const json v = loadVectors(file);
  ASSERT_GT(v["cases"].size(), 20u) << file;
  for (const json& c : v["cases"]) {
    JobHeader h = headerFrom(c["job"]);
    auto rows = gridFrom(c["job"]);
    Planned p = planOf(h, rows, machineFrom(c["machine"]));
    EXPECT_EQ(json(p.stops), c["plan"]["stops"]) << c["name"];
    EXPECT_EQ(p.passes, c["plan"]["passes"].get<int>()) << c["name"];
    EXPECT_EQ(p.estimate, c["plan"]["estimateUs"].get<uint64_t>()) << c["name"];
    EXPECT_EQ(json({p.travel[0], p.travel[1]}), c["plan"]["travelUm"]) << c["name"];
  }
  std::printf("[vectors] %s: %zu plans checked (C++)\n", file, v["cases"].size());
}

}  // namespace

TEST(PlannerGolden, ReproducesItsOwnPlans) { checkGolden("planner-cpp.json"); }

TEST(PlannerMemory, StreamsWithinItsBoundAndNeverAllocates) {
  // A 4096-column job fed one row at a time through the cursors: the planner's state is the
  // same at any size, and planning allocates nothing.
  std::vector<std::vector<uint8_t>> rows(64, std::vector<uint8_t>(4096, 0));
  for (size_t y = 0; y < rows.size(); y++)
    for (size_t x = y % 7; x < 4096; x += 3) rows[y][x] = static_cast<uint8_t>(1 + (x * y) % 255);
  JobHeader h{};
  h.cols = 4096;
  h.rows = 64;
  h.pitchUm[0] = h.pitchUm[1] = 50;
  h.map = DoseMap::Linear;
  h.fullUs = 5000;
  for (int k = 0; k < 4; k++) {
    h.gainPermille[k] = 1000;
    h.offsets[k][1] = static_cast<int16_t>(k * 16);  // bands
  }
  for (Strategy s : {Strategy::Raster, Strategy::Serpentine, Strategy::Shortest, Strategy::Random}) {
    h.strategy = s;
    GridCells cells(rows);
    const MotionModel m{{100000, 100000}, {2000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};
    long before = allocations;
    Planner planner(h, cells, m);
    Stop stop;
    long stops = 0;
    while (planner.next(stop)) stops++;
    EXPECT_EQ(allocations - before, 0) << "the planner allocated";
    EXPECT_GT(stops, 4096 * 16 / 3);
    // Each row is read once by one cursor; `shortest` reads a band up to three times (two
    // pricings and the chosen order), still without holding any of it.
    EXPECT_EQ(cells.rowsOpened, s == Strategy::Shortest ? 3 * 64 : 64);
  }
  // The host's duration table (Durations::kTableBytes) is not on the Mega, which the bound is for.
  EXPECT_LE(sizeof(Planner) - Durations::kTableBytes, kPlannerMaxBytes);
  std::printf("[planner memory] sizeof(Planner) = %zu bytes without the host's duration table (bound %u), no heap\n", sizeof(Planner) - Durations::kTableBytes, kPlannerMaxBytes);
}

// A cell's duration, round(full × gain × m / 255000), worked out without a 64-bit division (the
// Mega's speed): against the exact quotient over every value, for durations by time and by target
// across the ranges the job's header takes (job_verifier.cpp), modulo 2³² where a target over a faint
// LED needs more.
TEST(Durations, EveryValueIsTheExactRoundedQuotient) {
  Xorshift rng{0x39u};
  for (int job = 0; job < 400; job++) {
    JobHeader h{};
    h.map = DoseMap::Linear;
    h.byTarget = job % 2;
    h.fullUs = 1 + rng(10000000);
    h.targetUJcm2 = 1 + rng(100000000);
    for (uint8_t k = 0; k < 4; k++) {
      h.irradianceUWcm2[k] = 1 + rng(10000000);
      h.gainPermille[k] = static_cast<uint16_t>(1 + rng(10000));
    }
    const Durations dose(h);
    for (uint8_t k = 0; k < 4; k++) {
      const unsigned __int128 full = h.byTarget ? (static_cast<unsigned __int128>(h.targetUJcm2) * 1000000u * 2 + h.irradianceUWcm2[k]) / (2ull * h.irradianceUWcm2[k]) : h.fullUs;
      for (uint16_t v = 0; v < 256; v++) {
        const unsigned __int128 exact = (full * h.gainPermille[k] * v * 2 + 255000) / 510000;
        ASSERT_EQ(dose.us(k, static_cast<uint8_t>(v)), static_cast<uint32_t>(exact)) << "job " << job << " led " << int(k) << " value " << v;
      }
    }
  }
}

TEST(PlannerProperty, EveryLitCellOnceWithLedsSpreadOverManyRows) {
  // Rows marked as taken live in a ring of kCoveredWindowRows: jobs taller than it, with the LEDs'
  // rows spread up to its limit, still expose each lit cell exactly once and nothing else.
  Xorshift rnd{12345};
  for (int trial = 0; trial < 24; trial++) {
    uint16_t rows = static_cast<uint16_t>(1500 + rnd(2000)), cols = static_cast<uint16_t>(3 + rnd(9));
    std::vector<std::vector<uint8_t>> grid(rows, std::vector<uint8_t>(cols, 0));
    for (auto& row : grid)
      for (auto& v : row)
        if (rnd(3) == 0) v = static_cast<uint8_t>(1 + rnd(255));
    JobHeader h{};
    h.cols = cols;
    h.rows = rows;
    h.pitchUm[0] = h.pitchUm[1] = 50;
    h.map = DoseMap::Threshold;
    h.level = 1;
    h.fullUs = 1000;
    h.strategy = static_cast<Strategy>(trial % 4);
    h.seed = static_cast<uint32_t>(trial);
    uint16_t spread = trial % 3 == 0 ? static_cast<uint16_t>(kCoveredWindowRows - 1) : static_cast<uint16_t>(rnd(kCoveredWindowRows));
    for (int k = 0; k < 4; k++) {
      h.gainPermille[k] = 1000;
      h.offsets[k][0] = static_cast<int16_t>(rnd(3));
      h.offsets[k][1] = static_cast<int16_t>(k == 3 ? spread : rnd(spread + 1u));
    }
    GridCells cells(grid);
    const MotionModel m{{100000, 100000}, {2000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};
    Planner planner(h, cells, m);
    ASSERT_TRUE(planner.supported());
    std::vector<std::vector<int>> exposed(rows, std::vector<int>(cols, 0));
    Stop s;
    while (planner.next(s)) {
      for (int k = 0; k < 4; k++) {
        if (!s.us[k]) continue;
        int r = s.hy + h.offsets[k][1], c = s.hx + h.offsets[k][0];
        ASSERT_TRUE(r >= 0 && r < rows && c >= 0 && c < cols) << "trial " << trial;
        exposed[r][c]++;
      }
    }
    for (int r = 0; r < rows; r++)
      for (int c = 0; c < cols; c++) ASSERT_EQ(exposed[r][c], grid[r][c] ? 1 : 0) << "trial " << trial << " cell " << r << "," << c;
  }
  JobHeader wide{};
  wide.offsets[3][1] = static_cast<int16_t>(kCoveredWindowRows);
  std::vector<std::vector<uint8_t>> one(1, std::vector<uint8_t>(1, 1));
  GridCells cells(one);
  const MotionModel m{{100000, 100000}, {2000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};
  Planner planner(wide, cells, m);
  EXPECT_FALSE(planner.supported());
  Stop s;
  EXPECT_FALSE(planner.next(s));
}

TEST(PlannerStreaming, RowsArrivingOneByOneGiveTheWholePlanInOrderAndNothingEarly) {
  // planner.md "Planning while rows arrive": fed one more row at a time, the planner emits only
  // stops no later row can change, and in the end exactly the plan of the whole job.
  Xorshift rnd{777};
  for (int trial = 0; trial < 60; trial++) {
    uint16_t rows = static_cast<uint16_t>(1 + rnd(60)), cols = static_cast<uint16_t>(1 + rnd(12));
    std::vector<std::vector<uint8_t>> grid(rows, std::vector<uint8_t>(cols, 0));
    for (auto& row : grid)
      for (auto& v : row)
        if (rnd(4) == 0) v = static_cast<uint8_t>(1 + rnd(255));
    JobHeader h{};
    h.cols = cols;
    h.rows = rows;
    h.pitchUm[0] = h.pitchUm[1] = 50;
    h.map = DoseMap::Linear;
    h.fullUs = 1000;
    h.strategy = static_cast<Strategy>(trial % 4);
    h.seed = static_cast<uint32_t>(trial + 1);
    for (int k = 0; k < 4; k++) {
      h.gainPermille[k] = 1000;
      h.offsets[k][0] = static_cast<int16_t>(rnd(3)) - 1;
      h.offsets[k][1] = static_cast<int16_t>(trial % 5 == 0 ? rnd(9) : k);
    }
    const MotionModel m{{100000, 100000}, {2000000, 2000000}, 2000, 1500, {0, 0}, {80000, 80000}};
    GridCells all(grid);
    Planner whole(h, all, m);
    std::vector<Stop> expected;
    Stop s;
    while (whole.next(s)) expected.push_back(s);

    // The rows not yet arrived read as empty, as a stream's buffer shows them.
    std::vector<std::vector<uint8_t>> arrived(rows, std::vector<uint8_t>(cols, 0));
    GridCells partial(arrived);
    Planner streaming(h, partial, m);
    std::vector<Stop> got;
    for (uint16_t known = 0; known <= rows; known++) {
      if (known) arrived[known - 1] = grid[known - 1];
      streaming.setKnownRows(known);
      while (streaming.next(s)) {
        for (int k = 0; k < 4; k++) {
          if (s.us[k]) {
            ASSERT_LT(s.hy + h.offsets[k][1], known) << "trial " << trial << ": a stop before its row arrived";
          }
        }
        got.push_back(s);
      }
      ASSERT_EQ(streaming.starved(), known < rows) << "trial " << trial << " known " << known;
    }
    ASSERT_EQ(got.size(), expected.size()) << "trial " << trial;
    for (size_t i = 0; i < got.size(); i++) {
      ASSERT_EQ(got[i].hx, expected[i].hx) << "trial " << trial << " stop " << i;
      ASSERT_EQ(got[i].hy, expected[i].hy) << "trial " << trial << " stop " << i;
      for (int k = 0; k < 4; k++) ASSERT_EQ(got[i].us[k], expected[i].us[k]) << "trial " << trial << " stop " << i;
    }
  }
}

TEST(TimeModel, TrapezoidAndTriangle) {
  EXPECT_EQ(moveTimeUs(0, 150000, 3000000), 0u);
  EXPECT_EQ(moveTimeUs(100, 150000, 3000000), 2u * 5773u);
  EXPECT_EQ(moveTimeUs(100000, 150000, 3000000), 666667u + 50000u);
  EXPECT_EQ(isqrt64(0), 0u);
  EXPECT_EQ(isqrt64(99), 9u);
  EXPECT_EQ(isqrt64(100), 10u);
  EXPECT_EQ(isqrt64(1000000000000000000ull), 1000000000u);
  // Every size of n, on and either side of squares, and at the top of the range.
  auto check = [](uint64_t n) {
    const unsigned __int128 r = isqrt64(n);
    ASSERT_LE(r * r, n) << n;
    ASSERT_GT((r + 1) * (r + 1), n) << n;
  };
  uint64_t seed = 12345;
  for (int bits = 1; bits <= 64; bits++)
    for (int i = 0; i < 200; i++) {
      seed ^= seed << 13, seed ^= seed >> 7, seed ^= seed << 17;
      const uint64_t n = bits == 64 ? seed : seed & ((1ull << bits) - 1);
      check(n);
      const uint64_t r = isqrt64(n);
      check(r * r);
      if (r) check(r * r - 1);
    }
  check(UINT64_MAX);
  check(0xfffffffe00000001ull);  // (2³² − 1)²
}

TEST(MeshVectors, BilinearZ) {
  const json v = loadVectors("mesh.json");
  VectorCounter counted("mesh.json");
  for (const json& c : v["cases"]) {
    Mesh m{};
    m.nx = c["mesh"]["nx"];
    m.ny = c["mesh"]["ny"];
    m.x0 = c["mesh"]["x0"];
    m.y0 = c["mesh"]["y0"];
    m.dx = c["mesh"]["dx"];
    m.dy = c["mesh"]["dy"];
    for (int j = 0; j < m.ny; j++)
      for (int i = 0; i < m.nx; i++) m.z[j][i] = c["mesh"]["z"][j][i];
    for (const json& q : c["points"]) {
      EXPECT_EQ(meshZ(m, q[0], q[1]), q[2].get<int>()) << c["name"] << " at " << q;
      counted();
    }
  }
}
