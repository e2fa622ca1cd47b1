// The Mega's side of the printhead link (protocol/nano.md): polls, exposures, the probe, time-outs.
#include "printhead_link.h"

#include <string.h>

namespace mega {

namespace {
bool due(uint32_t now, uint32_t at) { return static_cast<int32_t>(now - at) >= 0; }
constexpr uint8_t kRefusals = uv::fault::kCapped | uv::fault::kBusy | uv::fault::kRefused;
}  // namespace

uint8_t PrintheadLink::send(const uv::NanoCommand& c) {
  // The speed is not settled: only the link's own L, V and R go (and nothing before the R after a start).
  if (switching() && (speed_ == Speed::Waking || (c.op != 'L' && c.op != 'V' && c.op != 'R'))) return 0;
  char out[uv::kNanoMaxLine + 2];
  uint8_t n = static_cast<uint8_t>(uv::formatNanoCommand(c, out, sizeof out));
  if (!n || !io_.write(out, n)) return 0;
  sent_++;
  return n;
}

bool PrintheadLink::ask(char op, uint32_t nowUs) {
  uv::NanoCommand c{};
  c.op = op;
  if (!send(c)) return false;
  awaitReply(op, nowUs);
  return true;
}

void PrintheadLink::awaitReply(char op, uint32_t nowUs) {
  inFlight_ = op;
  askedAt_ = nowUs;
}

void PrintheadLink::begin(uint32_t nowUs) {
  if (raise_) {
    // This side restarted at 115200; the Nano may still be at a raised speed. A 0x00 is a framing
    // error at any raised speed (its nine low bits outlast a fast frame), so it takes the Nano back to
    // 115200 at once; after a quiet 2 ms, a newline ends the line that noise began, then the R.
    const char nul = 0;
    io_.write(&nul, 1);
    speed_ = Speed::Waking;
    nextSpeed_ = nowUs + kWakeGapUs;
  } else {
    allOff();
  }
  identityWanted_ = true;
  clock_.forget();
  nextClock_ = nowUs;  // the first W right away
  nextThermal_ = nowUs;
  nextFault_ = nowUs + kFaultPollUs / 2;
}

void PrintheadLink::allOff(uint8_t why) {
  uv::NanoCommand r{};
  r.op = 'R';
  held_ = doseHeld_ = false;  // whatever a scan pass was waiting for, it is over
  offPending_ = !send(r);  // a full UART: poll() sends it before anything else
  // The Nano takes 115200 as the R ends; so does this side, once the R has gone out at the old speed.
  if (!offPending_ && speed_ != Speed::Start) {
    lowerSpeed(nextSpeed_);
    raiseSoon_ = true;  // no doubt about the speed: raised again at the next idle moment
  }
  if (fire_ == FireState::Firing) fireFailed(why);
}

void PrintheadLink::lowerSpeed(uint32_t retryAtUs) {
  raiseSoon_ = false;
  if (speed_ != Speed::Start && speed_ != Speed::Asked) speed_ = Speed::Lowering;
  else speed_ = Speed::Start;  // an L unanswered: this side never left 115200
  nextSpeed_ = retryAtUs;
  if (speed_ == Speed::Lowering && io_.setBaud(uv::kNanoBaud)) speed_ = Speed::Start;
}

bool PrintheadLink::speedStep(uint32_t nowUs) {
  if (speed_ == Speed::Waking) {
    if (!due(nowUs, nextSpeed_) || !io_.write("\n", 1)) return true;
    speed_ = Speed::Start;
    raiseSoon_ = true;
    allOff();
    return true;
  }
  if (speed_ == Speed::Lowering) {
    if (io_.setBaud(uv::kNanoBaud)) speed_ = Speed::Start;
    return speed_ == Speed::Lowering;  // nothing else goes meanwhile
  }
  if (speed_ == Speed::Probing) {  // both sides changed: a V must come back at the new speed
    ask('V', nowUs);
    return true;
  }
  // Raised only when idle: no exposure, no pass, nothing asked, the Nano known.
  if (!raise_ || speed_ != Speed::Start || held_ || !online_ || identityWanted_ || fire_ == FireState::Firing) return false;
  if (!raiseSoon_ && !due(nowUs, nextSpeed_)) return false;
  if (due(nowUs, nextClock_)) return false;  // a W due goes first: its exchange needs the line idle
  uv::NanoCommand l{};
  l.op = 'L';
  l.baud = kNanoFastBaud;
  if (!send(l)) return false;
  awaitReply('L', nowUs);
  speed_ = Speed::Asked;
  raiseSoon_ = false;
  nextSpeed_ = nowUs + kSpeedRetryUs;  // if this one fails
  return true;
}

void PrintheadLink::fireFailed(uint8_t code) {
  fire_ = FireState::Failed;
  fireError_ = code;
  fireCheckWanted_ = false;
}

bool PrintheadLink::fire(uint8_t mask, const uint32_t us[uv::kLedCount], uint32_t nowUs) {
  if (fire_ == FireState::Firing || !online_ || offPending_ || switching()) return false;
  uv::NanoCommand f{};
  f.op = 'F';
  f.mask = mask;
  uint32_t longest = 0;
  for (uint8_t i = 0; i < uv::kLedCount; i++) {
    f.durations[i] = us[i];
    if ((mask & (1 << i)) && us[i] > longest) longest = us[i];
  }
  const uint8_t n = send(f);
  if (!n) return false;
  fire_ = FireState::Firing;
  fireError_ = fireFlags_ = 0;
  fireCheckWanted_ = false;
  // When an S sent then finds the light over: the line's time on the wire counts (a 2 ms F is 1.3 ms).
  fireEndsAt_ = nowUs + static_cast<uint32_t>(n) * (10u * 1000000u) / baud() + kFireTakenUs + longest;
  // One early S confirms the Nano took it (a refused F is off at once), the next when it should be over.
  nextStatus_ = longest > kFireFirstCheckUs ? nowUs + kFireFirstCheckUs : fireEndsAt_;
  return true;
}

bool PrintheadLink::programLine(const char* line, uint8_t len, uint32_t nowUs) {
  const bool seal = line[0] == 'K';
  if ((seal && inFlight_) || offPending_ || switching() || !io_.write(line, len)) return false;
  sent_++;
  nextSpeed_ = nowUs + kSpeedRetryUs;  // programs flow: a job runs, and the speed is raised only after it
  if (seal) {
    awaitReply('K', nowUs);
    sealAnswered_ = false;
  }
  return true;
}

bool PrintheadLink::startChain() {
  uv::NanoCommand g{};
  g.op = 'G';
  return !offPending_ && send(g);
}

bool PrintheadLink::servo(char op) {
  uv::NanoCommand c{};
  c.op = op;
  return send(c);
}

void PrintheadLink::forgetClock(uint32_t nowUs) {
  clock_.forget();
  nextClock_ = nowUs + kClockPollUs;
}

void PrintheadLink::flagsSeen(uint8_t flags, uint32_t nowUs) {
  uint8_t newlyActive = static_cast<uint8_t>(flags & uv::fault::kActive & ~flags_);
  if (newlyActive || (flags & uv::fault::kCutoff)) events_ |= kFault;
  if (flags & uv::fault::kWatchdog) {
    events_ |= kNanoReset;
    forgetClock(nowUs);  // its micros() began again
    if (speed_ != Speed::Start) lowerSpeed(nowUs + kSpeedRetryUs);  // and it is at 115200
  }
  flags_ = flags;
}

void PrintheadLink::missed(uint32_t nowUs) {
  if (misses_ < 255) misses_++;
  if (misses_ < kNanoMissesOffline) return;
  online_ = false;
  forgetClock(nowUs);
  if (!reportedOffline_) {
    reportedOffline_ = true;
    events_ |= kWentOffline;
  }
  if (fire_ == FireState::Firing) {
    allOff();  // it may still hear this
    fireFailed(30);
  }
}

void PrintheadLink::handle(const uv::NanoReply& r, uint32_t nowUs, DoseSink dose) {
  if (r.op == inFlight_) inFlight_ = 0;
  misses_ = 0;
  online_ = true;
  if (reportedOffline_) {
    reportedOffline_ = false;
    identityWanted_ = true;  // maybe a different or reset Nano
    events_ |= kCameBack;
  }
  switch (r.op) {
    case 'T':
      memcpy(deciC_, r.deciC, sizeof deciC_);
      tempsKnown_ = true;
      break;
    case 'E':
      flagsSeen(r.flags, nowUs);
      if (fire_ == FireState::Firing && fireCheckWanted_) {
        fireCheckWanted_ = false;
        if (r.flags & kRefusals) {
          fireFlags_ = static_cast<uint8_t>(r.flags & kRefusals);
          // Refused because the head is too hot: said as the over-temperature it is.
          fireFailed((r.flags & uv::fault::kOvertemp) ? 31 : 33);
        } else if (r.flags & uv::fault::kCutoff) {
          fireFailed(31);
        } else {
          fire_ = FireState::Done;
        }
      }
      break;
    case 'S':
      if (fire_ != FireState::Firing) break;
      if (r.mask == 0) {
        fireCheckWanted_ = true;
      } else if (due(nowUs, fireEndsAt_ + kFireGraceUs)) {
        allOff(33);  // on far longer than asked: never leave an LED on
      } else {
        nextStatus_ = due(nowUs, fireEndsAt_) ? nowUs + kFireRepollUs : fireEndsAt_;
      }
      break;
    case 'P':
      probeTriggered_ = r.triggered;
      probeAnswered_ = true;
      break;
    case 'C':
      if (countersAnswered_ && r.boot != boot_ && speed_ != Speed::Start) lowerSpeed(nowUs + kSpeedRetryUs);  // it restarted
      boot_ = r.boot;
      fires_ = r.fires;
      whole_ = r.whole;
      countersAnswered_ = true;
      break;
    case 'K':
      sealCode_ = r.code;
      sealAnswered_ = true;
      break;
    case 'Q':
      passFree_ = r.free;
      passArmed_ = r.armed;
      passState_ = r.pass;
      passAnswered_ = true;
      break;
    case 'W':
      clock_.sample(clockSentUs_, r.us);
      break;
    case 'O':  // a record, and then the next is asked, until O:0
      if (!r.exposure) doseWanted_ = false;
      else if (dose.take) dose.take(dose.ctx, &r);
      break;
    case 'L':  // the Nano takes the speed as this reply ends: this side now, nothing having gone since
      if (speed_ != Speed::Asked) break;
      if (r.baud == kNanoFastBaud && io_.setBaud(kNanoFastBaud)) {
        speed_ = Speed::Probing;
      } else {
        speed_ = Speed::Start;  // the Nano, unconfirmed, returns to 115200 within 100 ms
        raiseFailed_ = true;
      }
      break;
    case 'V':
      if (speed_ == Speed::Probing) {  // heard both ways at the new speed
        speed_ = Speed::Raised;
        raiseFailed_ = false;
      }
      memcpy(firmware_, r.firmware, sizeof firmware_ - 1);
      firmware_[sizeof firmware_ - 1] = 0;
      identityWanted_ = false;
      break;
    default:
      break;
  }
}

void PrintheadLink::poll(uint32_t nowUs, DoseSink dose) {
  if (offPending_ && speed_ != Speed::Waking) allOff();
  for (uint8_t budget = 64; budget; budget--) {  // bounded: a chattering line cannot hold the loop
    int16_t b = io_.read();
    if (b < 0) break;
    if (!splitter_.push(static_cast<char>(b)) || splitter_.overflow()) continue;
    char reply[kReplyMax + 2];
    uint8_t n = splitter_.length();
    memcpy(reply, splitter_.text(), n);
    reply[n++] = '\n';
    uv::NanoReply r{};
    if (uv::parseNanoReply(reply, n, r)) handle(r, nowUs, dose);
  }
  if (inFlight_ && due(nowUs, askedAt_ + kNanoReplyTimeoutUs)) {
    if (inFlight_ == 'V') identityWanted_ = false;  // asked once; its absence is not a fault
    if (inFlight_ == 'C') countersWanted_ = true;   // asked again until answered
    if (inFlight_ == 'Q') passWanted_ = true;
    if (inFlight_ == 'O') {  // its records are given up (a Nano from before O answers nothing): no miss
      doseWanted_ = false;
      inFlight_ = 0;
      return;
    }
    if (inFlight_ == 'K') {  // the program's fate is unknown: the runner treats it as refused
      sealCode_ = kSealUnanswered;
      sealAnswered_ = true;
    }
    if (inFlight_ == 'L' || speed_ == Speed::Probing) raiseFailed_ = true;  // the Nano never took the raise
    inFlight_ = 0;
    if (speed_ != Speed::Start) lowerSpeed(nowUs + kSpeedRetryUs);  // a reply missed above 115200: any doubt lowers it
    missed(nowUs);
  }
  if (inFlight_) return;
  if (speedStep(nowUs)) return;
  if (held_) {  // a scan pass's own Q and O alone: it asks none while its G waits, and needs them in time after
    if (passWanted_ && ask('Q', nowUs)) passWanted_ = false;
    else if (doseMayAsk(dose)) ask('O', nowUs);
    return;
  }
  if (fire_ == FireState::Firing) {
    if (fireCheckWanted_) {
      ask('E', nowUs);
      return;
    }
    if (due(nowUs, nextStatus_)) {
      ask('S', nowUs);
      return;
    }
  }
  if (passWanted_) {  // a pass polls every 10 ms: the Nano cuts a chain after 50 ms of silence
    if (ask('Q', nowUs)) passWanted_ = false;
    return;
  }
  if (probeWanted_) {
    if (ask('P', nowUs)) probeWanted_ = false;
    return;
  }
  if (fire_ != FireState::Firing && doseMayAsk(dose)) {
    ask('O', nowUs);
    return;
  }
  if (countersWanted_ && fire_ != FireState::Firing) {
    if (ask('C', nowUs)) countersWanted_ = false;
    return;
  }
  if (identityWanted_ && due(nowUs, nextThermal_)) {
    ask('V', nowUs);
    nextThermal_ = nowUs + kThermalPollUs / 10;
    return;
  }
  // The clock's W must find the transmitter idle; when it does not, the next pass tries again.
  if (fire_ != FireState::Firing && due(nowUs, nextClock_) && io_.writeNow('W', clockSentUs_)) {
    // The Nano notes the W as its newline arrives, two byte-times on: timed from then, a sample taken
    // at one speed compares with one taken at another.
    clockSentUs_ += 2 * uv::linkByteUs(baud());
    sent_++;
    awaitReply('W', nowUs);
    nextClock_ = nowUs + (clock_.known() ? kClockRepollUs : kClockPollUs);
    return;
  }
  // No background E while an exposure runs: its latched bits belong to the exposure's own check.
  if (fire_ != FireState::Firing && due(nowUs, nextFault_)) {
    if (ask('E', nowUs)) nextFault_ = nowUs + kFaultPollUs;
    return;
  }
  if (due(nowUs, nextThermal_)) {
    if (ask('T', nowUs)) nextThermal_ = nowUs + kThermalPollUs;
  }
}

}  // namespace mega
