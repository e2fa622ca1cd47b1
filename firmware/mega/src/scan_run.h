// Runs a scan job's passes (issue 19; protocol/nano.md "Scan programs"), one at a time as the scan
// planner opens them: to the pass's start, its first two programs loaded and armed on the Nano, the
// stroke queued with its G on the marked step, the rest of the chain sent as the Nano's buffers
// free up (asked by Q when the program before them is due to end, and every 10 ms, which also keeps
// the chain from being cut as silent), and the pass confirmed whole by the Nano's Q (asked as its
// last event is due) and its dose reported before the next opens, while the stroke runs out: a hop
// in Y alone to the next pass glides beside that run-out (protocol/planner.md "Gliding").
#pragma once
#include <stdint.h>

#include "config.h"
#include "motion.h"
#include "printhead_link.h"
#include "scan.h"
#include "scan_program.h"
#include "scan_stroke.h"

namespace mega {

constexpr uint32_t kScanPollUs = 10000;      // Q while a chain runs: well inside the Nano's 50 ms
// Once the chain is written: the first Q this long after its last event is due (the Nano's loop
// marks the pass whole on its next turn), then one this often until the answer says whole.
constexpr uint32_t kScanEndMarginUs = 200;
constexpr uint32_t kScanEndPollUs = 1000;
// From the step that writes the G to the chain's time 0: the G and its newline (two bytes at 115200
// baud), then the Nano's lead.
constexpr uint32_t kScanStartUs = 174 + uv::kProgramStartLeadUs;
constexpr uint32_t kScanSettleUs = 50000;    // after the stroke, the chain must have ended by then
// A pass waits this long at most for the Nano's clock (known 2 s after the Nano answers W) and for the
// link at the plan's speed (the job's linkBaud: raised again within kSpeedRetryUs of a fall-back). A
// Nano that never answers W cannot run a scan job (E29, no light); a link that stays below the plan's
// speed ends the job with E34 (a job planned at 115200, as with a Nano that never takes L, never waits).
constexpr uint32_t kScanClockWaitUs = 10000000;

class ScanRun {
 public:
  explicit ScanRun(uv::ScanPlanner& planner)
      : planner_(planner), lines_(source, this), sealSent_(false), written_(false), asked_(false), loading_(false), moved_(false), clockWaiting_(false),
        afterStroke_(false) {}

  // Stops: a mixed job's pass opened as stops (planner.md "Mixed mode"): the job runner takes them
  // from the planner's nextStop(), and the next poll opens the pass after it.
  enum class Step : uint8_t { Busy, Starved, PassDone, End, Failed, Stops };
  // `h`: the job (its origin and pitch place each pass on the bed). `kept`: the pass it may open as
  // planning kept it (a card job's: ScanPlanner::nextPass), else null.
  Step poll(Motion& motion, PrintheadLink& head, const uv::JobHeader& h, uint32_t nowUs, const uv::KeptPass* kept = nullptr);
  // Why it failed: an error code (29 the speed is out of the step engine's range or the Nano's clock
  // could not be measured, 34 the link stayed below the plan's speed, 30 the Nano went
  // silent before a pass, 31 the Nano cut the chain for a fault, 33 the Nano refused or cut it
  // otherwise).
  uint8_t error() const { return error_; }
  // Between passes, and not failed: the next poll opens the next pass.
  bool idle() const { return phase_ == Phase::Open && !error_; }
  uint16_t passes() const { return passes_; }
  // For the tests: the last stroke.
  const StrokePlan& stroke() const { return stroke_; }

 private:
  enum class Phase : uint8_t { Open, Load, Arm, Run, Finish, Drain };
  static bool source(void* ctx, uint32_t& t, uint8_t& m);
  static bool jumpAt(void* ctx, uint8_t i, Motion::StrokeJump& out);
  // What open() found: no pass (starved, or the end), a pass on the move, or a mixed job's stop pass.
  enum class Opened : uint8_t { None, Stroke, Stops };
  Opened open(Motion& motion, const uv::JobHeader& h, uint32_t linkBaud, const uv::KeptPass* kept);
  // Sends the chain's lines up to the end of one program; true once its K is answered 0.
  bool sendProgram(PrintheadLink& head, uint32_t nowUs);
  // The chain's next line into line_, unless one is held already; false once every line is written.
  bool take();
  // The held line's start: the chain's time just before its first event, Nano µs after time 0.
  uint32_t lineStartUs() const;
  // When the next buffer frees on the Nano, by this clock: as the program before the newest sent ends.
  uint32_t freeAt() const { return start_ + NanoClock::toNano(older_, -clockRate_); }
  // When the Nano's pass is whole, by this clock: its last event, and a margin (kScanEndMarginUs).
  uint32_t chainEnd() const { return start_ + NanoClock::toNano(lines_.lastUs(), -clockRate_) + kScanEndMarginUs; }
  Step fail(PrintheadLink& head, uint8_t code);

  uv::ScanPlanner& planner_;
  uv::ProgramLines lines_;
  char line_[uv::kNanoMaxLine + 2];
  uint8_t held_ = 0;          // a line taken from lines_, not sent yet
  // One byte for the seven (the Mega's static RAM holds a ScanJob twice: card_scan.h, stream_job.h).
  bool sealSent_ : 1;         // its K went out; its answer is awaited
  bool written_ : 1;          // the chain's every line has gone
  bool asked_ : 1;            // a Q is out: its answer is awaited
  bool loading_ : 1;          // a Q found a buffer free: the next program goes out
  bool moved_ : 1;            // the move to the pass's start is queued
  bool clockWaiting_ : 1;     // Open: waiting for the Nano's clock
  bool afterStroke_ : 1;      // the last pass was a stroke: the hop to the next glides (planner.md "Gliding")
  uint8_t armed_ = 0;         // programs answered K:0 before the stroke
  Phase phase_ = Phase::Open;
  uint8_t marks_ = 0, missed_ = 0;  // the step engine's counts before the stroke
  uint8_t error_ = 0;
  uint16_t passes_ = 0;
  uint32_t nextPoll_ = 0, until_ = 0;
  int32_t y_ = 0;
  int32_t clockRate_ = 0;  // the Nano's clock when the pass opened, as NanoClock::rate (nano_clock.h)
  union {
    uint32_t clockWaitFrom_ = 0;  // Open: when this pass began to wait for the Nano's clock
    uint32_t start_;              // Finish: the chain's time 0 by this clock (its G seen, so a little late)
  };
  uint32_t older_ = 0;  // the end of the program before the newest one sent, Nano µs after time 0
  StrokePlan stroke_ = {};
};

// A scan job's planner and the runner of its passes, together. The stroke flies the stretches the
// planner flies (Motion::StrokeJump).
struct ScanJob {
  // A band is priced a pass a main-loop pass (ScanPlanner::sliceBands): ScanRun waits it out. A scan
  // pass is not priced (ScanPlanner::unpriced): the run has its own stroke and hop, and the job's
  // time was planned at M29 (or is not known, a stream's).
  ScanJob(const uv::JobHeader& h, uv::CellSource& cells, const uv::MotionModel& m) : planner(h, cells, m), run(planner) {
    planner.sliceBands();
    planner.unpriced();
  }
  uv::ScanPlanner planner;
  ScanRun run;
};

}  // namespace mega
