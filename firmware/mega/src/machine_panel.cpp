// The Mega's panel: the SSD1306 status screen, the three buttons, and M117's message line.
#include <string.h>

#include "error_codes.h"
#include "fast_div.h"
#include "machine.h"
#include "progmem.h"

namespace mega {

ScreenState Machine::screenState(uint8_t row) const {
  ScreenState s{};
  using Mode = ScreenState::Mode;
  s.mode = halted_ ? Mode::Halted : Mode::Idle;
  if (!halted_ && long_.op == Op::Home) s.mode = Mode::Homing;
  else if (!halted_ && long_.op != Op::None) s.mode = Mode::Busy;
  if (!halted_ && running()) {
    const JobRunner& j = *run();
    static const uint8_t kRun[] UV_FLASH = {static_cast<uint8_t>(Mode::Running), static_cast<uint8_t>(Mode::Paused),
                                            static_cast<uint8_t>(Mode::Done), static_cast<uint8_t>(Mode::Aborted),
                                            static_cast<uint8_t>(Mode::Aborted)};
    s.mode = static_cast<Mode>(uvFlashByte(&kRun[static_cast<uint8_t>(j.state())]));
    s.stop = j.done();
    s.stops = j.count();
    if (row == 4) s.remainingS = j.remainingS();
  }
  s.homed = axisHomed(0) && axisHomed(1);
  if (row == 1 || row == 2) {
    int32_t steps[3];
    motion_.positionSteps(steps);
    for (uint8_t a = row == 1 ? 0 : 2; a < (row == 1 ? 2 : 3); a++) s.um[a] = motion_.toUm(a, steps[a]);
  }
  s.nanoOnline = head_.online() && head_.tempsKnown();
  const int16_t* t = head_.deciC();
  for (uint8_t i = 1; i < uv::kSensorCount; i++)
    if (t[i] > t[s.hottest]) s.hottest = i;
  s.hottestDeciC = t[s.hottest];
  s.hottestLimitDeciC = static_cast<int16_t>(config_.milli(Key::ThermalLimit0 + s.hottest) / 100);
  s.fault = lastFault_;
  s.message = message_[0] ? message_ : nullptr;
  return s;
}

// Never inlined: the simavr rig measures the panel's CPU per pass from this function's entry.
__attribute__((noinline)) void Machine::panel() {
  uint32_t ms = msOf(now_);  // every pass of the main loop: no division (fast_div.h)
  uint8_t pressed = buttons_.sample(io_.buttons(), ms);
  if (pressed) button(pressed);
  if (screen_.due(ms)) screen_.draw(screenState(screen_.nextRow()), ms);  // a snapshot only when a row is due
}

void Machine::button(uint8_t pressed) {
  if (pressed & kButtonStop) {  // the e-stop: at once, whatever runs
    emergency();
    broadcastP(UV_P("echo:stop button: halted, send M999"));
    return;
  }
  if (halted_) return;
  if (pressed & kButtonPause) {
    if (running() && run()->state() == RunState::Running) {
      run()->pause(0);
    } else if (running() && run()->state() == RunState::Paused) {
      if (head_.online() && !head_.activeFaults() && !headHot(head_, config_)) run()->resume(now_);
    }
  }
  if ((pressed & kButtonHome) && long_.op == Op::None && !jobActive()) {
    homed_ = 0;
    io_.motorsEnabled(true);
    homing_.start(7);
    long_ = {};
    long_.op = Op::Home;
    long_.port = nullptr;  // no host line to answer
    long_.keepalive = now_ + kKeepaliveUs;
  }
}

Machine::Result Machine::message(HostLink&, const uv::Command& c) {
  uint8_t n = c.text ? c.textLen : 0;
  if (n > kScreenCols) n = kScreenCols;
  memcpy(message_, c.text, n);
  message_[n] = 0;
  return Result::Done;
}

}  // namespace mega
