// One WS2812 NeoPixel on D8: writes a colour as 24 cycle-timed bits (about 32 µs, interrupts off).
#pragma once
#include <stdint.h>

namespace nano {
namespace neopixel {

void begin();
void show(uint8_t r, uint8_t g, uint8_t b);

}  // namespace neopixel
}  // namespace nano
