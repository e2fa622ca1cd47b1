// The golden writer's shared pieces (planner_golden_*.cpp): its random source, random jobs and machines.
#pragma once
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "time_model.h"

namespace uvgolden {

using nlohmann::json;
using Geometries = std::vector<std::pair<const char*, std::vector<std::array<int, 2>>>>;

struct Rng {
  uint64_t x;
  explicit Rng(uint64_t seed) : x(seed * 0x9E3779B97F4A7C15ull | 1) {}
  uint32_t next() {  // splitmix64
    uint64_t z = (x += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return static_cast<uint32_t>((z ^ (z >> 31)) >> 32);
  }
  int below(int n) { return static_cast<int>(next() % static_cast<uint32_t>(n)); }
};

inline json makeJob(Rng& r, const std::vector<std::array<int, 2>>& offsets, const char* strategy) {
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
inline std::pair<uv::MotionModel, json> raised(uv::MotionModel m, json j) {
  m.linkBaud = 250000;
  j["linkBaud"] = 250000;
  return {m, j};
}

// A machine that caps the scan's speed, for the scan and mixed vectors.
inline std::pair<uv::MotionModel, json> slowMachine() {
  const uv::MotionModel slow{{8000, 90000}, {600000, 1500000}, 1000, 900, {0, 4000}, {80000, 100000}};
  const json slowJson = {{"vmaxUmS", {8000, 90000}}, {"accelUmS2", {600000, 1500000}}, {"settleUs", 1000},
                         {"overheadUs", 900}, {"startUm", {0, 4000}}, {"stepsMilli", {80000, 100000}}, {"linkBaud", 115200}};
  return {slow, slowJson};
}

// A grid of `cols` × `rows` random cells, about `densityPercent` % of them lit at random values.
inline json randomGrid(Rng& r, int cols, int rows, int densityPercent) {
  json grid = json::array();
  for (int y = 0; y < rows; y++) {
    json row = json::array();
    for (int x = 0; x < cols; x++) row.push_back(r.below(100) < densityPercent ? 1 + r.below(255) : 0);
    grid.push_back(row);
  }
  return grid;
}

// Real doses: a window under a second or so (random targets make minutes).
inline void shortenTarget(json& job) {
  if (job["dose"].contains("targetUJcm2")) job["dose"]["targetUJcm2"] = job["dose"]["targetUJcm2"].get<int>() / 1000 + 1;
}

// The job's grid as rows of cells.
inline std::vector<std::vector<uint8_t>> cellsOf(const json& job) {
  std::vector<std::vector<uint8_t>> cells;
  for (const auto& row : job["gridData"]) cells.emplace_back(row.begin(), row.end());
  return cells;
}

// planner_golden_scan.cpp, planner_golden_mixed.cpp.
void writeScans(const char* path, const Geometries& geometries, const uv::MotionModel& fast, const json& fastJson);
void writeMixed(const char* path, const Geometries& geometries, const uv::MotionModel& fast, const json& fastJson);

}  // namespace uvgolden
