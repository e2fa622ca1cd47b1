// Writes protocol/vectors/mixed-cpp.json: golden mixed plans made by the C++ planner (planner_golden_main.cpp runs it).
#include <cstdio>
#include <fstream>
#include <string>

#include "job_json_fixture.h"
#include "mixed_json_fixture.h"
#include "planner_golden.h"

namespace uvgolden {
namespace {

// A golden mixed case: the job, its machine and the mixed plan the C++ planner makes of it.
json mixedCase(const std::string& name, const json& job, const json& machineJson, const uv::MotionModel& m) {
  return {{"name", name}, {"job", job}, {"machine", machineJson}, {"mixed", uvtest::mixedPlanJson(uvtest::headerFrom(job), cellsOf(job), m)}};
}

// A family's passes by the way taken: on the move, a pass of stops, a band of stops; and its cases
// with passes both ways (on the move and stops).
struct Ways {
  int scans = 0, stops = 0, bands = 0, bothWays = 0, cases = 0, redrawn = 0;
  void add(const json& mixed) {
    int s = 0, t = 0;
    for (const auto& p : mixed["passes"]) {
      (p["scan"].get<bool>() ? s : t)++;
      bands += p.contains("band");
    }
    scans += s;
    stops += t;
    bothWays += s > 0 && t > 0;
    cases++;
  }
  void print(const char* family) const {
    std::printf("  %s: %d cases, %d passes on the move, %d of stops (%d of them bands of stops), %d cases both ways; %d draws refused\n",
                family, cases, scans, stops, bands, bothWays, redrawn);
  }
};

// A job of `cols` × `rows` cells 85 % lit, whose every `sparseEvery`-th band of two rows keeps only
// a few cells far apart (about one in 23, on a lattice `salt` shifts).
json patchyJob(Rng& r, const std::vector<std::array<int, 2>>& offsets, int cols, int rows, int sparseEvery) {
  json job = makeJob(r, offsets, "mixed");
  shortenTarget(job);
  job["grid"] = {{"cols", cols}, {"rows", rows}};
  job["gridData"] = randomGrid(r, cols, rows, 85);
  const int salt = r.below(23);
  for (int y = 0; y < rows; y++)
    if ((y / 2) % sparseEvery == 0)
      for (int x = 0; x < cols; x++)
        if ((x * 13 + y * 5 + salt) % 23 != 0) job["gridData"][y][x] = 0;
  return job;
}

// The windows of a mixed plan's passes on the move longer than the job's (the link cap), µs: how many, and their sum.
std::pair<int, uint64_t> capped(const json& mixed) {
  std::pair<int, uint64_t> n{0, 0};
  for (const auto& p : mixed["passes"])
    if (p["scan"].get<bool>() && p["windowUs"].get<uint32_t>() > mixed["windowUs"].get<uint32_t>()) {
      n.first++;
      n.second += p["windowUs"].get<uint32_t>();
    }
  return n;
}

}  // namespace

// Mixed plans (planner.md "Mixed mode"): rows dense in places and sparse in others, on both machines,
// so the plans take both ways.
void writeMixed(const char* path, const Geometries& geometries, const uv::MotionModel& fast, const json& fastJson) {
  const auto [slow, slowJson] = slowMachine();
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
  // The families below are drawn after those above, so those keep their draws. A draw the plan
  // refuses (a window too long for the step engine: no passes) is drawn again.
  const auto planned = [&cases](Ways& ways, const std::string& name, const json& mJson, const uv::MotionModel& m, const auto& draw) {
    json c = mixedCase(name, draw(), mJson, m);
    for (; c["mixed"]["passes"].empty(); ways.redrawn++) c = mixedCase(name, draw(), mJson, m);
    ways.add(c["mixed"]);
    cases.push_back(c);
  };
  // Patchy jobs: dense rows with bands of two sparse rows among them, every second or third band,
  // on both machines; the first two at a full cell's dose.
  Ways patchy, uniform, patchyUp;
  for (const auto& [gname, geometry] : geometries) {
    const auto& offsets = geometry;  // a plain reference: the draws' lambdas capture it
    for (int n = 0; n < 4; n++) {
      planned(patchy, std::string("c++ mixed ") + gname + " patchy #" + std::to_string(n), n % 2 ? slowJson : fastJson, n % 2 ? slow : fast, [&] {
        json job = patchyJob(r, offsets, 50 + 10 * n, 10 + 3 * n, 2 + n % 2);
        if (n < 2) job["dose"] = {{"map", "threshold"}, {"level", 100}, {"fullUs", 1500 + 700 * n}};
        return job;
      });
    }
  }
  patchy.print("patchy");
  // Small random jobs, each row as dense as the others.
  for (const auto& [gname, geometry] : geometries) {
    const auto& offsets = geometry;
    planned(uniform, std::string("c++ mixed ") + gname + " random", fastJson, fast, [&] {
      json job = makeJob(r, offsets, "mixed");
      shortenTarget(job);
      return job;
    });
  }
  uniform.print("random");
  // Patchy photos (gray levels at a short window) on the raised link: at 115200 the link caps their
  // passes on the move, on the raised link less (planner.md "The printhead link"). Evidence: the same
  // jobs planned at 115200, not written.
  const auto [up, upJson] = raised(fast, fastJson);
  std::pair<int, uint64_t> cappedAt115200{0, 0}, cappedUp{0, 0};
  uint64_t estimateAt115200 = 0, estimateUp = 0;
  const auto add = [](std::pair<int, uint64_t>& sum, std::pair<int, uint64_t> n) {
    sum.first += n.first;
    sum.second += n.second;
  };
  for (const auto& [gname, geometry] : geometries) {
    const auto& offsets = geometry;
    planned(patchyUp, std::string("c++ mixed ") + gname + " patchy photo, link at 250000", upJson, up, [&] {
      json job = patchyJob(r, offsets, 60, 12, 2);
      job["dose"] = {{"map", "linear"}, {"fullUs", 800 + r.below(400)}};
      return job;
    });
    const json& c = cases.back();
    const json slowLink = uvtest::mixedPlanJson(uvtest::headerFrom(c["job"]), cellsOf(c["job"]), fast);
    add(cappedUp, capped(c["mixed"]));
    add(cappedAt115200, capped(slowLink));
    estimateUp += c["mixed"]["estimateUs"].get<uint64_t>();
    estimateAt115200 += slowLink["estimateUs"].get<uint64_t>();
  }
  patchyUp.print("patchy photo, link at 250000");
  std::printf("  patchy photo: passes on the move the link caps, at 250000 %d (windows %llu us in all), at 115200 %d (%llu us); estimates %llu us, %llu us\n",
              cappedUp.first, static_cast<unsigned long long>(cappedUp.second), cappedAt115200.first,
              static_cast<unsigned long long>(cappedAt115200.second), static_cast<unsigned long long>(estimateUp),
              static_cast<unsigned long long>(estimateAt115200));
  std::ofstream(path) << json({{"version", 1}, {"madeBy", "c++"}, {"cases", cases}}).dump() << "\n";
  std::printf("wrote %zu mixed cases\n", cases.size());
}

}  // namespace uvgolden
