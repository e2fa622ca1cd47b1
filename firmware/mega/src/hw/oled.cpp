// The SSD1306 panel through U8x8 (or dark, in a build without U8g2).
#include "hw/oled.h"

namespace mega {

#ifdef UV_WITH_U8G2

void Oled::begin() {
  u8x8_.begin();
  u8x8_.setFont(u8x8_font_chroma48medium8_r);
  u8x8_.clearDisplay();
}

void Oled::row(uint8_t r, const char* text) { u8x8_.drawString(0, r, text); }

#else

void Oled::begin() {}
void Oled::row(uint8_t, const char*) {}

#endif

}  // namespace mega
