// A scan job's passes in the job runner (issue 19): the planner opens each pass (the stream's, or
// the card job's own, card_scan.h) and ScanRun exposes it on the move; a mixed job's stop pass
// (issue 28) goes back to the stop-by-stop phases, its stops from the stream's planner. Passes count as the job's
// stops, and a card job checkpoints after each. A pause, the checks that come before every
// exposure and a paced job's wait to cool (mega.md "Pacing") take effect between passes. A pass the Nano cut short is exposed again on continue
// from the card; a stream cannot (its rows are gone), so it ends failed, dark and stopped.
#include "error_codes.h"
#include "job_runner.h"

namespace mega {

void JobRunner::pollScan(uint32_t nowUs) {
  if (!stopInHand_) {  // between passes (stopInHand_: a pass is under way)
    if (!doseSettled()) return;  // a mixed job's stop before: its record first
    if (pauseWanted_) {
      pauseWanted_ = false;
      count(nowUs);
      phase_ = Phase::Load;  // on continue, the stream says Scan again and the next pass opens
      return halt(RunState::Paused, pauseReason_);
    }
    if (uint8_t why = exposureBlocked()) return fail(why);
    if (paced_ && paceWaits(false)) {
      phase_ = Phase::Cool;  // before the pass and its move, LEDs off, until the readings show it cool
      changed_ = true;
      return;
    }
    stopInHand_ = true;
    doseStarts();  // its programs' records, as they end
    lit_ = false;              // no F: its records carry no plan
  }
  StopSource& passes = card_ ? *static_cast<StopSource*>(card_) : *source_;
  switch (passes.scanStep(motion_, head_, nowUs)) {
    case ScanRun::Step::Busy:
      waiting_ = false;
      return;
    case ScanRun::Step::Starved:
      waiting_ = true;  // the rows of the next pass are on their way
      stopInHand_ = false;
      return;
    case ScanRun::Step::Stops:
      stopInHand_ = false;
      phase_ = Phase::Load;  // a mixed job's stop pass: its stops come from the source, stop by stop
      return;
    case ScanRun::Step::PassDone:
      stopInHand_ = false;
      doseFor_ = DoseFor::None;
      done_++;
      progress_.done = done_;
      progress_.fires++;  // the Nano counts a chain as one exposure
      changed_ = true;
      // The pass's records are in (ScanRun waits for them): its dose file reaches the directory too.
      if (card_ && (!checkpoint_.write(progress_) || (dose_ >= 0 && !sd_.sync(dose_)))) return fail(uv::kFileError);
      return;
    case ScanRun::Step::End:
      stopInHand_ = false;
      count(nowUs);
      if (card_) checkpoint_.clear();
      return halt(RunState::Done, 0);
    case ScanRun::Step::Failed: {
      const uint8_t code = passes.scanError();
      stopInHand_ = false;
      if (card_) {
        phase_ = Phase::Load;  // on continue: the pass again, planned afresh
        return fail(code ? code : static_cast<uint8_t>(uv::kExposureRefused));
      }
      doseFor_ = DoseFor::Cut;  // what the cut pass gave, reported: a stream's pass is not run again
      head_.requestDose();
      head_.allOff(code);
      motion_.stop();
      stopInHand_ = false;
      count(nowUs);
      return halt(RunState::Failed, code ? code : static_cast<uint8_t>(uv::kExposureRefused));
    }
  }
}

}  // namespace mega
