// Writes protocol/vectors/scan-cpp.json: golden scan plans made by the C++ planner (planner_golden_main.cpp runs it).
#include <cstdio>
#include <fstream>
#include <string>
#include <tuple>

#include "job_json_fixture.h"
#include "planner_golden.h"
#include "scan.h"
#include "scan_json_fixture.h"

namespace uvgolden {
namespace {

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

// How many of a scan plan's passes fly `jumps` blank stretches, of how many.
std::string passesFlying(const json& scan, size_t jumps) {
  size_t n = 0;
  for (const auto& p : scan["passes"]) n += p["jumps"].size() == jumps;
  return std::to_string(n) + " of " + std::to_string(scan["passes"].size());
}

}  // namespace

// Scan plans (planner.md "Scan mode") of random jobs, on the same machine and on one that caps the speed.
void writeScans(const char* path, const Geometries& geometries, const uv::MotionModel& fast, const json& fastJson) {
  const auto [slow, slowJson] = slowMachine();
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

}  // namespace uvgolden
