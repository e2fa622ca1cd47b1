// Writes protocol/vectors/planner-cpp.json (and scan-cpp.json, mixed-cpp.json): golden plans made by the C++ planners,
// for the TypeScript suite to check (npm run vectors:planner). Host tool, not firmware.
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
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

// A grid of `cols` × `rows` random cells, about `densityPercent` % of them lit at random values.
json randomGrid(Rng& r, int cols, int rows, int densityPercent) {
  json grid = json::array();
  for (int y = 0; y < rows; y++) {
    json row = json::array();
    for (int x = 0; x < cols; x++) row.push_back(r.below(100) < densityPercent ? 1 + r.below(255) : 0);
    grid.push_back(row);
  }
  return grid;
}

// A golden scan case: the job, its machine and the scan plan the C++ planner makes of it.
json scanCase(const std::string& name, const json& job, const json& machineJson, const uv::MotionModel& m) {
  uv::JobHeader h = uvtest::headerFrom(job);
  std::vector<std::vector<uint8_t>> cells;
  for (const auto& row : job["gridData"]) cells.emplace_back(row.begin(), row.end());
  return {{"name", name}, {"job", job}, {"machine", machineJson}, {"scan", uvtest::scanPlanJson(h, cells, m)}};
}

// Rows `from` to `to` − 1 of the simavr scan test's pattern (firmware/mega/src/scan_dose.h testPattern,
// 40 columns) as a job: 100 µm at 1 ms a cell, four LEDs a row apart, in one pass.
json testPatternJob(int from, int to) {
  json grid = json::array();
  for (int r = from; r < to; r++) {
    json row = json::array();
    for (int c = 0; c < 40; c++) row.push_back(r % 3 == 0 ? (c % 2 ? 255 : 0) : r % 3 == 1 ? ((c / 4) % 2 ? 255 : 0) : (c * 41 + r * 13) % 256);
    grid.push_back(row);
  }
  return {{"grid", {{"cols", 40}, {"rows", to - from}}},
          {"pitchUm", {{"x", 100}, {"y", 100}}},
          {"originUm", {{"x", 5000}, {"y", 4000}}},
          {"dose", {{"map", "linear"}, {"fullUs", 1000}}},
          {"leds", {{"offsets", {{0, 0}, {0, 1}, {0, 2}, {0, 3}}}, {"gainPermille", {1000, 1000, 1000, 1000}}}},
          {"strategy", {{"name", "serpentine"}}},
          {"gridData", grid}};
}

// Real doses: a window under a second or so (random targets make minutes).
void shortenTarget(json& job) {
  if (job["dose"].contains("targetUJcm2")) job["dose"]["targetUJcm2"] = job["dose"]["targetUJcm2"].get<int>() / 1000 + 1;
}

