// A scan job's passes on the machine: see scan_run.h.
#include "scan_run.h"

#include "error_codes.h"

namespace mega {

namespace {
bool due(uint32_t now, uint32_t at) { return static_cast<int32_t>(now - at) >= 0; }
}  // namespace

bool ScanRun::source(void* ctx, uint32_t& t, uint8_t& m) {
  ScanRun* s = static_cast<ScanRun*>(ctx);
  if (!s->planner_.nextEvent(t, m)) return false;
  t += s->stroke_.shiftUs;  // the plan's time 0 falls this long after the Nano's
  // As the Nano's clock counts it. Its time 0 is kProgramStartLeadUs of its own µs after the G's
  // newline, where this plan put it that many of the Mega's: so the lead is scaled with the times.
  t = NanoClock::toNano(t + uv::kProgramStartLeadUs, s->clockRate_) - uv::kProgramStartLeadUs;
  return true;
}

bool ScanRun::jumpAt(void* ctx, uint8_t i, Motion::StrokeJump& out) {
  ScanRun* s = static_cast<ScanRun*>(ctx);
  if (i >= s->planner_.jumps()) return false;
  uint32_t window, windows, flyUs;
  s->planner_.jump(i, window, windows, flyUs);
  strokeJump(s->stroke_, s->planner_.passMotion().windowUs, window, windows, flyUs, out.from, out.steps, out.savedTicks);
  return true;
}

ScanRun::Step ScanRun::fail(PrintheadLink& head, uint8_t code) {
  head.hold(false);
  error_ = code;
  return Step::Failed;
}

ScanRun::Opened ScanRun::open(Motion& motion, const uv::JobHeader& h, uint32_t linkBaud, const uv::KeptPass* kept) {
  uv::ScanPass p;
  if (!planner_.nextPass(p, kept)) {
    if (planner_.refused()) error_ = uv::kScanUnsupported;  // a window the step engine cannot run
    return planner_.refused() ? Opened::Stroke : Opened::None;
  }
  if (p.stops) return Opened::Stops;  // a mixed job's pass of stops: the job runner exposes them
  const int32_t pitch = static_cast<int32_t>(h.pitchUm[0]), dir = p.descending ? -1 : 1;
  const int32_t x0 = static_cast<int32_t>(h.originUm[0]);
  // Window 0's column and the last window's, in the pass's direction.
  const int32_t firstX = x0 + (p.descending ? p.last : p.first) * pitch;
  const int32_t lastX = x0 + (p.descending ? p.first : p.last) * pitch;
  StrokeInput in{};
  in.markX2Um = 2 * firstX - dir * pitch;
  in.endX2Um = 2 * lastX + dir * pitch;
  in.descending = p.descending;
  in.windowUs = planner_.passMotion().windowUs;  // the pass's own: the link cap may slow it
  in.pitchUm = h.pitchUm[0];
  in.stepsMilli = motion.stepsMilli(0);
  in.linkBaud = linkBaud;  // the G's two bytes take their time at it
  uint16_t interval = 0, frac = 0;
  if (!strokeInterval(in.windowUs, in.pitchUm, in.stepsMilli, interval, frac)) {
    error_ = uv::kScanUnsupported;
    return Opened::Stroke;
  }
  in.rampSteps = motion.strokeRampSteps(interval, frac);
  if (!planStroke(in, stroke_)) {  // a pass of 35 minutes or more (M29 refuses such a job first)
    error_ = uv::kScanUnsupported;
    return Opened::Stroke;
  }
  y_ = static_cast<int32_t>(h.originUm[1]) + p.hy * static_cast<int32_t>(h.pitchUm[1]);
  lines_ = uv::ProgramLines(source, this);
  held_ = 0;
  sealSent_ = written_ = moved_ = false;
  armed_ = 0;
  return Opened::Stroke;
}

bool ScanRun::take() {
  if (held_) return true;
  if ((held_ = lines_.next(line_))) return true;
  written_ = true;
  if (lines_.failed()) error_ = uv::kScanUnsupported;  // a gap of 2²⁸ µs or more
  return false;
}

uint32_t ScanRun::lineStartUs() const {
  uint32_t t = lines_.lastUs();
  uv::AppendLine a;
  uint32_t d;
  uint8_t m;
  if (a.begin(line_, static_cast<uint8_t>(held_ - 1)))
    while (a.next(d, m)) t -= d;
  return t;
}

bool ScanRun::sendProgram(PrintheadLink& head, uint32_t nowUs) {
  for (;;) {
    if (sealSent_) {
      if (!head.sealAnswered()) return false;
      sealSent_ = false;
      if (head.sealCode() != 0) {
        error_ = uv::kExposureRefused;
        return false;
      }
      return true;
    }
    if (!take()) return false;
    const bool seal = line_[0] == 'K';
    if (!head.programLine(line_, held_, nowUs)) return false;  // the UART is full or a request waits
    if (line_[2] == '0' && line_[3] == ',') older_ = lineStartUs();  // a program's first line (B:0,)
    held_ = 0;
    sealSent_ = seal;
  }
}

ScanRun::Step ScanRun::poll(Motion& motion, PrintheadLink& head, const uv::JobHeader& h, uint32_t nowUs, const uv::KeptPass* kept) {
  if (error_) return Step::Failed;
  switch (phase_) {
    case Phase::Open: {
      // The Nano's clock must be known before a pass: its light runs on it (nano_clock.h). And the
      // link must be as fast as the plan counts on (its programs would come late): after a fall-back
      // to 115200 the link is raised again once idle (kSpeedRetryUs), which this waits for.
      if (!head.online()) return fail(head, uv::kNanoTimeout);
      if (!head.nanoClock().known() || head.baud() < planner_.linkBaud()) {
        if (!clockWaiting_) {
          clockWaiting_ = true;
          clockWaitFrom_ = nowUs;
        }
        if (!due(nowUs, clockWaitFrom_ + kScanClockWaitUs)) return Step::Busy;
        // The clock never came (a Nano from before W), or the link stays slower than the plan counts
        // on: the raise failed since the job was planned (E34; protocol/nano.md "Link speed").
        return fail(head, head.nanoClock().known() ? uv::kLinkSpeed : uv::kScanUnsupported);
      }
      clockWaiting_ = false;
      if (head.switching()) return Step::Busy;  // the link's speed is settling: it times the G
      clockRate_ = NanoClock::rate(head.nanoClock().ppm());
      const Opened opened = open(motion, h, head.baud(), kept);
      if (opened == Opened::None && planner_.pricing()) return Step::Busy;  // a band priced a pass at a time: open again
      if (opened == Opened::None && planner_.starved()) return Step::Starved;
      if (opened == Opened::None) return motion.idle() ? Step::End : Step::Busy;  // the last stroke at rest
      if (error_) return fail(head, error_);
      if (opened == Opened::Stops) {
        afterStroke_ = false;  // its stops leave the head at rest
        return Step::Stops;    // stays Open: the pass after it opens next
      }
      phase_ = Phase::Load;
      return Step::Busy;
    }
    case Phase::Load: {
      if (!moved_) {
        int32_t to[3];
        motion.targetSteps(to);  // Z stays where the job put it; X and Y where the queued moves end
        const int32_t dy = motion.toSteps(1, y_) - to[1];
        to[0] = stroke_.startSteps;
        to[1] += dy;
        // The whole stroke, run-up and run-out included, on the bed, or the head never sets off.
        if (!motion.onBed(0, to[0]) || !motion.onBed(0, to[0] + stroke_.steps) || !motion.onBed(1, to[1])) return fail(head, uv::kSoftLimit);
        // After a stroke, a hop in Y that can glide does so at once, beside its run-out (protocol/
        // planner.md "Gliding"), and X's part goes in the queue behind it on the next poll.
        if (afterStroke_ && dy != 0 && motion.glides(dy)) motion.glide(dy);
        else moved_ = motion.moveToSteps(to);
      }
      // Two programs armed before the head sets off (the Nano's two buffers), or the whole chain.
      while (armed_ < 2 && !written_) {
        if (!sendProgram(head, nowUs)) break;
        armed_++;
      }
      if (error_) return fail(head, error_);
      if (!moved_ || !motion.idle() || (armed_ < 2 && !written_)) return Step::Busy;
      phase_ = Phase::Arm;
      return Step::Busy;
    }
    case Phase::Arm:
      if (armed_ == 0) {  // a pass whose chain is empty cannot happen: the planner drops dark passes
        phase_ = Phase::Open;
        return Step::PassDone;
      }
      head.hold(true);  // from here until the G is out, nothing else goes to the Nano
      marks_ = motion.engine().marks();
      missed_ = motion.engine().marksMissed();
      if (!motion.stroke({stroke_.steps, stroke_.interval, stroke_.frac, stroke_.markStep, &ScanRun::jumpAt, this})) return fail(head, uv::kExposureRefused);
      phase_ = Phase::Run;
      return Step::Busy;
    case Phase::Run:
      if (motion.engine().marks() == marks_) {
        if (motion.idle()) return fail(head, uv::kExposureRefused);  // the stroke ended unmarked
        return Step::Busy;
      }
      head.hold(false);
      if (motion.engine().marksMissed() != missed_) return fail(head, uv::kExposureRefused);  // the UART was busy
      phase_ = Phase::Finish;
      asked_ = loading_ = false;
      until_ = 0;
      nextPoll_ = nowUs;
      start_ = nowUs + kScanStartUs - kMarkLeadUs + stroke_.leadUs;
      return Step::Busy;
    case Phase::Finish: {
      head.hold(!written_);  // no T, E or W in the way of the Q while programs wait to go
      if (asked_ && head.passAnswered()) {
        asked_ = false;
        const uint8_t state = head.passState();
        if (state >= static_cast<uint8_t>(uv::PassState::CutByReset)) {
          return fail(head, state == static_cast<uint8_t>(uv::PassState::CutByFault) ? uv::kOverTemperature : uv::kExposureRefused);
        }
        if (!written_ && head.passFree() > 0) loading_ = true;  // a buffer is free: the next program
        head.holdDose(loading_);  // until that program is armed
        // The programs that have ended, reported (protocol/mega.md "Dose reports"): the Nano keeps two
        // records, and a program cannot end sooner than the next one loads, so one O after each Q, or
        // once the program it made way for is armed, keeps up. A program waiting to go goes first.
        if (!loading_) head.requestDose();
        if (written_ && state == static_cast<uint8_t>(uv::PassState::Whole)) {
          head.requestDose();  // the last program's record: the pass counts once it is reported
          phase_ = Phase::Drain;
          return Step::Busy;
        }
      }
      if (loading_) {
        const bool armed = sendProgram(head, nowUs);
        if (armed || written_) loading_ = false;
        if (error_) return fail(head, error_);
        if (armed) {  // its O before the next Q, which waits for the answer
          head.holdDose(false);
          head.requestDose();
          return Step::Busy;
        }
      }
      // A program waits for a buffer: Q as the one before it ends (not just before, which would
      // only learn it is not yet free), then again as each answer comes until one is, so the program
      // goes out within the relay the planner allows (planner.md "The printhead link"); its first
      // line is made ready meanwhile (the planner takes milliseconds over a line's events).
      if (!written_ && !loading_ && take()) {
        const uint32_t at = freeAt();
        if (!due(nowUs, at)) {
          if (due(nextPoll_, at - kScanPollUs / 5)) nextPoll_ = at;
        } else if (!due(nowUs, nextPoll_)) {
          nextPoll_ = nowUs;
        }
      }
      // Every line out: the pass is whole with its last event, most often while the stroke still runs
      // out. Q as that event is due, not up to a poll later, then every kScanEndPollUs until it is.
      uint32_t pollEvery = kScanPollUs;
      if (written_) {
        const uint32_t end = chainEnd();
        if (!due(nowUs, end)) {
          if (due(nextPoll_, end)) nextPoll_ = end;
        } else {
          pollEvery = kScanEndPollUs;
        }
      }
      // No Q while a program goes out: its K would wait behind the answer, and its lines keep the
      // chain from being cut as silent as the Q does.
      if (!asked_ && !loading_ && due(nowUs, nextPoll_)) {
        head.requestPass();
        asked_ = true;
        nextPoll_ = nowUs + pollEvery;
      }
      if (motion.idle()) {
        if (!until_) until_ = nowUs + kScanSettleUs;
        else if (due(nowUs, until_)) return fail(head, uv::kExposureRefused);  // the chain never ended
      }
      return Step::Busy;
    }
    case Phase::Drain:
      head.hold(false);
      // Whole and reported. The stroke may still be running out, but every segment of it is queued,
      // so the next pass may open (its jumps replace this one's) and its hop glide beside it.
      if (!head.doseDrained() || motion.cuttingStroke()) return Step::Busy;
      passes_++;
      afterStroke_ = true;
      phase_ = Phase::Open;
      return Step::PassDone;
  }
  return Step::Busy;
}

}  // namespace mega
