// The printhead's command brain: the protocol/nano.md table, refusals, latched faults and the pixel colour.
#include "printhead.h"

#include <string.h>

namespace nano {

void Printhead::line(const char* text, uint8_t len, bool overflow, uint32_t nowMs) {
  if (len == 0 && !overflow) return;  // empty lines are ignored without a flag
  uv::NanoCommand c;  // not zeroed: parse sets what each command uses (saves ~100 cycles a line)
  if (!uv::nanoLineUsable(text, len, overflow) || !uv::parseNanoCommand(text, len, c)) {
    latched_ |= uv::fault::kMalformed;
    return;
  }
  uv::Colour flash = uv::flashColour(c.op);
  // A status poll (S, T, E, V, C: dim white) comes right after every F in a job: it must not hide
  // the exposure's purple, which would then never be seen (the pixel is written between edges).
  bool exposing = colour(nowMs) == uv::Colour::Purple;
  if (!(exposing && flash == uv::Colour::DimWhite)) {
    flash_ = flash;
    flashUntilMs_ = nowMs + kFlashMs;
    flashing_ = true;
  }
  handle(c, nowMs);
}

void Printhead::handle(const uv::NanoCommand& c, uint32_t) {
  uv::NanoReply r;  // not zeroed: each case sets the one field formatNanoReply reads for it
  r.op = c.op;
  switch (c.op) {
    case 'S':
      r.mask = io_.litMask();
      return send(r);
    case 'F':
      return fire(c);
    case 'R':
      if (io_.litMask()) whole_ = false;  // an exposure cut short
      return io_.allOff();
    case 'D':
      return io_.servoPulse(kServoDeployUs);
    case 'U':
      return io_.servoPulse(kServoStowUs);
    case 'X':
      return io_.servoPulse(kServoAlarmReleaseUs);
    case 'P':
      r.triggered = io_.probeTriggered();
      return send(r);
    case 'T':
      memcpy(r.deciC, deciC_, sizeof deciC_);
      return send(r);
    case 'E':
      r.flags = faults();
      latched_ = 0;  // latched bits clear once reported; active ones are recomputed from the guard
      return send(r);
    case 'C':
      r.boot = boot_;
      r.fires = fires_;
      r.whole = whole_;
      return send(r);
    case 'V':
      r.protocol = 1;
      strncpy(r.firmware, cfg_.firmwareVersion, sizeof r.firmware - 1);
      return send(r);
  }
}

void Printhead::fire(const uv::NanoCommand& c) {
  if (guard_.active() || !measured_) {
    latched_ |= uv::fault::kRefused;
    return;
  }
  if (io_.litMask()) {
    latched_ |= uv::fault::kBusy;
    return;
  }
  FirePlan plan;
  switch (planFire(c, cfg_.capUs, plan)) {
    case FireVerdict::Capped: latched_ |= uv::fault::kCapped; return;
    case FireVerdict::Nothing: return;
    case FireVerdict::Fire:
      io_.fire(plan);
      fires_++;
      whole_ = true;
      return;
  }
}

void Printhead::readings(const uint16_t mv[uv::kSensorCount]) {
  for (uint8_t i = 0; i < uv::kSensorCount; i++) deciC_[i] = tmp36DeciC(mv[i]);
  measured_ = true;
  if (guard_.update(mv) && io_.litMask()) {
    io_.allOff();
    whole_ = false;
    latched_ |= uv::fault::kCutoff;
  }
}

uv::Colour Printhead::colour(uint32_t nowMs) {
  if (io_.litMask()) return uv::Colour::Purple;  // while any LED is lit, whatever came since
  if (flashing_ && static_cast<int32_t>(nowMs - flashUntilMs_) < 0) return flash_;
  flashing_ = false;  // so a flash cannot come back when the millisecond clock wraps
  return guard_.active() ? uv::Colour::Red : uv::Colour::Green;
}

void Printhead::send(const uv::NanoReply& r) {
  char out[uv::kNanoReplyMax];
  size_t n = uv::formatNanoReply(r, out, sizeof out);
  io_.reply(out, static_cast<uint8_t>(n));
}

}  // namespace nano
