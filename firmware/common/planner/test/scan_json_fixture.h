// Host-only: a C++ scan plan as the golden vectors write it (vectors/scan-*.json), for the tests and the golden tool.
#pragma once
#include <nlohmann/json.hpp>
#include <vector>

#include "grid_cells.h"
#include "scan.h"

namespace uvtest {

inline nlohmann::json scanPlanJson(const uv::JobHeader& h, const std::vector<std::vector<uint8_t>>& rows, const uv::MotionModel& m) {
  using nlohmann::json;
  GridCells cells(rows), cellsForEvents(rows);
  uv::ScanPlanner planner(h, cells, m);
  uv::ScanPlanner eventPlanner(h, cellsForEvents, m);  // the same passes, read as the Nano's events
  const uv::ScanMotion& motion = planner.motion();
  json passes = json::array();
  uv::ScanPass p, q;
  while (planner.nextPass(p) && eventPlanner.nextPass(q)) {
    json leds = {json::array(), json::array(), json::array(), json::array()}, jumps = json::array();
    uv::ScanEvent e;
    while (planner.next(e)) {
      if (e.jump) jumps.push_back({e.window, e.windows, e.flyUs});
      else leds[e.led].push_back({e.onUs, e.offUs});
    }
    json events = json::array();
    uint32_t t;
    uint8_t state;
    while (eventPlanner.nextEvent(t, state)) events.push_back({t, state});
    const uv::ScanMotion& own = planner.passMotion();
    passes.push_back({{"hy", p.hy}, {"descending", p.descending}, {"first", p.first}, {"last", p.last},
                      {"windowUs", own.windowUs}, {"accelUs", own.accelUs}, {"overscanUm", own.overscanUm},
                      {"runUpUm", p.runUpUm}, {"runOutUm", p.runOutUm}, {"leds", leds}, {"jumps", jumps},
                      {"events", events}, {"moveUs", p.moveUs}, {"startSteps", p.startSteps}, {"stopSteps", p.stopSteps},
                      {"strokeUs", p.strokeUs}, {"markUs", p.markUs}});
  }
  return {{"windowUs", motion.windowUs}, {"speedUmS", motion.speedUmS}, {"accelUs", motion.accelUs},
          {"overscanUm", motion.overscanUm}, {"passes", passes}, {"estimateUs", planner.estimateUs()}};
}

}  // namespace uvtest
