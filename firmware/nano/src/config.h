// Build-time safety settings of the printhead (protocol/nano.md); override with -D in platformio.ini.
#pragma once

#ifndef NANO_MAX_EXPOSURE_US
#define NANO_MAX_EXPOSURE_US 10000000UL  // cap on any single LED duration
#endif
#ifndef NANO_TEMP_LIMITS_DC
// Over-temperature limit of each sensor A0..A5, in 0.1 °C, e.g. -DNANO_TEMP_LIMITS_DC="{600,600,600,600,550,550}".
#define NANO_TEMP_LIMITS_DC {600, 600, 600, 600, 600, 600}
#endif
#ifndef NANO_TEMP_HYSTERESIS_DC
#define NANO_TEMP_HYSTERESIS_DC 50
#endif
#define NANO_FIRMWARE_VERSION "0.2.0"
