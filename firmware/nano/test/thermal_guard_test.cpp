// Host tests of the over-temperature and sensor-fault state machine.
#include "thermal_guard.h"

#include <gtest/gtest.h>

using namespace nano;

namespace {
const ThermalLimits kLimits = {{600, 600, 600, 600, 550, 550}, 50, 100, 1750};

struct Readings {
  uint16_t mv[6] = {750, 750, 750, 750, 750, 750};  // 25.0 °C
};
}  // namespace

TEST(ThermalGuard, ConversionsMatchTheTmp36) {
  EXPECT_EQ(tmp36DeciC(750), 250);
  EXPECT_EQ(tmp36DeciC(100), -400);
  EXPECT_EQ(adcSumToMv(16 * 1023, 16), 4995);
  EXPECT_EQ(adcSumToMv(16 * 154, 16), 752);  // 154/1024 * 5000 = 751.95
  EXPECT_EQ(adcSumToMv(0, 16), 0);
}

TEST(ThermalGuard, AnySensorTripsAtItsOwnLimitAndClearsBelowHysteresis) {
  ThermalGuard g(kLimits);
  Readings r;
  EXPECT_EQ(g.update(r.mv), 0);
  r.mv[4] = 500 + 550;  // sensor 4 at its 55.0 °C limit
  EXPECT_EQ(g.update(r.mv), uv::fault::kOvertemp);
  EXPECT_EQ(g.hotMask(), 1 << 4);
  r.mv[4] = 500 + 510;  // 51.0: cooled, but not below 55.0 - 5.0
  EXPECT_EQ(g.update(r.mv), uv::fault::kOvertemp);
  r.mv[4] = 500 + 499;  // 49.9: below the hysteresis
  EXPECT_EQ(g.update(r.mv), 0);
  r.mv[0] = 500 + 590;  // 59.0 is under sensor 0's 60.0 limit
  EXPECT_EQ(g.update(r.mv), 0);
}

TEST(ThermalGuard, OpenOrShortedSensorIsAFault) {
  ThermalGuard g(kLimits);
  Readings r;
  r.mv[2] = 0;  // open with a pull-down, or shorted to ground
  EXPECT_EQ(g.update(r.mv), uv::fault::kSensor);
  EXPECT_EQ(g.brokenMask(), 1 << 2);
  r.mv[2] = 4990;  // shorted to the supply: reads as 449 °C, but it is a sensor fault
  EXPECT_EQ(g.update(r.mv), uv::fault::kSensor);
  r.mv[2] = 750;
  EXPECT_EQ(g.update(r.mv), 0);
}
