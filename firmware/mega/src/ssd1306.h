// The SSD1306 panel as a sequence of I2C write frames: its set-up, then for each text row an
// address frame and the row's glyphs two characters a frame. The board driver (hw/oled) sends one
// frame at a time from the TWI interrupt; this part decides what the next frame is, so a redraw
// costs the main loop one short frame build per pass and never a wait.
#pragma once
#include <stdint.h>

#include "screen.h"

namespace mega {

constexpr uint8_t kPanelAddress = 0x3c;    // 7-bit; SA0 low, as on the common modules
constexpr uint8_t kFrameGlyphs = 2;        // characters per data frame
constexpr uint8_t kFrameMax = 1 + kFrameGlyphs * 8;  // the control byte and 16 bytes
constexpr uint32_t kPanelRetryMs = 1000;   // after a panel that did not answer, try again this late

// The bytes of one I2C write after the address: a control byte (0x00 commands, 0x40 data), then
// the commands or the display data.
struct PanelFrame {
  uint8_t len;
  uint8_t bytes[kFrameMax];
};

class Ssd1306 {
 public:
  // From the top: the set-up goes first (also after a failure).
  void begin();
  // True when a row can be handed over (set up, and the last row sent).
  bool ready() const { return step_ == Step::Idle; }
  // Sends this row's text (kScreenCols characters) next. Only when ready().
  void show(uint8_t row, const char* text);
  // Builds the next frame to send; false if there is none now.
  bool next(PanelFrame& f, uint32_t nowMs);
  // The last frame was not taken (no answer, or the bus hung): set up again after kPanelRetryMs.
  void failed(uint32_t nowMs);
  // True once after a failure: whatever was drawn may be lost, so the screen redraws everything.
  bool takeLost() {
    bool l = lost_;
    lost_ = false;
    return l;
  }

 private:
  enum class Step : uint8_t { Setup, Address, Glyphs, Idle, Wait };
  Step step_ = Step::Setup;
  uint8_t index_ = 0;  // Setup: the next set-up byte; Glyphs: the next character
  uint8_t row_ = 0;
  bool lost_ = false;
  uint32_t retryAt_ = 0;
  char text_[kScreenCols];
};

}  // namespace mega
