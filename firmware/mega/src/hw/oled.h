// The SSD1306 128x64 panel through U8g2's U8x8 text mode, bit-banged on D20/D21 (no Wire buffers:
// about 40 bytes of RAM). Built with -DUV_WITH_U8G2 (PlatformIO's lib_deps); without it (the
// Debian toolchain build, which cannot fetch U8g2) the panel stays dark.
#pragma once
#include "screen.h"

#ifdef UV_WITH_U8G2
#include <U8x8lib.h>
#endif

namespace mega {

class Oled : public TextDisplay {
 public:
  void begin();
  void row(uint8_t r, const char* text) override;

 private:
#ifdef UV_WITH_U8G2
  U8X8_SSD1306_128X64_NONAME_SW_I2C u8x8_{/* clock */ 21, /* data */ 20};
#endif
};

}  // namespace mega
