// CR Touch trigger on D7: its level, plus any short trigger pulse latched by a pin-change interrupt.
#pragma once

namespace nano {
namespace probe_input {

void begin();
// High now, or went high since the last call; clears the latch.
bool takeTriggered();

}  // namespace probe_input
}  // namespace nano
