// What the LEDs got (protocol/nano.md "Dose records"), tallied in the main loop.
#include "dose_tally.h"

namespace nano {

void DoseTally::keep(const uint32_t onUs[uv::kLedCount]) {
  if (count_ < kRecords) {  // else the Mega has left the queue full: this record is lost, its number shows it
    DoseRecord& r = next();
    r.exposure = exposure_;
    r.program = program_;
    for (uint8_t i = 0; i < uv::kLedCount; i++) r.onUs[i] = onUs[i];
    count_++;
  }
  program_++;
}

void DoseTally::openFire(const uv::NanoCommand& f) {
  fireOpen_ = true;
  if (count_ == kRecords) return;  // no room: closeFire() counts it lost
  DoseRecord& r = next();
  for (uint8_t i = 0; i < uv::kLedCount; i++) r.onUs[i] = f.mask >> i & 1 ? f.durations[i] : 0;
}

void DoseTally::closeFire(uint32_t untilUs) {
  fireOpen_ = false;
  uint32_t on[uv::kLedCount] = {};
  if (count_ < kRecords) {
    const DoseRecord& r = next();
    for (uint8_t i = 0; i < uv::kLedCount; i++) on[i] = r.onUs[i] < untilUs ? r.onUs[i] : untilUs;
  }
  keep(on);
}

void DoseTally::program(const uint32_t* words, uint8_t count, uint32_t untilUs) {
  uint32_t on[uv::kLedCount] = {};
  uint32_t t = 0;
  uint8_t lit = lights_;
  for (uint8_t e = 0; e < count; e++) {
    uint32_t d = words[e] >> 4;
    bool cut = untilUs - t < d;  // the cut came before this event
    if (cut) d = untilUs - t;
    for (uint8_t i = 0; i < uv::kLedCount; i++)
      if (lit >> i & 1) on[i] += d;
    if (cut) {
      lit = 0;
      break;
    }
    t += d;
    lit = static_cast<uint8_t>(words[e] & 0x0F);
  }
  lights_ = lit;
  keep(on);
}

bool DoseTally::take(DoseRecord& out) {
  if (!count_) return false;
  out = queue_[first_];
  first_ = static_cast<uint8_t>((first_ + 1) % kRecords);
  count_--;
  return true;
}

}  // namespace nano
