// The SSD1306's set-up and text-row frames.
#include "ssd1306.h"

#include <string.h>

#include "panel_font.h"
#include "progmem.h"

namespace mega {

namespace {

// Set-up for a 128x64 module with the charge pump (datasheet's application note order). Each part
// ends on a command boundary, since each goes in its own frame.
const uint8_t kSetup[] UV_FLASH = {
    0xae,        // display off while it is set up
    0xd5, 0x80,  // clock divide and oscillator: the reset default
    0xa8, 0x3f,  // multiplex: 64 lines
    0xd3, 0x00,  // no display offset
    0x40,        // start line 0
    0x8d, 0x14,  // charge pump on (no external VCC on these modules)
    0x20, 0x00,  // horizontal addressing: a row's 128 bytes run left to right
    0xa1,        // column 127 on SEG0 and
    0xc8,        // COM63 first: as the common modules are wired, column 0 is left and page 0 on top
    0xda, 0x12,  // COM pins: alternative, for 64 lines
    // frame two
    0x81, 0xcf,  // contrast
    0xd9, 0xf1,  // pre-charge for the internal charge pump
    0xdb, 0x40,  // VCOMH deselect level
    0xa4,        // show RAM
    0xa6,        // normal, not inverted
    0xaf,        // display on
};
constexpr uint8_t kSetupFirstFrame = 16;  // bytes of kSetup in frame one
static_assert(sizeof kSetup - kSetupFirstFrame <= kFrameMax - 1, "the set-up fits two frames");
static_assert(kScreenCols % kFrameGlyphs == 0, "a row splits into whole frames");

}  // namespace

void Ssd1306::begin() {
  step_ = Step::Setup;
  index_ = 0;
}

void Ssd1306::show(uint8_t row, const char* text) {
  memcpy(text_, text, kScreenCols);
  row_ = static_cast<uint8_t>(row & 7);
  step_ = Step::Address;
}

bool Ssd1306::next(PanelFrame& f, uint32_t nowMs) {
  switch (step_) {
    case Step::Wait:
      if (static_cast<int32_t>(nowMs - retryAt_) < 0) return false;
      begin();
      // fall through - set up again
    case Step::Setup: {
      uint8_t end = index_ == 0 ? kSetupFirstFrame : sizeof kSetup;
      f.bytes[0] = 0x00;
      f.len = 1;
      while (index_ < end) f.bytes[f.len++] = uvFlashByte(&kSetup[index_++]);
      if (index_ == sizeof kSetup) step_ = Step::Idle;
      return true;
    }
    case Step::Address: {
      // Columns 0-127 and pages row-7: the data that follows fills this row's page.
      const uint8_t frame[] = {0x00, 0x21, 0, 127, 0x22, row_, 7};
      memcpy(f.bytes, frame, sizeof frame);
      f.len = sizeof frame;
      step_ = Step::Glyphs;
      index_ = 0;
      return true;
    }
    case Step::Glyphs: {
      f.bytes[0] = 0x40;
      f.len = 1;
      for (uint8_t g = 0; g < kFrameGlyphs; g++, index_++)
        for (uint8_t col = 0; col < 8; col++) f.bytes[f.len++] = glyphColumn(text_[index_], col);
      if (index_ == kScreenCols) step_ = Step::Idle;
      return true;
    }
    case Step::Idle:
      break;
  }
  return false;
}

void Ssd1306::failed(uint32_t nowMs) {
  step_ = Step::Wait;
  retryAt_ = nowMs + kPanelRetryMs;
  lost_ = true;
}

}  // namespace mega
