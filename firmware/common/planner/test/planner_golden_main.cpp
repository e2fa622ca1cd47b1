// Host tool (npm run vectors:planner): writes golden plans of the C++ planners, stop plans to planner-cpp.json, then scan and mixed.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "grid_cells.h"
#include "job_json_fixture.h"
#include "planner.h"
#include "planner_golden.h"
#include "time_model.h"

using namespace uvgolden;

namespace {

// A golden stop case: the job, its machine and the stops, passes, estimate and travel of the C++ planner's plan.
json stopCase(const std::string& name, const json& job, const json& machineJson, const uv::MotionModel& m) {
  uv::JobHeader h = uvtest::headerFrom(job);
  const auto rows = cellsOf(job);
  uvtest::GridCells cells(rows);  // reads the rows in place
  uv::Planner planner(h, cells, m);
  uv::PlanClock clock(h, m);
  json stops = json::array();
  uv::Stop st;
  while (planner.next(st)) {
    clock.add(st);
    stops.push_back({st.hx, st.hy, st.us[0], st.us[1], st.us[2], st.us[3]});
  }
  return {{"name", name},
          {"job", job},
          {"machine", machineJson},
          {"plan", {{"stops", stops}, {"passes", planner.passes()}, {"estimateUs", clock.totalUs()},
                    {"travelUm", {clock.travelUm(0), clock.travelUm(1)}}}}};
}

// A plan's stops as runs of one head row: its passes, when it takes them one after another.
std::vector<std::vector<json>> runsOf(const json& stops) {
  std::vector<std::vector<json>> runs;
  for (const auto& s : stops) {
    if (runs.empty() || runs.back().back()[1] != s[1]) runs.emplace_back();
    runs.back().push_back(s);
  }
  return runs;
}

// The stops' head columns rise (step > 0) or fall (step < 0) from one to the next, or stay.
bool monotonic(const std::vector<json>& stops, int step) {
  for (size_t i = 1; i < stops.size(); i++)
    if ((stops[i][0].get<int>() - stops[i - 1][0].get<int>()) * step < 0) return false;
  return true;
}

// The head rows of the passes the stop planner opens (Planner::openPass), in order: a row with a
// lit cell not yet covered opens one, which covers its LEDs' rows.
std::vector<int> passRows(const json& job) {
  const int rows = job["grid"]["rows"].get<int>();
  std::vector<int> dy;
  for (const auto& o : job["leds"]["offsets"]) dy.push_back(o[1].get<int>());
  const int dyMin = *std::min_element(dy.begin(), dy.end());
  std::vector<bool> covered(rows, false);
  std::vector<int> hys;
  for (int r = 0; r < rows; r++) {
    const auto& row = job["gridData"][r];
    if (covered[r] || std::all_of(row.begin(), row.end(), [](const json& v) { return v.get<int>() == 0; })) continue;
    const int hy = r - dyMin;
    for (int d : dy)
      if (hy + d >= 0 && hy + d < rows) covered[hy + d] = true;
    hys.push_back(hy);
  }
  return hys;
}

// `shortest`'s bands of kShortestBand passes in a plan, by the order their stops show: column by
// column (the head columns one way through the band, its rows visited again) or pass by pass (each
// row's stops together, the columns not one way). A band that shows neither could be either.
void shortestOrders(const json& job, const json& stops, int& columns, int& rows, int& either) {
  const std::vector<int> hys = passRows(job);
  size_t at = 0;
  for (size_t b = 0; b < hys.size(); b += uv::kShortestBand) {
    const std::set<int> band(hys.begin() + b, hys.begin() + std::min(hys.size(), b + uv::kShortestBand));
    std::vector<json> own;
    while (at < stops.size() && band.count(stops[at][1].get<int>())) own.push_back(stops[at++]);
    if (own.empty()) continue;
    std::set<int> seen;
    bool revisits = false;
    for (size_t i = 0; i < own.size(); i++) {
      const int hy = own[i][1].get<int>();
      if (i > 0 && hy != own[i - 1][1].get<int>() && seen.count(hy)) revisits = true;
      seen.insert(hy);
    }
    const bool oneWay = monotonic(own, 1) || monotonic(own, -1);
    if (!oneWay && revisits) std::printf("  !! a band in neither order\n");
    (oneWay && revisits ? columns : !oneWay && !revisits ? rows : either)++;
  }
  if (at != stops.size()) std::printf("  !! %zu stops outside the bands found\n", stops.size() - at);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::fprintf(stderr, "usage: planner_golden <planner out.json> [<scan out.json> [<mixed out.json>]]\n");
    return 2;
  }
  const Geometries geometries = {
      {"adjacent", {{{0, 0}}, {{0, 1}}, {{0, 2}}, {{0, 3}}}},
      {"bands", {{{0, 0}}, {{0, 4}}, {{0, 8}}, {{0, 12}}}},
      {"coincident", {{{1, 1}}, {{1, 1}}, {{1, 1}}, {{1, 1}}}},
      {"staggered", {{{0, 0}}, {{1, 2}}, {{-2, 5}}, {{0, -1}}}},
  };
  const json machine = {{"vmaxUmS", {120000, 90000}}, {"accelUmS2", {2500000, 1500000}}, {"settleUs", 3000},
                        {"overheadUs", 1200}, {"startUm", {5000, 0}}, {"stepsMilli", {80000, 80000}}, {"linkBaud", 115200}};
  uv::MotionModel m{{120000, 90000}, {2500000, 1500000}, 3000, 1200, {5000, 0}, {80000, 80000}};
  Rng r(20261121);
  json cases = json::array();
  for (const auto& [gname, offsets] : geometries) {
    for (const char* s : {"raster", "serpentine", "shortest", "random"}) {
      for (int n = 0; n < 3; n++) {
        // The third of each is on the raised link (its F lines shorter): the first two are as before.
        const bool up = n == 2;
        const auto [mu, machineUp] = raised(m, machine);
        json job = makeJob(r, offsets, s);
        cases.push_back(stopCase(std::string("c++ ") + gname + " " + s + " #" + std::to_string(n) + (up ? ", link at 250000" : ""), job,
                                 up ? machineUp : machine, up ? mu : m));
      }
    }
  }
  // The families below are drawn after those above, so those keep their draws.
  // Wide passes (75 x 9, adjacent LEDs): `random` shuffles several kRandomBlock-stop blocks, `shortest`
  // turns around.
  for (const char* s : {"raster", "serpentine", "shortest", "random"}) {
    json job = makeJob(r, geometries[0].second, s);
    job["grid"] = {{"cols", 75}, {"rows", 9}};
    job["gridData"] = randomGrid(r, 75, 9, 20 + r.below(60));
    cases.push_back(stopCase(std::string("c++ wide ") + s, job, machine, m));
    const auto runs = runsOf(cases.back()["plan"]["stops"]);
    const auto falls = [](const std::vector<json>& run) { return run.front()[0].get<int>() > run.back()[0].get<int>(); };
    int up = 0, down = 0, turns = 0, blocks = 0, shuffled = 0;
    for (size_t i = 0; i < runs.size(); i++) {
      (falls(runs[i]) ? down : up)++;
      if (i > 0 && falls(runs[i]) != falls(runs[i - 1])) turns++;
      for (size_t b = 0; b < runs[i].size(); b += uv::kRandomBlock, blocks++) {
        const std::vector<json> block(runs[i].begin() + b, runs[i].begin() + std::min(runs[i].size(), b + uv::kRandomBlock));
        shuffled += !monotonic(block, 1) && !monotonic(block, -1);
      }
    }
    std::printf("  wide %s: %zu stops in %zu passes, %d rising and %d falling (%d turns); %d of its %d %d-stop blocks shuffled\n", s,
                cases.back()["plan"]["stops"].size(), runs.size(), up, down, turns, shuffled, blocks, uv::kRandomBlock);
    if (std::string(s) == "shortest") {
      int columns = 0, rows = 0, either = 0;
      shortestOrders(job, cases.back()["plan"]["stops"], columns, rows, either);
      std::printf("  wide shortest: bands column by column %d, pass by pass %d, could be either %d\n", columns, rows, either);
    }
  }
  // Sparse dots (90 x 70, 2 %) over several bands: `shortest` takes the column order in some bands, rows
  // in others. A draw whose plan shows only one order is drawn again.
  for (const auto& [gname, offsets] : geometries) {
    int columns = 0, rows = 0, either = 0, draws = 0;
    json c;
    do {
      json job = makeJob(r, offsets, "shortest");
      job["grid"] = {{"cols", 90}, {"rows", 70}};
      job["gridData"] = randomGrid(r, 90, 70, 2);
      c = stopCase(std::string("c++ sparse shortest ") + gname, job, machine, m);
      columns = rows = either = 0;
      shortestOrders(job, c["plan"]["stops"], columns, rows, either);
      draws++;
    } while (columns == 0 || rows == 0);
    cases.push_back(c);
    std::printf("  sparse shortest %s: %zu stops; bands column by column %d, pass by pass %d, could be either %d (draw %d)\n", gname,
                c["plan"]["stops"].size(), columns, rows, either, draws);
  }
  std::ofstream(argv[1]) << json({{"version", 1}, {"madeBy", "c++"}, {"cases", cases}}).dump() << "\n";
  std::printf("wrote %zu cases\n", cases.size());
  if (argc >= 3) writeScans(argv[2], geometries, m, machine);
  if (argc == 4) writeMixed(argv[3], geometries, m, machine);
  return 0;
}
