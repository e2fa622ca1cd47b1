// The printhead's command brain: the protocol/nano.md table, refusals, latched faults and the pixel colour.
#include "printhead.h"

#include <string.h>

namespace nano {

void Printhead::line(const char* text, uint8_t len, bool overflow, uint32_t nowMs) {
  lastLineMs_ = nowMs;  // any line: the Mega is alive
  settle();
  if (len == 0 && !overflow) return;  // empty lines are ignored without a flag
  uv::NanoCommand c;  // not zeroed: parse sets what each command uses (saves ~100 cycles a line)
  bool usable = uv::nanoLineUsable(text, len, overflow);
  if (usable && len >= 2 && text[1] == ':' && (text[0] == 'A' || text[0] == 'B' || text[0] == 'K')) {
    if (!program(text, len)) {  // a program line, taken first: a malformed one flashes nothing
      latched_ |= uv::fault::kMalformed;
      if (raised_) fallBack();
      return;
    }
    confirming_ = false;
    c.op = text[0];  // then it flashes dim white, like a poll
  } else if (!usable || !uv::parseNanoCommand(text, len, c)) {
    latched_ |= uv::fault::kMalformed;
    if (raised_) fallBack();  // a line misread: maybe the Mega is at another speed
    return;
  }
  confirming_ = false;  // a correct line: the speed, raised or not, is heard
  uv::Colour flash = uv::flashColour(c.op);
  // A status poll (S, T, E, V, C: dim white) comes right after every F in a job: it must not hide
  // the exposure's purple, which would then never be seen (the pixel is written between edges).
  bool purple = colour(nowMs) == uv::Colour::Purple;
  if (!(purple && flash == uv::Colour::DimWhite)) {
    flash_ = flash;
    flashUntilMs_ = nowMs + kFlashMs;
    flashing_ = true;
  }
  if (c.op == 'A' || c.op == 'B' || c.op == 'K') return;
  handle(c, nowMs);
}

bool Printhead::program(const char* text, uint8_t len) {
  if (text[0] != 'K') return store_.append(text, len);
  uv::Seal s;
  if (!uv::parseSeal(text, len, s)) return false;
  uv::NanoReply r;
  r.op = 'K';
  r.code = static_cast<uint8_t>(store_.seal(s));
  send(r);
  return true;
}

void Printhead::start() {
  if (guard_.active() || !measured_) {
    latched_ |= uv::fault::kRefused;
  } else if (exposing()) {
    latched_ |= uv::fault::kBusy;
    if (store_.running()) return;  // Q goes on telling the running chain's state
  } else if (store_.startable()) {
    store_.start();
    dose_.begin(fires_ + 1);
    if (io_.startProgram(store_)) {
      fires_++;
      whole_ = true;
      programLast_ = true;
      return;
    }
    store_.discard(uv::PassState::Refused);  // time 0 went by: the chain cannot run as planned
    return;
  }
  store_.refuse();
}

void Printhead::handle(const uv::NanoCommand& c, uint32_t nowMs) {
  uv::NanoReply r;  // not zeroed: each case sets the one field formatNanoReply reads for it
  r.op = c.op;
  switch (c.op) {
    case 'S':
      r.mask = io_.litMask();
      return send(r);
    case 'F':
      return fire(c);
    case 'G':
      return start();
    case 'W':
      r.us = io_.clockLineUs();
      return send(r);
    case 'O': {
      DoseRecord d;
      r.exposure = 0;  // none waits
      if (dose_.take(d)) {
        r.exposure = d.exposure;
        r.program = d.program;
        memcpy(r.onUs, d.onUs, sizeof d.onUs);
      }
      return send(r);
    }
    case 'Q':
      r.free = store_.freeBuffers();
      r.armed = store_.armed();
      r.pass = static_cast<uint8_t>(store_.pass());
      return send(r);
    case 'R':
      if (exposing() || io_.cutByReset()) whole_ = false;  // an exposure cut short
      io_.allOff();
      settle();
      if (raised_) {  // back to 115200: the receive interrupt already did, as the line ended
        io_.linkSpeed(uv::kNanoBaud, false);
        raised_ = false;
        confirming_ = false;
      }
      return store_.discard(uv::PassState::CutByReset);
    case 'L':
      if (exposing() || store_.armed()) {  // a speed change is for an idle link
        latched_ |= uv::fault::kBusy;
        return;
      }
      r.baud = c.baud;
      send(r);
      return speed(c.baud, nowMs);
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
      r.whole = whole_ && !(programLast_ && store_.pass() == uv::PassState::Underrun);
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
  if (exposing()) {
    latched_ |= uv::fault::kBusy;
    return;
  }
  FirePlan plan;
  switch (planFire(c, cfg_.capUs, plan)) {
    case FireVerdict::Capped: latched_ |= uv::fault::kCapped; return;
    case FireVerdict::Nothing: return;
    case FireVerdict::Fire:
      dose_.begin(fires_ + 1);
      dose_.openFire(c);
      io_.fire(plan);
      fires_++;
      whole_ = true;
      programLast_ = false;
      return;
  }
}

// A chain runs on the Nano's clock while the head moves on the Mega's. If the Mega stops (a reset,
// a hang), so does the head, and the chain would go on lighting one place: a Mega that runs a pass
// sends a line at least every 20 ms, and a chain that hears none for 50 ms is cut.
void Printhead::poll(uint32_t nowMs) {
  if (confirming_ && static_cast<uint16_t>(nowMs - switchedMs_) > kLinkConfirmMs) fallBack();  // never heard at the new speed
  settle();
  if (!store_.running() || nowMs - lastLineMs_ <= uv::kChainSilenceMs) return;
  io_.allOff();
  settle();
  store_.discard(uv::PassState::CutBySilence);
  whole_ = false;
}

// The reply that names the new speed goes out at the old one; the UART changes after its stop bit.
void Printhead::speed(uint32_t baud, uint32_t nowMs) {
  io_.linkSpeed(baud, true);
  raised_ = confirming_ = baud != uv::kNanoBaud;
  switchedMs_ = static_cast<uint16_t>(nowMs);
}

void Printhead::noise() {
  if (raised_) fallBack();
}

void Printhead::fallBack() {
  if (exposing() || io_.cutByReset()) whole_ = false;  // the receive interrupt may have cut it already
  io_.allOff();
  settle();
  store_.discard(uv::PassState::CutByReset);
  io_.linkSpeed(uv::kNanoBaud, false);
  raised_ = confirming_ = false;
}

void Printhead::readings(const uint16_t mv[uv::kSensorCount]) {
  for (uint8_t i = 0; i < uv::kSensorCount; i++) deciC_[i] = tmp36DeciC(mv[i]);
  measured_ = true;
  if (guard_.update(mv) && exposing()) {
    io_.allOff();
    settle();
    store_.discard(uv::PassState::CutByFault);
    whole_ = false;
    latched_ |= uv::fault::kCutoff;
  }
}

uv::Colour Printhead::colour(uint32_t nowMs) {
  if (exposing()) return uv::Colour::Purple;  // while any LED is lit or a pass runs, whatever came since
  if (flashing_ && static_cast<int32_t>(nowMs - flashUntilMs_) < 0) return flash_;
  flashing_ = false;  // so a flash cannot come back when the millisecond clock wraps
  return guard_.active() ? uv::Colour::Red : uv::Colour::Green;
}

void Printhead::settle() {
  bool dark = !io_.litMask();  // read before the cut: a cut that comes after it waits for the next call
  int32_t ticks;
  bool cut = io_.takeCut(ticks);
  uint32_t untilUs = ticks <= 0 ? 0 : (static_cast<uint32_t>(ticks) + 8) >> 4;
  if (dose_.fireOpen() && (cut || dark)) dose_.closeFire(cut ? untilUs : DoseTally::kWhole);
  ScanStore::ProgramView v;
  while (store_.oldestSpent(v)) {
    dose_.program(v.words, v.count, DoseTally::kWhole);
    store_.freeOldestSpent();
  }
  uint8_t made;
  if (cut && store_.runningProgram(v, made)) {
    for (uint8_t e = 0; e < made; e++) untilUs += v.words[e] >> 4;  // its events made before the cut
    dose_.program(v.words, v.count, untilUs);
  }
}

void Printhead::send(const uv::NanoReply& r) {
  char out[uv::kNanoReplyMax];
  size_t n = uv::formatNanoReply(r, out, sizeof out);
  io_.reply(out, static_cast<uint8_t>(n));
}

}  // namespace nano
