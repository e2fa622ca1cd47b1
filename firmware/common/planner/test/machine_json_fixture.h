// Host-only: the planner's machine as the golden vectors write it (vectors/planner-*.json, scan-*.json).
#pragma once
#include <nlohmann/json.hpp>

#include "time_model.h"

namespace uvtest {

inline uv::MotionModel machineFrom(const nlohmann::json& m) {
  uv::MotionModel out{};
  for (int a = 0; a < 2; a++) {
    out.vmaxUmS[a] = m["vmaxUmS"][a];
    out.accelUmS2[a] = m["accelUmS2"][a];
    out.startUm[a] = m["startUm"][a];
    out.stepsMilli[a] = m["stepsMilli"][a];
  }
  out.settleUs = m["settleUs"];
  out.overheadUs = m["overheadUs"];
  out.linkBaud = m["linkBaud"];
  return out;
}

}  // namespace uvtest
