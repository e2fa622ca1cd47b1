// Test-only helpers for the simavr runs of the printhead image: a booted rig, pulses on a pin,
// and a command's reply.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "nano_rig.h"
#include "scan_program.h"

namespace {

constexpr double kByteTimeUs = 1e6 * 10 / 115200;  // one byte at the real 115200 baud: 86.8 µs

inline std::unique_ptr<NanoRig> bootedRig() {
  auto rig = std::make_unique<NanoRig>(NANO_ELF);
  rig->runUs(30000);  // start-up and the first temperature sweeps
  rig->resetInterruptStats();  // the C runtime starts with interrupts off, before the UART is on
  return rig;
}

inline double us(uint64_t cycles) { return cycles / NanoRig::kCyclesPerUs; }

using Events = std::vector<std::pair<uint32_t, uint8_t>>;  // absolute µs after time 0, LED state

// The chain's lines, one program (its A lines and K line) per entry, as the Mega makes them.
inline std::vector<std::string> programs(const Events& ev) {
  struct Cursor {
    const Events& ev;
    size_t i;
  } cursor{ev, 0};
  uv::ProgramLines lines(
      [](void* ctx, uint32_t& t, uint8_t& m) {
        auto& c = *static_cast<Cursor*>(ctx);
        if (c.i == c.ev.size()) return false;
        t = c.ev[c.i].first;
        m = c.ev[c.i++].second;
        return true;
      },
      &cursor);
  std::vector<std::string> out(1);
  char line[uv::kNanoMaxLine + 2];
  while (uint8_t n = lines.next(line)) {
    out.back().append(line, n);
    if (line[0] == 'K') out.emplace_back();
  }
  out.pop_back();
  return out;
}

// Replies the Nano wrote, with the line they answered when the test asked for that.
inline std::string reply(NanoRig& rig, const std::string& cmd) {
  rig.takeLines();
  rig.send(cmd + "\n");
  std::vector<std::string> lines;
  rig.runUntil([&] {
    auto l = rig.takeLines();
    lines.insert(lines.end(), l.begin(), l.end());
    return !lines.empty();
  }, 20000);
  return lines.empty() ? "" : lines.back();
}

// High spans of one pin after `from`: (rise, fall) cycles.
inline std::vector<std::pair<uint64_t, uint64_t>> pulses(const std::vector<NanoRig::Edge>& edges, uint64_t from = 0) {
  std::vector<std::pair<uint64_t, uint64_t>> out;
  uint64_t rise = 0;
  bool high = false;
  for (const auto& e : edges) {
    if (e.cycle < from) continue;
    if (e.high && !high) rise = e.cycle;
    if (!e.high && high) out.push_back({rise, e.cycle});
    high = e.high;
  }
  return out;
}

}  // namespace
