// Test-only: a POST /print-shaped JSON job (protocol/esp.md) to a JobHeader, with esp.md's defaults.
#pragma once
#include <nlohmann/json.hpp>

#include "job_types.h"

namespace uvtest {

inline uv::JobHeader headerFrom(const nlohmann::json& j) {
  uv::JobHeader h{};
  h.cols = j["grid"]["cols"];
  h.rows = j["grid"]["rows"];
  h.pitchUm[0] = j["pitchUm"]["x"];
  h.pitchUm[1] = j["pitchUm"]["y"];
  h.originUm[0] = j["originUm"]["x"];
  h.originUm[1] = j["originUm"]["y"];
  const nlohmann::json& d = j["dose"];
  h.map = d["map"] == "linear" ? uv::DoseMap::Linear : uv::DoseMap::Threshold;
  h.level = d.value("level", 0);
  h.byTarget = d.contains("targetUJcm2");
  h.fullUs = d.value("fullUs", 0u);
  h.targetUJcm2 = d.value("targetUJcm2", 0u);
  for (int i = 0; i < 4; i++) {
    if (h.byTarget) h.irradianceUWcm2[i] = d["irradianceUWcm2"][i];
    h.gainPermille[i] = j["leds"].contains("gainPermille") ? j["leds"]["gainPermille"][i].get<int>() : 1000;
    h.offsets[i][0] = j["leds"]["offsets"][i][0];
    h.offsets[i][1] = j["leds"]["offsets"][i][1];
  }
  h.thermalCoeff = j.contains("thermal") ? j["thermal"]["coeffCentiPctPerC"].get<int>() : 0;
  h.thermalRefDeciC = j.contains("thermal") ? j["thermal"]["refDeciC"].get<int>() : 250;
  static const char* const names[] = {"raster", "serpentine", "shortest", "random", "scan", "mixed"};
  static_assert(sizeof(names) / sizeof(names[0]) == uv::kStrategyCount, "a name for every strategy");
  for (int i = 0; i < uv::kStrategyCount; i++)
    if (j["strategy"]["name"] == names[i]) h.strategy = static_cast<uv::Strategy>(i);
  h.seed = h.strategy == uv::Strategy::Random ? j["strategy"].value("seed", 0u) : 0;
  return h;
}

}  // namespace uvtest
