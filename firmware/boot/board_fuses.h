// What an AVR board's fuses and lock bits, as Arduino ships them (boards-as-shipped.json), make of the
// chip: where the boot section starts, whether SPM may write there, how long the chip stays in reset.
#pragma once
#include <cstdint>

namespace uv {

struct ChipFacts {
  uint32_t flashBytes;
  uint32_t pageBytes;
  uint32_t bootWordsByBootsz[4];  // BOOTSZ1..0 = 00, 01, 10, 11
  double spmMs;                   // page erase, page write
};

struct ShippedFuses {
  uint8_t low, high, extended, lock;
};

// High fuse bits 2..1: BOOTSZ1..0 (both datasheets, "Fuse High Byte").
inline uint32_t bootSectionBytes(const ChipFacts& chip, const ShippedFuses& f) {
  return chip.bootWordsByBootsz[(f.high >> 1) & 3] * 2;
}

inline uint32_t bootSectionStart(const ChipFacts& chip, const ShippedFuses& f) {
  return chip.flashBytes - bootSectionBytes(chip, f);
}

// High fuse bit 0, BOOTRST programmed (0): a reset starts at the boot section, not at 0.
inline bool resetsToBootloader(const ShippedFuses& f) { return (f.high & 1) == 0; }

// Lock bits 5..4, BLB12 and BLB11: modes 2 (10) and 3 (00) forbid SPM to write the boot section
// ("Boot Lock Bit1 Protection Modes"). Arduino's 0x0F is mode 3.
inline bool bootSectionWritable(const ShippedFuses& f) { return (f.lock & 0x10) != 0; }

// The time-out a reset adds before the chip runs: "Start-up Times for the Low Power Crystal Oscillator
// Clock Selection", by CKSEL0 and SUT1..0 (low fuse bits 0 and 5..4), "Additional Delay from Reset
// (VCC = 5.0V)": 14 CK plus 0, 4.1 or 65 ms. Arduino's 0xFF is a crystal, slowly rising power: 14 CK + 65 ms.
// (The 16K CK beside it is the oscillator's start from power-down, which an external reset does not need.)
struct ResetDelay {
  uint32_t clocks;
  double ms;
};

inline ResetDelay resetDelay(const ShippedFuses& f) {
  const bool cksel0 = f.low & 1;
  const unsigned sut = (f.low >> 4) & 3;
  // Rows in the datasheet's order, CKSEL0 then SUT1..0.
  static constexpr double kMs[8] = {4.1, 65, 0, 4.1, 65, 0, 4.1, 65};
  return {14, kMs[(cksel0 ? 4 : 0) + sut]};
}

// The DTR# edge reaches RESET through the auto-reset capacitor; RESET climbs back through the pull-up
// and the chip leaves reset once it crosses the pin's threshold (taken as half of Vcc: ln 2 * RC).
inline double autoResetPulseMs(double capacitorNf, double pullUpOhms) {
  return 0.6931471805599453 * capacitorNf * 1e-9 * pullUpOhms * 1e3;
}

}  // namespace uv
