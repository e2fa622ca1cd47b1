// What the command core's files share: the room a reply needs, the work done per main-loop pass.
#pragma once
#include <stdint.h>

#include "progmem.h"

namespace mega {

// Room a command needs in its port's transmit ring before it runs: one payload line and the ok.
constexpr uint16_t kReplyRoom = 140;  // the longest payload line (112) and its ok
constexpr uint16_t kPlanStopsPerPass = 8;    // a few ms of card reads a main-loop pass
constexpr uint8_t kPrepareLinesPerPass = 4;

inline void strcpy_flash(char* out, const char* flash) { uvMemcpyP(out, flash, uvStrlenP(flash) + 1); }

}  // namespace mega