// How many of a scan plan's passes fly `jumps` blank stretches, of how many.
std::string passesFlying(const json& scan, size_t jumps) {
  size_t n = 0;
  for (const auto& p : scan["passes"]) n += p["jumps"].size() == jumps;
  return std::to_string(n) + " of " + std::to_string(scan["passes"].size());
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
      shortenTarget(job);
      if (n == 4) {  // full cells at uncapped speed fill their windows: runs merge
        job["dose"] = {{"map", "threshold"}, {"level", 60}, {"fullUs", 1200 + r.below(900)}};
        job["leds"]["gainPermille"] = {1000, 1000, 1000, 1000};
      }
      const bool capped = n % 2 == 1;
      cases.push_back(scanCase(std::string("c++ scan ") + gname + " #" + std::to_string(n), job,
                               capped ? slowJson : fastJson, capped ? slow : fast));
    }
  }
  // Photos in many gray levels at a speed whose program lines would outrun the printhead link: the
  // link cap lays their passes out again at longer windows (planner.md "The printhead link").
  for (const auto& [gname, offsets] : geometries) {
    json job = makeJob(r, offsets, "serpentine");
    const int cols = 40 + r.below(40), rows = 4 + r.below(6);
    job["grid"] = {{"cols", cols}, {"rows", rows}};
    job["gridData"] = randomGrid(r, cols, rows, 90);
    job["dose"] = {{"map", "linear"}, {"fullUs", 1000 + r.below(2000)}};
    job["pitchUm"]["x"] = 40 + r.below(40);
    cases.push_back(scanCase(std::string("c++ scan ") + gname + " photo, link-capped", job, fastJson, fast));
    const auto [up, upJson] = raised(fast, fastJson);  // the same photo on the raised link: capped less
    cases.push_back(scanCase(std::string("c++ scan ") + gname + " photo, link at 250000", job, upJson, up));
  }
  // The families below are drawn after those above, so those keep their draws.
  // Wide passes on the fast machine, sparse dots (long blank stretches) on the slow one. A draw the
  // plan refuses (a window too long for the step engine: no passes) is drawn again.
  const auto planned = [](const std::string& name, const json& mJson, const uv::MotionModel& m, const auto& draw) {
    json c;
    do c = scanCase(name, draw(), mJson, m);
    while (c["scan"]["passes"].empty());
    return c;
  };
  for (const auto& [gname, offsets] : geometries) {
    const auto randomSized = [&r, &offsets = offsets](int cols, int rows, int densityPercent) {
      json job = makeJob(r, offsets, "serpentine");
      shortenTarget(job);
      job["grid"] = {{"cols", cols}, {"rows", rows}};
      job["gridData"] = randomGrid(r, cols, rows, densityPercent);
      return job;
    };
    cases.push_back(planned(std::string("c++ scan ") + gname + " wide", fastJson, fast, [&] { return randomSized(70, 12, 15 + r.below(60)); }));
    cases.push_back(planned(std::string("c++ scan ") + gname + " sparse", slowJson, slow, [&] { return randomSized(60, 30, 3); }));
  }
  // More blank stretches a pass than it flies (kMaxJumps): the longest are kept, the lower column
  // first among equals. Random gaps in each geometry, then equal ones.
  // Coincident LEDs make a pass of one row, too few stretches at 2 %: their second job is 4 times as dense.
  const auto manyStretches = [&](const std::string& name, const std::vector<std::array<int, 2>>& offsets, int densityPercent) {
    json job = makeJob(r, offsets, "serpentine");
    job["grid"] = {{"cols", 400}, {"rows", 8}};
    job["gridData"] = randomGrid(r, 400, 8, densityPercent);
    job["dose"] = {{"map", "threshold"}, {"level", 100}, {"fullUs", 2000}};
    cases.push_back(scanCase("c++ scan " + name, job, fastJson, fast));
    std::printf("  %s: %s passes fly %d stretches\n", name.c_str(), passesFlying(cases.back()["scan"], uv::kMaxJumps).c_str(), uv::kMaxJumps);
  };
  for (const auto& [gname, offsets] : geometries) manyStretches(std::string(gname) + " many stretches", offsets, 2);
  manyStretches("coincident many stretches, dense", geometries[2].second, 8);
  // Eleven equal stretches a pass (rows 0 and 5 lit every 20 columns), in both directions (two passes):
  // the eight of the lowest columns are flown.
  json even = makeJob(r, geometries[0].second, "serpentine");  // adjacent LEDs
  even["grid"] = {{"cols", 241}, {"rows", 8}};
  even["gridData"] = json(8, json(std::vector<int>(241, 0)));
  even["dose"] = {{"map", "threshold"}, {"level", 100}, {"fullUs", 2000}};
  for (int y : {0, 5})
    for (int x = 3; x < 241; x += 20) even["gridData"][y][x] = 255;
  cases.push_back(scanCase("c++ scan equal stretches", even, fastJson, fast));
  std::printf("  equal stretches: %s passes fly %d stretches; first blank windows:", passesFlying(cases.back()["scan"], uv::kMaxJumps).c_str(),
              uv::kMaxJumps);
  for (const auto& p : cases.back()["scan"]["passes"]) {
    std::printf(" [");
    for (const auto& j : p["jumps"]) std::printf(" %u", j[0].get<unsigned>());
    std::printf(" ]");
  }
  std::printf("\n");
  // The simavr scan test's dense pass (testPattern's rows 8 to 11): a chain of four programs whose
  // third would come late at the window the whole chain's rule gives, so each program's own rule
  // slows it further. Then the same at 250000 baud: the Mega's 300 µs an event, not the wire, now
  // sets the window.
  uv::MotionModel simavr = fast;
  simavr.vmaxUmS[0] = simavr.vmaxUmS[1] = 100000;
  simavr.accelUmS2[0] = 2000000;
  simavr.accelUmS2[1] = 1500000;
  simavr.overheadUs = 400;
  json simavrJson = fastJson;
  simavrJson["vmaxUmS"] = {100000, 100000};
  simavrJson["accelUmS2"] = {2000000, 1500000};
  simavrJson["overheadUs"] = 400;
  const auto [simavrUp, simavrUpJson] = raised(simavr, simavrJson);
  for (const auto& [name, m, mJson] : {std::tuple{"each in time", simavr, simavrJson}, std::tuple{"link at 250000", simavrUp, simavrUpJson}}) {
    cases.push_back(scanCase(std::string("c++ scan four programs, ") + name, testPatternJob(8, 12), mJson, m));
    const json& scan = cases.back()["scan"];
    std::printf("  four programs, %s: job window %u us, pass windows", name, scan["windowUs"].get<unsigned>());
    for (const auto& p : scan["passes"]) std::printf(" %u", p["windowUs"].get<unsigned>());
    std::printf(" us\n");
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
