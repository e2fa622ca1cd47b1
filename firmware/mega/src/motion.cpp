// The main loop's side of motion: moves in µm become step blocks with trapezoidal profiles, fed to
// the step interrupt as segments; controlled and immediate stops; endstop seeks for homing.
#include "motion.h"

namespace mega {

namespace {
const Key kSteps[3] = {Key::StepsX, Key::StepsY, Key::StepsZ};
const Key kAccel[3] = {Key::AccelX, Key::AccelY, Key::AccelZ};

int32_t roundDiv(int64_t n, int64_t d) { return static_cast<int32_t>(n >= 0 ? (n + d / 2) / d : -((-n + d / 2) / d)); }
uint32_t absU(int32_t v) { return static_cast<uint32_t>(v < 0 ? -v : v); }
}  // namespace

int32_t Motion::toSteps(uint8_t axis, int32_t um) const {
  return roundDiv(static_cast<int64_t>(um) * c_.milli(kSteps[axis]), 1000000);
}

uint32_t Motion::stepsMilli(uint8_t axis) const { return static_cast<uint32_t>(c_.milli(kSteps[axis])); }

int32_t Motion::toUm(uint8_t axis, int32_t steps) const {
  return roundDiv(static_cast<int64_t>(steps) * 1000000, c_.milli(kSteps[axis]));
}

bool Motion::onBed(uint8_t axis, int32_t steps) const {
  return steps >= 0 && steps <= toSteps(axis, c_.milli(axis ? Key::BedY : Key::BedX));
}

uint32_t Motion::rateFor(uint8_t axis, int32_t milliMmS) const {
  // (mm/s × 1000) × (steps/mm × 1000) / 10⁶
  uint64_t r = static_cast<uint64_t>(milliMmS) * static_cast<uint64_t>(c_.milli(kSteps[axis])) / 1000000u;
  return r > kMaxStepRate ? kMaxStepRate : static_cast<uint32_t>(r);
}

AxisLimits Motion::limits(uint8_t axis, uint32_t feedUmS) const {
  int32_t vmax = c_.milli(axis == 2 ? Key::SpeedZ : Key::SpeedTravel);
  int32_t v = feedUmS && static_cast<int32_t>(feedUmS) < vmax ? static_cast<int32_t>(feedUmS) : vmax;
  uint64_t accel = static_cast<uint64_t>(c_.milli(kAccel[axis])) * static_cast<uint64_t>(c_.milli(kSteps[axis])) / 1000000u;
  return AxisLimits{rateFor(axis, v), static_cast<uint32_t>(accel)};
}

void Motion::positionUm(int32_t out[3]) const {
  int32_t s[3];
  e_.position(s);
  for (uint8_t a = 0; a < 3; a++) out[a] = toUm(a, s[a]);
}

void Motion::targetUm(int32_t out[3]) const {
  for (uint8_t a = 0; a < 3; a++) out[a] = toUm(a, target_[a]);
}

void Motion::setPositionSteps(const int32_t steps[3]) {
  e_.setPosition(steps);
  for (uint8_t a = 0; a < 3; a++) target_[a] = steps[a];
}

bool Motion::push(const int32_t delta[3], const AxisLimits lim[3], int8_t seekAxis) {
  if (!accepting() || (delta[1] && e_.gliding())) return false;
  StepBlock b{};
  uint32_t total = 0;
  for (uint8_t a = 0; a < 3; a++) {
    b.steps[a] = absU(delta[a]);
    if (delta[a] < 0) b.dirNeg |= static_cast<uint8_t>(1 << a);
    if (b.steps[a] > total) total = b.steps[a];
  }
  b.seekAxis = seekAxis;
  if (total == 0) return true;  // already there
  uint8_t slot = e_.pushBlock(b);
  profiles_[slot] = profileFor(b.steps, lim);
  for (uint8_t a = 0; a < 3; a++) target_[a] += delta[a];
  feed(true);  // a plain move's segments are quick to cut, each at least 2.5 ms long: no underrun
  return true;
}

bool Motion::moveTo(const int32_t um[3], uint32_t feedUmS) {
  int32_t delta[3];
  AxisLimits lim[3];
  for (uint8_t a = 0; a < 3; a++) {
    delta[a] = toSteps(a, um[a]) - target_[a];
    lim[a] = limits(a, feedUmS);
  }
  return push(delta, lim, -1);
}

bool Motion::moveToSteps(const int32_t steps[3]) {
  int32_t delta[3];
  AxisLimits lim[3];
  for (uint8_t a = 0; a < 3; a++) {
    delta[a] = steps[a] - target_[a];
    lim[a] = limits(a, 0);
  }
  return push(delta, lim, -1);
}

bool Motion::seek(uint8_t axis, int32_t steps, uint32_t rateStepsS) {
  int32_t delta[3] = {0, 0, 0};
  delta[axis] = steps;
  AxisLimits lim[3] = {limits(0, 0), limits(1, 0), limits(2, 0)};
  lim[axis].rate = rateStepsS;
  return push(delta, lim, static_cast<int8_t>(axis));
}

bool Motion::moveSteps(uint8_t axis, int32_t steps, uint32_t rateStepsS) {
  int32_t delta[3] = {0, 0, 0};
  delta[axis] = steps;
  AxisLimits lim[3] = {limits(0, 0), limits(1, 0), limits(2, 0)};
  lim[axis].rate = rateStepsS;
  return push(delta, lim, -1);
}

Profile Motion::strokeProfile(uint32_t steps, uint16_t interval, uint16_t frac) const {
  const uint32_t total[3] = {steps, 0, 0};
  AxisLimits lim[3] = {limits(0, 0), limits(1, 0), limits(2, 0)};
  // The whole-tick rate at or just above the exact one, so no ramp segment outruns the middle.
  const uint64_t exact = (static_cast<uint64_t>(interval) << 16) | frac;
  lim[0].rate = static_cast<uint32_t>(((static_cast<uint64_t>(kTickHz) << 16) + exact - 1) / exact);
  return profileFor(total, lim);
}

bool Motion::glides(int32_t dy) const {
  const AxisLimits y = limits(1, 0);
  uv::GlidePlan p;
  return uv::planGlide(absU(dy), y.rate, y.accel, p);
}

bool Motion::glide(int32_t dy) {
  if (stopping_ || e_.gliding() || e_.blocksMove(1)) return false;
  const AxisLimits y = limits(1, 0);
  uv::GlidePlan p;
  if (!uv::planGlide(absU(dy), y.rate, y.accel, p)) return false;
  const uint8_t n = static_cast<uint8_t>(absU(dy));
  e_.startGlide(uv::Glide{p.first, n, n}, dy < 0);
  target_[1] += dy;
  stepperKick();
  return true;
}

uint32_t Motion::strokeRampSteps(uint16_t interval, uint16_t frac) const { return strokeProfile(1, interval, frac).rampSteps; }

bool Motion::stroke(const Stroke& k) {
  if (!accepting() || strokeSlot_ >= 0 || k.steps == 0) return false;
  const uint32_t n = static_cast<uint32_t>(k.steps < 0 ? -k.steps : k.steps);
  StepBlock b{{n, 0, 0}, static_cast<uint8_t>(k.steps < 0 ? 1 : 0), -1};
  const uint8_t slot = e_.pushBlock(b);
  profiles_[slot] = strokeProfile(n, k.interval, k.frac);
  strokeSlot_ = static_cast<int8_t>(slot);
  strokeInterval_ = k.interval;
  strokeFrac_ = k.frac;
  strokeMark_ = k.markStep;
  midTicks_ = savedTicks_ = 0;
  fracAcc_ = 0;
  jumps_ = k.jumps;
  jumpCtx_ = k.ctx;
  jumpNext_ = 0;
  flying_ = false;
  nextJump();
  target_[0] += k.steps;
  feed();
  return true;
}

#ifndef __AVR__
void stepperKick() {}  // the host's rig starts its interrupt itself when work is queued
#endif

void Motion::feed(bool kickFirst) {
  while (e_.segmentFree()) {
    if (planSlot_ < 0) {
      if (nextPlan_ == e_.blockHead()) return;
      planSlot_ = static_cast<int8_t>(nextPlan_ % StepEngine::kBlocks);
      nextPlan_ = static_cast<uint8_t>(nextPlan_ + 1);
      planDone_ = 0;
    }
    const Profile& p = profiles_[planSlot_];
    Segment s = nextSegment(p, planDone_);
    uint16_t frac = 0;
    bool mark = false;
    if (planSlot_ == strokeSlot_) {
      // A stroke's middle runs at its exact interval; segments are cut where the ramps end and
      // where the mark is, so each is all ramp or all middle and the mark starts one.
      const uint32_t up = p.rampSteps, down = p.total > p.rampSteps ? p.total - p.rampSteps : 0;
      const uint32_t cuts[3] = {up, down, strokeMark_ ? strokeMark_ - 1 : 0};
      for (uint32_t c : cuts)
        if (c > planDone_ && c < planDone_ + s.steps) s.steps = static_cast<uint16_t>(c - planDone_);
      if (planDone_ >= up && planDone_ + s.steps <= down) strokeSegment(s.steps, s.steps, s.interval, frac);
      mark = strokeMark_ && planDone_ == strokeMark_ - 1;
    }
    bool last = planDone_ + s.steps >= p.total;
    if (last && planSlot_ == strokeSlot_) strokeSlot_ = -1;  // its every segment is queued
    if (!e_.pushSegment(static_cast<uint8_t>(planSlot_), s.steps, s.interval, last, frac, mark)) {
      planSlot_ = -1;  // a seek whose endstop closed: the rest of it is dropped
      continue;
    }
    planDone_ += s.steps;
    if (last) planSlot_ = -1;
    if (kickFirst) {  // a move from rest takes its first step while the rest are cut: 1 ms sooner
      kickFirst = false;
      stepperKick();
    }
  }
}

void Motion::forgetStroke() {
  strokeSlot_ = -1;
  flying_ = jumpHeld_ = false;
  jumps_ = nullptr;
}

void Motion::nextJump() {
  jumpHeld_ = jumps_ && jumps_(jumpCtx_, jumpNext_, jump_);
  if (jumpHeld_) jumpNext_++;
}

void Motion::strokeSegment(uint16_t most, uint16_t& steps, uint16_t& interval, uint16_t& frac) {
  const uint32_t exact = (static_cast<uint32_t>(strokeInterval_) << 16) | strokeFrac_;  // 16.16 ticks a step
  const uint32_t up = profiles_[planSlot_].rampSteps;
  while (!flying_ && jumpHeld_ && jump_.from < planDone_) nextJump();  // out of order, or behind: skipped
  // In 16.16 ticks from the middle's first step, when the step after the held stretch is due: where
  // the speed puts it, less what the stretches up to it save, as the plan counts (its windows) and
  // the Nano times its light.
  const bool near = flying_ || (jumpHeld_ && planDone_ == jump_.from);
  const uint64_t due = near ? (static_cast<uint64_t>(jump_.from) + jump_.steps - up) * exact - (static_cast<uint64_t>(savedTicks_ + (flying_ ? 0 : jump_.savedTicks)) << 16) : 0;
  if (near && !flying_) {
    const Profile& p = profiles_[planSlot_];
    if (jump_.steps == 0 || jump_.from + jump_.steps > p.total - up || jump_.savedTicks >= (static_cast<uint64_t>(jump_.steps) * exact >> 16)) {
      nextJump();  // not a stretch inside the middle that can be flown: crossed at the speed
      return strokeSegment(most, steps, interval, frac);
    }
    savedTicks_ += jump_.savedTicks;
    const float rate = 65536.0f / static_cast<float>(exact);
    const float accel = static_cast<float>(p.accel) / (static_cast<float>(kTickHz) * kTickHz);
    path_.plan(jump_.steps, static_cast<uint32_t>(due >> 16) - midTicks_, rate, accel);
    flying_ = true;
  }
  uint32_t ticks;  // what this segment's steps take, as the step interrupt counts them
  if (flying_) {
    // The next piece of the stretch: about a segment's time at its speed here, ending on the tick at
    // which the path reaches its last step.
    const uint32_t x = planDone_ - jump_.from, left = jump_.steps - x;
    const float dt = path_.at(x + 1) - path_.at(x);
    uint32_t k = static_cast<uint32_t>(static_cast<float>(2 * kSegmentUs) / (dt > 1 ? dt : 1));
    if (k < 1) k = 1;
    if (k > left) k = left;  // a stretch ends inside the middle: only its own end cuts it
    if (k > 0xffff) k = 0xffff;
    const uint32_t start = static_cast<uint32_t>(due >> 16) - path_.ticks();  // midTicks_ when it began
    const uint32_t end = x + k == jump_.steps ? path_.ticks() : static_cast<uint32_t>(path_.at(x + k) + 0.5f);
    ticks = start + end - midTicks_;
    // 16.16 ticks a step such that k steps, carrying from fracAcc_, take exactly `ticks`; the last
    // piece also leaves the carried fraction where the speed's would be, so the steps after the
    // stretch fall as if never interrupted (within a tick below the exact time, as everywhere).
    uint32_t phase = 0;
    if (x + k == jump_.steps) phase = static_cast<uint16_t>(due) < 0x10000 - k ? static_cast<uint16_t>(due) : 0x10000 - k;
    const uint32_t each = static_cast<uint32_t>(((static_cast<uint64_t>(ticks) << 16) + phase - fracAcc_ + k - 1) / k);
    steps = static_cast<uint16_t>(k);
    interval = static_cast<uint16_t>(each >> 16);
    frac = static_cast<uint16_t>(each);
    if (x + k == jump_.steps) {
      flying_ = false;
      nextJump();
    }
  } else {
    steps = most;
    if (jumpHeld_ && jump_.from > planDone_ && jump_.from < planDone_ + steps) steps = static_cast<uint16_t>(jump_.from - planDone_);
    interval = strokeInterval_;
    frac = strokeFrac_;
    ticks = static_cast<uint32_t>(steps) * interval + ((static_cast<uint32_t>(steps) * frac + fracAcc_) >> 16);
  }
  midTicks_ += ticks;
  fracAcc_ = static_cast<uint16_t>(fracAcc_ + static_cast<uint32_t>(steps) * frac);
}

void Motion::poll() {
  if (stopping_ && planSlot_ < 0 && e_.idle()) {
    stopping_ = false;
    e_.position(target_);  // the queued moves were dropped: the next one starts from here
  }
  feed();
}

void Motion::stop() {
  StepEngine::Cut c = e_.cutAfterCurrent();
  e_.dropBlocksAfter(c.running ? c.slot : 0xff);
  forgetStroke();  // a stroke cut short slows down as any move
  nextPlan_ = e_.blockHead();
  planSlot_ = -1;
  stopping_ = true;
  if (!c.running) return;
  Profile& p = profiles_[c.slot];
  uint32_t rate = kTickHz / c.interval;
  if (rate > p.rate) {  // faster than the move's cruise (a stroke's flown stretch): slow down from there
    p.rate = rate;
    const uint32_t ramp = stoppingSteps(p, rate);
    p.rampSteps = ramp < c.done ? ramp : c.done;
  }
  uint32_t end = c.done + stoppingSteps(p, rate);
  if (end >= p.total) {
    // It would not stop sooner than it ends: keep cutting it as it was.
    if (c.done < p.total) {
      planSlot_ = static_cast<int8_t>(c.slot);
      planDone_ = c.done;
    }
  } else {
    // Shorten the move: from here the profile's nearer end is the new one, so it decelerates.
    p.total = end;
    planSlot_ = static_cast<int8_t>(c.slot);
    planDone_ = c.done;
  }
  feed();
}

void Motion::halt() {
  e_.halt();
  forgetStroke();
  nextPlan_ = e_.blockHead();
  planSlot_ = -1;
  stopping_ = false;
  e_.position(target_);
}

}  // namespace mega
