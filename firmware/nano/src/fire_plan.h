// Plans one F command: which LEDs go on together and the order, in timer ticks, in which they go off.
#pragma once
#include <stdint.h>

#include "nano_codec.h"

namespace nano {

// Timer1 runs at the CPU clock: 16 ticks per µs.
constexpr uint32_t kTicksPerUs = 16;

struct OffEvent {
  uint32_t tick;  // after the on-edge
  uint8_t mask;   // LEDs (bits 0-3) that go off together at this tick
};

struct FirePlan {
  uint8_t onMask;
  uint8_t count;  // events, ascending by tick, at most one per distinct duration
  OffEvent events[uv::kLedCount];
};

enum class FireVerdict : uint8_t { Fire, Nothing, Capped };

// Nothing: no LED in the mask has a non-zero duration. Capped: a lit duration is over capUs.
FireVerdict planFire(const uv::NanoCommand& cmd, uint32_t capUs, FirePlan& out);

}  // namespace nano
