// Plans one F command: which LEDs go on together and the order, in timer ticks, in which they go off.
#include "fire_plan.h"

namespace nano {

FireVerdict planFire(const uv::NanoCommand& cmd, uint32_t capUs, FirePlan& out) {
  out.onMask = 0;
  out.count = 0;
  for (uint8_t i = 0; i < uv::kLedCount; i++) {
    if (!(cmd.mask >> i & 1) || cmd.durations[i] == 0) continue;
    if (cmd.durations[i] > capUs) return FireVerdict::Capped;
    out.onMask |= static_cast<uint8_t>(1u << i);
  }
  if (!out.onMask) return FireVerdict::Nothing;
  for (uint8_t i = 0; i < uv::kLedCount; i++) {
    if (!(out.onMask >> i & 1)) continue;
    uint32_t tick = cmd.durations[i] * kTicksPerUs;
    uint8_t at = 0;
    while (at < out.count && out.events[at].tick < tick) at++;
    if (at < out.count && out.events[at].tick == tick) {
      out.events[at].mask |= static_cast<uint8_t>(1u << i);
      continue;
    }
    for (uint8_t k = out.count; k > at; k--) out.events[k] = out.events[k - 1];
    out.events[at] = {tick, static_cast<uint8_t>(1u << i)};
    out.count++;
  }
  return FireVerdict::Fire;
}

}  // namespace nano
