// The SSD1306 128x64 panel on the Mega's hardware TWI (D20 SDA, D21 SCL) at 400 kHz, sent from the
// TWI interrupt a frame at a time (ssd1306.h decides the frames). Written for this project instead
// of using U8g2: U8x8 bit-bangs I2C inside drawString, measured at 157 ms of main loop per row
// (the queued steps cover 40 ms), and it costs about 350 B of RAM (its object, Wire and twi that
// U8x8lib links, its set-up tables in .data); this driver needs no library, so the Debian build
// and its simavr rig run it too.
#pragma once
#include "screen.h"
#include "ssd1306.h"

namespace mega {

class Oled : public TextDisplay {
 public:
  // The TWI at 400 kHz with its interrupt, and the panel's set-up queued.
  void begin();
  void poll(uint32_t nowMs) override;
  bool ready() override { return panel_.ready(); }
  void row(uint8_t r, const char* text) override { panel_.show(r, text); }
  bool takeLost() override { return panel_.takeLost(); }

 private:
  Ssd1306 panel_;
  uint32_t startedMs_ = 0;
};

}  // namespace mega
