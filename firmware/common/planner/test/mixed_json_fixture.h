// Host-only: a C++ mixed plan as the golden vectors write it (vectors/mixed-*.json), for the tests and the golden tool.
#pragma once
#include <nlohmann/json.hpp>
#include <vector>

#include "grid_cells.h"
#include "scan.h"

namespace uvtest {

// Each pass's two prices and the way taken (planner.md "Mixed mode"), or a band of stops's; a scan pass's motion, jumps,
// events and stroke, a stop pass's stops. `h` must ask for the strategy `mixed`.
inline nlohmann::json mixedPlanJson(const uv::JobHeader& h, const std::vector<std::vector<uint8_t>>& rows, const uv::MotionModel& m) {
  using nlohmann::json;
  GridCells cells(rows);
  uv::ScanPlanner planner(h, cells, m);
  json passes = json::array();
  uv::ScanPass p;
  uint32_t steps = 0;  // the Mega's progress count: one a scan pass, one a stop
  while (planner.nextPass(p)) {
    steps += p.stops ? 0 : 1;
    json pass = {{"hy", p.hy}, {"descending", p.descending}, {"first", p.first}, {"last", p.last},
                 {"scanUs", p.scanUs}, {"stopsUs", p.stopsUs}, {"scan", !p.stops}};
    if (p.band) pass["band"] = p.band;  // a band of stops (planner.md "Bands")
    if (p.stops) {
      json stops = json::array();
      uv::Stop s;
      while (planner.nextStop(s)) stops.push_back({s.hx, s.hy, s.us[0], s.us[1], s.us[2], s.us[3]});
      steps += static_cast<uint32_t>(stops.size());
      pass["stops"] = stops;
    } else {
      json jumps = json::array(), events = json::array();
      for (uint8_t i = 0; i < planner.jumps(); i++) {
        uint32_t window, windows, flyUs;
        planner.jump(i, window, windows, flyUs);
        jumps.push_back({window, windows, flyUs});
      }
      uint32_t t;
      uint8_t state;
      while (planner.nextEvent(t, state)) events.push_back({t, state});
      pass["windowUs"] = planner.passMotion().windowUs;
      pass["jumps"] = jumps;
      pass["events"] = events;
      pass["moveUs"] = p.moveUs;
      pass["startSteps"] = p.startSteps;
      pass["stopSteps"] = p.stopSteps;
      pass["strokeUs"] = p.strokeUs;
      pass["markUs"] = p.markUs;
    }
    passes.push_back(pass);
  }
  return {{"windowUs", planner.motion().windowUs}, {"passes", passes}, {"steps", steps}, {"estimateUs", planner.estimateUs()}};
}

}  // namespace uvtest
