// The Mega's pins as the command core sees them (hw/board implements it on the CNC shield).
#pragma once
#include <stdint.h>

namespace mega {

class MachineIo {
 public:
  // bit a set while axis a's endstop is closed
  virtual uint8_t endstops() = 0;
  virtual void motorsEnabled(bool on) = 0;
  // The work light (M355) on the configured pin; false if the pin cannot be used.
  virtual bool light(uint8_t pin, bool on) = 0;
  // The panel's buttons as they read now (buttons.h bits: stop, pause/continue, home).
  virtual uint8_t buttons() = 0;
  // Bit a reverses axis a's direction pin (invert.x/y/z).
  virtual void invertDirections(uint8_t bits) = 0;
};

}  // namespace mega
