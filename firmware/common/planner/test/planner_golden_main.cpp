// Writes protocol/vectors/planner-cpp.json (and scan-cpp.json, mixed-cpp.json): golden plans made by the C++ planners,
// for the TypeScript suite to check (npm run vectors:planner). Host tool, not firmware.
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "grid_cells.h"
#include "job_json_fixture.h"
#include "planner.h"
#include "mixed_json_fixture.h"
#include "scan_json_fixture.h"
#include "time_model.h"

using nlohmann::json;

namespace {

struct Rng {
  uint64_t x;
  explicit Rng(uint64_t seed) : x(seed * 0x9E3779B97F4A7C15ull | 1) {}
  uint32_t next() {  // splitmix64, a different generator from the TypeScript side's
    uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<uint32_t>((z ^ (z >> 31)) >> 32);
  }
  int below(int n) { return static_cast<int>(next() % static_cast<uint32_t>(n)); }
};

json makeJob(Rng& r, const std::vector<std::array<int, 2>>& offsets, const char* strategy) {
  int cols = 5 + r.below(20), rows = 5 + r.below(14);
  json grid = json::array();
  int density = 15 + r.below(60);
  for (int y = 0; y < rows; y++) {
    json row = json::array();
    for (int x = 0; x < cols; x++) row.push_back(r.below(100) < density ? 1 + r.below(255) : 0);
    grid.push_back(row);
  }
  json dose;
  switch (r.below(3)) {
    case 0: dose = {{"map", "threshold"}, {"level", 1 + r.below(128)}, {"fullUs", 1 + r.below(80000)}}; break;
    case 1: dose = {{"map", "linear"}, {"fullUs", 1 + r.below(80000)}}; break;
    default:
      dose = {{"map", "linear"}, {"targetUJcm2", 500 + r.below(300000)},
              {"irradianceUWcm2", {500 + r.below(90000), 500 + r.below(90000), 500 + r.below(90000), 500 + r.below(90000)}}};
  }
  json offs = json::array();
  for (auto o : offsets) offs.push_back({o[0], o[1]});
  return {{"grid", {{"cols", cols}, {"rows", rows}}},
          {"pitchUm", {{"x", 20 + r.below(200)}, {"y", 20 + r.below(200)}}},
          {"originUm", {{"x", r.below(30000)}, {"y", r.below(30000)}}},
          {"dose", dose},
          {"leds", {{"offsets", offs}, {"gainPermille", {700 + r.below(600), 700 + r.below(600), 700 + r.below(600), 700 + r.below(600)}}}},
          {"strategy", {{"name", strategy}, {"seed", r.next()}}},
          {"gridData", grid}};
}

// The same machine on a printhead link raised to 250000 baud (nano.md "Link speed"), as the board runs it.
std::pair<uv::MotionModel, json> raised(uv::MotionModel m, json j) {
  m.linkBaud = 250000;
  j["linkBaud"] = 250000;
  return {m, j};
}

// Scan plans (planner.md "Scan mode") of random jobs, on the same machine and on one that caps the speed.
void writeScans(const char* path, const std::vector<std::pair<const char*, std::vector<std::array<int, 2>>>>& geometries,
                const uv::MotionModel& fast, const json& fastJson) {
  const uv::MotionModel slow{{8000, 90000}, {600000, 1500000}, 1000, 900, {0, 4000}, {80000, 100000}};
  const json slowJson = {{"vmaxUmS", {8000, 90000}}, {"accelUmS2", {600000, 1500000}}, {"settleUs", 1000},
                         {"overheadUs", 900}, {"startUm", {0, 4000}}, {"stepsMilli", {80000, 100000}}, {"linkBaud", 115200}};
  Rng r(20261124);
  json cases = json::array();
  for (const auto& [gname, offsets] : geometries) {
    for (int n = 0; n < 5; n++) {
      json job = makeJob(r, offsets, "serpentine");
      // Real doses: a window under a second or so (random targets make minutes).
      if (job["dose"].contains("targetUJcm2")) job["dose"]["targetUJcm2"] = job["dose"]["targetUJcm2"].get<int>() / 1000 + 1;
      if (n == 4) {  // full cells at uncapped speed fill their windows: runs merge
        job["dose"] = {{"map", "threshold"}, {"level", 60}, {"fullUs", 1200 + r.below(900)}};
        job["leds"]["gainPermille"] = {1000, 1000, 1000, 1000};
      }
      const bool capped = n % 2 == 1;
      uv::JobHeader h = uvtest::headerFrom(job);
      std::vector<std::vector<uint8_t>> rows;
      for (const auto& row : job["gridData"]) rows.emplace_back(row.begin(), row.end());
      cases.push_back({{"name", std::string("c++ scan ") + gname + " #" + std::to_string(n)},
                       {"job", job},
                       {"machine", capped ? slowJson : fastJson},
                       {"scan", uvtest::scanPlanJson(h, rows, capped ? slow : fast)}});
    }
  }
  // Photos in many gray levels at a speed whose program lines would outrun the printhead link: the
  // link cap lays their passes out again at longer windows (planner.md "The printhead link").
  for (const auto& [gname, offsets] : geometries) {
    json job = makeJob(r, offsets, "serpentine");
    const int cols = 40 + r.below(40), rows = 4 + r.below(6);
    json grid = json::array();
    for (int y = 0; y < rows; y++) {
      json row = json::array();
      for (int x = 0; x < cols; x++) row.push_back(r.below(100) < 90 ? 1 + r.below(255) : 0);
      grid.push_back(row);
    }
    job["grid"] = {{"cols", cols}, {"rows", rows}};
    job["gridData"] = grid;
    job["dose"] = {{"map", "linear"}, {"fullUs", 1000 + r.below(2000)}};
    job["pitchUm"]["x"] = 40 + r.below(40);
    uv::JobHeader h = uvtest::headerFrom(job);
    std::vector<std::vector<uint8_t>> cells;
    for (const auto& row : job["gridData"]) cells.emplace_back(row.begin(), row.end());
    cases.push_back({{"name", std::string("c++ scan ") + gname + " photo, link-capped"},
                     {"job", job},
                     {"machine", fastJson},
                     {"scan", uvtest::scanPlanJson(h, cells, fast)}});
    const auto [up, upJson] = raised(fast, fastJson);  // the same photo on the raised link: capped less
    cases.push_back({{"name", std::string("c++ scan ") + gname + " photo, link at 250000"},
                     {"job", job},
                     {"machine", upJson},
                     {"scan", uvtest::scanPlanJson(h, cells, up)}});
  }
  std::ofstream(path) << json({{"version", 1}, {"madeBy", "c++"}, {"cases", cases}}).dump() << "\n";
  std::printf("wrote %zu scan cases\n", cases.size());
}

// Mixed plans (planner.md "Mixed mode"): rows dense in places and sparse in others, on both machines,
// so the plans take both ways.
void writeMixed(const char* path, const std::vector<std::pair<const char*, std::vector<std::array<int, 2>>>>& geometries,
                const uv::MotionModel& fast, const json& fastJson) {
  const uv::MotionModel slow{{8000, 90000}, {600000, 1500000}, 1000, 900, {0, 4000}, {80000, 100000}};
  const json slowJson = {{"vmaxUmS", {8000, 90000}}, {"accelUmS2", {600000, 1500000}}, {"settleUs", 1000},
                         {"overheadUs", 900}, {"startUm", {0, 4000}}, {"stepsMilli", {80000, 100000}}, {"linkBaud", 115200}};
  Rng r(20261127);
  json cases = json::array();
  for (const auto& [gname, offsets] : geometries) {
    for (int n = 0; n < 5; n++) {
      json job = makeJob(r, offsets, "mixed");
      const int cols = 30 + r.below(40), rows = 8 + r.below(10);
      json grid = json::array();
      for (int y = 0; y < rows; y++) {
        const bool sparse = r.below(100) < 45;
        json row = json::array();
        for (int x = 0; x < cols; x++) row.push_back(r.below(100) < (sparse ? 4 : 80) ? 1 + r.below(255) : 0);
        grid.push_back(row);
      }
      job["grid"] = {{"cols", cols}, {"rows", rows}};
      job["gridData"] = grid;
      if (job["dose"].contains("targetUJcm2")) job["dose"]["targetUJcm2"] = job["dose"]["targetUJcm2"].get<int>() / 1000 + 1;
      if (n < 2) job["dose"] = {{"map", "threshold"}, {"level", 60}, {"fullUs", 1200 + r.below(2000)}};
      const bool capped = n % 2 == 1;
      uv::JobHeader h = uvtest::headerFrom(job);
      std::vector<std::vector<uint8_t>> cells;
      for (const auto& row : job["gridData"]) cells.emplace_back(row.begin(), row.end());
      cases.push_back({{"name", std::string("c++ mixed ") + gname + " #" + std::to_string(n)},
                       {"job", job},
                       {"machine", capped ? slowJson : fastJson},
                       {"mixed", uvtest::mixedPlanJson(h, cells, capped ? slow : fast)}});
      if (n == 0) {  // dense rows at the job's window: on the raised link fewer of them are capped
        const auto [up, upJson] = raised(fast, fastJson);
        cases.push_back({{"name", std::string("c++ mixed ") + gname + " #0, link at 250000"},
                         {"job", job},
                         {"machine", upJson},
                         {"mixed", uvtest::mixedPlanJson(h, cells, up)}});
      }
    }
  }
  std::ofstream(path) << json({{"version", 1}, {"madeBy", "c++"}, {"cases", cases}}).dump() << "\n";
  std::printf("wrote %zu mixed cases\n", cases.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::fprintf(stderr, "usage: planner_golden <planner out.json> [<scan out.json> [<mixed out.json>]]\n");
    return 2;
  }
  const std::vector<std::pair<const char*, std::vector<std::array<int, 2>>>> geometries = {
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
        uv::JobHeader h = uvtest::headerFrom(job);
        std::vector<std::vector<uint8_t>> rows;
        for (const auto& row : job["gridData"]) rows.emplace_back(row.begin(), row.end());
        uvtest::GridCells cells(rows);
        uv::Planner planner(h, cells, up ? mu : m);
        uv::PlanClock clock(h, up ? mu : m);
        json stops = json::array();
        uv::Stop st;
        while (planner.next(st)) {
          clock.add(st);
          stops.push_back({st.hx, st.hy, st.us[0], st.us[1], st.us[2], st.us[3]});
        }
        cases.push_back({{"name", std::string("c++ ") + gname + " " + s + " #" + std::to_string(n) + (up ? ", link at 250000" : "")},
                         {"job", job},
                         {"machine", up ? machineUp : machine},
                         {"plan", {{"stops", stops}, {"passes", planner.passes()}, {"estimateUs", clock.totalUs()},
                                   {"travelUm", {clock.travelUm(0), clock.travelUm(1)}}}}});
      }
    }
  }
  std::ofstream(argv[1]) << json({{"version", 1}, {"madeBy", "c++"}, {"cases", cases}}).dump() << "\n";
  std::printf("wrote %zu cases\n", cases.size());
  if (argc >= 3) writeScans(argv[2], geometries, m, machine);
  if (argc == 4) writeMixed(argv[3], geometries, m, machine);
  return 0;
}
