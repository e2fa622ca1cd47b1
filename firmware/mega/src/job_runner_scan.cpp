// A scan job's passes in the job runner (issue 19): the stream's planner opens each pass and
// ScanRun exposes it on the move. Passes count as the job's stops. A pause, and the checks that
// come before every exposure, take effect between passes; a pass the Nano cut short cannot be
// exposed again from a stream (its rows are gone), so the job ends failed, dark and stopped.
#include "error_codes.h"
#include "job_runner.h"

namespace mega {

void JobRunner::pollScan(uint32_t nowUs) {
  if (!stopInHand_) {  // between passes (stopInHand_: a pass is under way)
    if (pauseWanted_) {
      pauseWanted_ = false;
      count(nowUs);
      phase_ = Phase::Load;  // on continue, the stream says Scan again and the next pass opens
      return halt(RunState::Paused, pauseReason_);
    }
    if (tooHot() || head_.activeFaults()) return fail(uv::kOverTemperature);
    if (!head_.online()) return fail(uv::kNanoTimeout);
    stopInHand_ = true;
  }
  switch (source_->scanStep(motion_, head_, nowUs)) {
    case ScanRun::Step::Busy:
      waiting_ = false;
      return;
    case ScanRun::Step::Starved:
      waiting_ = true;  // the rows of the next pass are on their way
      stopInHand_ = false;
      return;
    case ScanRun::Step::PassDone:
      stopInHand_ = false;
      done_++;
      progress_.done = done_;
      progress_.fires++;  // the Nano counts a chain as one exposure
      changed_ = true;
      return;
    case ScanRun::Step::End:
      stopInHand_ = false;
      count(nowUs);
      return halt(RunState::Done, 0);
    case ScanRun::Step::Failed: {
      const uint8_t code = source_->scanError();
      head_.allOff(code);
      motion_.stop();
      stopInHand_ = false;
      count(nowUs);
      return halt(RunState::Failed, code ? code : static_cast<uint8_t>(uv::kExposureRefused));
    }
  }
}

}  // namespace mega
