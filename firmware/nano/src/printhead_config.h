// The printhead's build-time settings (config.h) as the Printhead takes them: one constant for the
// real Nano (main.cpp) and the simulated one (firmware/virtual/fake_nano.h), so the simulated
// printer reports the Nano's version and cuts off at its limits.
#pragma once
#include "config.h"
#include "printhead.h"

namespace nano {

const PrintheadConfig kPrintheadConfig = {
    NANO_MAX_EXPOSURE_US,
    // A TMP36 reading under 100 mV is open or shorted to ground; over 1750 mV, shorted to the supply.
    {NANO_TEMP_LIMITS_DC, NANO_TEMP_HYSTERESIS_DC, 100, 1750},
    NANO_FIRMWARE_VERSION,
};

}  // namespace nano
