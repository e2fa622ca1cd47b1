// What the SSD1306 shows (128 x 64 as 8 rows of 16 characters): state, position, job progress,
// temperatures and the last fault or message. Composed from a snapshot of the machine, and
// redrawn a row at a time, only where the text changed, so a refresh never holds the main loop.
#pragma once
#include <stdint.h>

namespace mega {

constexpr uint8_t kScreenRows = 8;
constexpr uint8_t kScreenCols = 16;

// The display as the screen logic sees it (hw/oled wraps U8g2's U8x8 text mode).
class TextDisplay {
 public:
  // Draws one row: exactly kScreenCols characters.
  virtual void row(uint8_t r, const char* text) = 0;
};

struct ScreenState {
  enum class Mode : uint8_t { Idle, Homing, Busy, Running, Paused, Done, Aborted, Halted };
  Mode mode;
  bool homed;              // X and Y
  int32_t um[3];           // head position
  uint32_t stop, stops;    // job progress
  uint32_t remainingS;
  int16_t hottestDeciC, hottestLimitDeciC;
  uint8_t hottest;         // its sensor
  bool nanoOnline;
  uint8_t fault;           // the last fault's code, 0 for none
  const char* message;     // M117's text (RAM), or nullptr
};

// Writes row r's text (kScreenCols characters, padded with spaces, NUL-terminated).
void composeRow(const ScreenState& s, uint8_t r, char out[kScreenCols + 1]);

class Screen {
 public:
  explicit Screen(TextDisplay& display) : display_(display) {}
  // Redraws at most one changed row; call every main-loop pass. Returns true if it drew.
  bool poll(const ScreenState& s, uint32_t nowMs);
  void invalidate();

 private:
  TextDisplay& display_;
  uint8_t shown_[kScreenRows] = {};  // a checksum of each row's text as drawn
  uint8_t next_ = 0;
  uint32_t lastMs_ = 0;
  bool any_ = false;
};

}  // namespace mega
