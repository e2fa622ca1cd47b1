// The CNC shield's pins as the command core's MachineIo.
#pragma once
#include "machine_io.h"

namespace mega {

class Board : public MachineIo {
 public:
  void begin();
  uint8_t endstops() override;
  void motorsEnabled(bool on) override;
  bool light(uint8_t pin, bool on) override;
  // The buttons, debounced by the caller: bit 0 stop, 1 pause/continue, 2 home (pressed = set).
  uint8_t buttons() override;
  void invertDirections(uint8_t bits) override;
};

}  // namespace mega
