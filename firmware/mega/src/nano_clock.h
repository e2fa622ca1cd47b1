// The Nano's clock against the Mega's (protocol/nano.md `W`). Each board's 16 MHz comes from its own
// crystal or resonator (±50 ppm, ±0.5 %), and a scan pass's light runs on the Nano's clock while the
// head runs on the Mega's: 0.5 % over a 1.6 s pass is 8 ms, four 2 ms cells. The Mega asks `W` now
// and then, noting its own micros() as the line goes out; the Nano answers with its micros() as the
// line arrived. The two clocks' spans since a first exchange give the Nano's rate.
#pragma once
#include <stdint.h>

namespace mega {

// Spans shorter than this are not trusted: both timestamps are good to about 10 µs (both micros()
// tick 4 µs), so 2 s give the rate to 5 ppm, 8 µs over a 1.6 s pass; it only improves after.
constexpr uint32_t kClockBaselineUs = 2000000;
// A measured rate further off than this is no crystal or resonator: the Nano restarted between two
// exchanges (its micros() began again), or an answer was lost. The exchanges start over.
constexpr int32_t kClockMaxPpm = 20000;
// After this long the first exchange is dropped for the latest, so the rate follows a clock that
// drifts as the boards warm.
constexpr uint32_t kClockRebaseUs = 300000000;

class NanoClock {
 public:
  // One `W` exchange: the Mega's micros() when the W went out, the Nano's when it arrived.
  void sample(uint32_t megaUs, uint32_t nanoUs);
  // A Nano that restarted or fell silent: its clock is measured again from the next exchange.
  void forget() { anchored_ = known_ = false; }
  bool known() const { return known_; }
  // How many parts per million the Nano's clock runs fast (negative: slow).
  int32_t ppm() const { return ppm_; }
  // A rate of `ppm` as a factor for toNano: the Nano's extra µs per µs of the Mega's, in 2⁻³² (within
  // ±85 899 346 for the ±20 000 ppm a clock may be off). Worked out once a pass: it takes a 64-bit
  // division, 38 µs on the Mega, which each of a scan's events would otherwise pay.
  static int32_t rate(int32_t ppm);
  // `us` of the Mega's clock as the Nano counts them at `rate` (rate(ppm)), rounded: within 1 µs of
  // us × (1 + ppm / 10⁶) below 2³² µs.
  static uint32_t toNano(uint32_t us, int32_t rate);

 private:
  bool anchored_ = false, known_ = false;
  uint32_t megaUs0_ = 0, nanoUs0_ = 0;
  int32_t ppm_ = 0;
};

}  // namespace mega
