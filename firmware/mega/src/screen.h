// What the SSD1306 shows (128 x 64 as 8 rows of 16 characters): state, position, job progress,
// temperatures and the last fault or message. Composed from a snapshot of the machine one row per
// pass at most, and redrawn a row at a time, only where the text changed, by a display that sends in
// the background: so a refresh never holds the main loop.
#pragma once
#include <stdint.h>

namespace mega {

constexpr uint8_t kScreenRows = 8;
constexpr uint8_t kScreenCols = 16;

// The display as the screen logic sees it (hw/oled: an SSD1306 on the TWI, driven from its interrupt).
class TextDisplay {
 public:
  // Moves the display's own work on a step (a frame to send); called every main-loop pass, never waits.
  virtual void poll(uint32_t nowMs) = 0;
  // True when row() may be called: the row before has gone out.
  virtual bool ready() = 0;
  // Hands over one row (exactly kScreenCols characters); it is sent in the background.
  virtual void row(uint8_t r, const char* text) = 0;
  // True once after the display stopped answering: what it showed must be drawn again.
  virtual bool takeLost() = 0;
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
  // Moves the display on and says whether a row is due to be composed: the display is free and
  // kComposeEveryMs have passed. Cheap; call every main-loop pass, and draw() only when true, so
  // the snapshot is taken only then.
  bool due(uint32_t nowMs);
  // Composes the next row from s and hands it to the display if it changed; true if it did.
  bool draw(const ScreenState& s, uint32_t nowMs);
  bool poll(const ScreenState& s, uint32_t nowMs) { return due(nowMs) && draw(s, nowMs); }
  // The row draw() composes next (the snapshot may leave out what the others need).
  uint8_t nextRow() const { return next_; }
  void invalidate();

 private:
  TextDisplay& display_;
  uint8_t shown_[kScreenRows] = {};  // a checksum of each row's text as drawn
  uint8_t next_ = 0;
  uint32_t lastMs_ = 0;
  bool any_ = false;
};

}  // namespace mega
