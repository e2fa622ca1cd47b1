// Build-time safety settings of the printhead (protocol/nano.md); override with -D in platformio.ini.
#pragma once

#ifndef NANO_MAX_EXPOSURE_US
#define NANO_MAX_EXPOSURE_US 10000000UL  // cap on any single LED duration
#endif
#ifndef NANO_TEMP_LIMIT_DC
#define NANO_TEMP_LIMIT_DC 600  // per-sensor over-temperature limit, 0.1 °C (default for all six)
#endif
#ifndef NANO_TEMP_HYSTERESIS_DC
#define NANO_TEMP_HYSTERESIS_DC 50
#endif
#define NANO_FIRMWARE_VERSION "0.2.0"
