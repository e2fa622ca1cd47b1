// The panel's buttons (the CNC shield's Abort, Hold and Resume inputs): sampled every 5 ms, a press
// counts once the pin has read pressed four samples in a row, so contact bounce never doubles it.
#pragma once
#include <stdint.h>

namespace mega {

enum Button : uint8_t { kButtonStop = 1, kButtonPause = 2, kButtonHome = 4 };

class Buttons {
 public:
  static constexpr uint32_t kSampleMs = 5;
  static constexpr uint8_t kStable = 4;

  // `pressed`: bit per button as the pins read now. Returns the buttons that became pressed.
  uint8_t sample(uint8_t pressed, uint32_t nowMs);

 private:
  uint32_t lastMs_ = 0;
  uint8_t count_[3] = {};
  uint8_t state_ = 0;
  bool started_ = false;
};

}  // namespace mega
