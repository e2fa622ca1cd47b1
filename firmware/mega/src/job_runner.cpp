// Runs a planned job from its stop file, stop by stop, with a checkpoint after each confirmed one.
#include "job_runner.h"

#include <new>
#include <string.h>

#include "error_codes.h"
#include "job_files.h"
#include "job_plan.h"
#include "progmem.h"

namespace mega {

namespace {
constexpr uint32_t kNanoCapUs = 10000000;  // protocol/nano.md: a longer duration is refused, never clamped there
constexpr uint32_t kDoseSyncStops = 16;
bool due(uint32_t now, uint32_t at) { return static_cast<int32_t>(now - at) >= 0; }
}  // namespace

JobRunner::~JobRunner() {
  if (card_) card_->~CardScan();
  if (stops_ >= 0) sd_.close(stops_);
  if (dose_ >= 0) sd_.close(dose_);  // not kDoseRefused: closed already
  checkpoint_.close();
}

uint8_t JobRunner::start(const char* name, uint32_t from, uint32_t nowUs) {
  char work[kWorkNameMax + 1];
  workFileName(name, JobFile::Stops, work);
  stops_ = sd_.open(work, Storage::Mode::Read);
  if (stops_ < 0) return uv::kFileNotFound;
  if (!readStopHeader(sd_, stops_, header_) || from > header_.count) return uv::kFileError;
  if (header_.scan) {
    uv::JobHeader job;
    uint32_t linkBaud;  // the speed it was planned at: it runs and resumes at it
    uint32_t kept;      // its passes as planning kept them, in the index file
    if (!readScanHeader(sd_, stops_, job, linkBaud, kept) || !scanMem_ || scanBytes_ < sizeof(CardScan)) return uv::kFileError;
    // Its passes are planned again from the cells as they run: the stop file is done with, and its
    // place is another's (kCardFiles: the cells, their index, the checkpoint and the dose file).
    sd_.close(stops_);
    stops_ = -1;
    card_ = new (scanMem_) CardScan(sd_, job, plannerMachine(config_, 0, 0, linkBaud), header_.count, kept);
    const uint8_t err = card_->open(name);
    if (err) return err;
  }
  // The run's dose file: afresh from the first stop, added to from a later one (a resume).
  workFileName(name, JobFile::Dose, work);
  dose_ = sd_.open(work, from ? Storage::Mode::Update : Storage::Mode::Create);
  if (dose_ < 0 || !sd_.seek(dose_, sd_.size(dose_))) return uv::kFileError;
  strncpy(progress_.file, name, kFileNameMax);
  progress_.file[kFileNameMax] = 0;
  progress_.count = header_.count;
  progress_.done = done_ = from;
  int32_t here[3];
  motion_.targetUm(here);
  zBase_ = here[2];
  state_ = RunState::Running;
  phase_ = Phase::Sync;  // the Nano's counters first: each checkpoint carries them
  head_.requestCounters();
  since_ = nowUs;
  changed_ = true;
  return 0;
}

void JobRunner::startStream(StopSource& source, const uv::JobHeader& header, uint32_t nowUs) {
  source_ = &source;
  streamHeader_ = &header;
  uvMemcpyP(progress_.file, UV_P("stream"), 7);  // from flash: a literal here would sit in RAM
  progress_.done = done_ = 0;
  int32_t here[3];
  motion_.targetUm(here);
  zBase_ = here[2];
  state_ = RunState::Running;
  phase_ = Phase::Drain;  // records from before the stream are no stop's
  head_.requestDose();
  since_ = nowUs;
  changed_ = true;
}

uint8_t JobRunner::resume(const Progress& checkpoint, uint32_t nowUs) {
  uint8_t err = start(checkpoint.file, checkpoint.done, nowUs);
  if (err) return err;
  if (checkpoint.count != header_.count) return uv::kFileError;  // replanned since: not the same stops
  doseFor_ = DoseFor::Resuming;
  checkpointed_ = {checkpoint.done, checkpoint.boot, checkpoint.fires};
  return 0;
}

uint32_t JobRunner::remainingS() const {
  if (source_ || !header_.count || done_ >= header_.count) return 0;
  return static_cast<uint32_t>(static_cast<uint64_t>(header_.estimateS) * (header_.count - done_) / header_.count);
}

void JobRunner::keepDose(const char* line) {
  if (dose_ < 0) return;
  if (sd_.write(dose_, line, static_cast<uint16_t>(strlen(line))) && sd_.write(dose_, "\n", 1)) return;
  sd_.close(dose_);
  // Failed by the next poll: this runs inside the printhead link's record sink, which the failure
  // (LEDs off, the cut record asked for) must not re-enter.
  dose_ = kDoseRefused;
}

void JobRunner::halt(RunState s, uint8_t reason) {
  if (dose_ >= 0) {
    if (s == RunState::Done || s == RunState::Aborted) {  // its last record is in (doseSettled)
      sd_.close(dose_);
      dose_ = -1;
    } else {
      sd_.sync(dose_);  // what it holds so far survives a power cut; a paused job's records go on
    }
  }
  state_ = s;
  reason_ = reason;
  changed_ = true;
}

void JobRunner::fail(uint8_t code) {
  // The light the Nano gave the stop (or pass) under way before the cut is reported as cut: the stop
  // is exposed again from its start on continue, and that exposure is its light again.
  if (doseFor_ == DoseFor::Stop || doseFor_ == DoseFor::StopAgain) {
    doseFor_ = DoseFor::Cut;
    head_.requestDose();
  }
  head_.allOff(code);
  motion_.stop();
  count(now_);
  halt(RunState::Paused, code);  // the checkpoint stays: continue, or resume after a reset
}

void JobRunner::pause(uint8_t reason) {
  if (state_ != RunState::Running) return;
  pauseWanted_ = true;
  pauseReason_ = reason;
}

void JobRunner::resume(uint32_t nowUs, bool coolFirst) {
  if (state_ != RunState::Paused) return;
  pauseWanted_ = false;
  reason_ = 0;
  if (coolFirst) phase_ = Phase::CoolFirst;  // nothing moves, nothing is read, until it is cool
  else continueAfterPause();
  since_ = nowUs;
  state_ = RunState::Running;
  changed_ = true;
}

void JobRunner::continueAfterPause() {
  // A stop that failed is exposed again from its start: it was not confirmed. The Nano's count is
  // read again first, since a failed exposure may or may not have been counted.
  phase_ = source_ ? Phase::Load : Phase::Sync;  // a stream keeps the stop in hand: moved to, exposed again
  if (!source_) head_.requestCounters();
}

void JobRunner::abort() {
  head_.allOff();
  motion_.stop();
  if (!source_) checkpoint_.clear();
  if (stops_ >= 0) sd_.close(stops_);
  stops_ = -1;
  halt(RunState::Aborted, 0);
}

uint32_t JobRunner::compensate(uint8_t led, uint32_t us) const {
  // job.md: t' = round(t × (100000 + c × (T − ref)) / 100000), T from the sensor beside LED i.
  int32_t c = header_.thermalCoeff;
  if (!c || !us) return us;
  int64_t factor = 100000 + static_cast<int64_t>(c) * (head_.deciC()[led] - header_.thermalRefDeciC);
  if (factor <= 0) return 0;
  uint64_t t = (static_cast<uint64_t>(us) * static_cast<uint64_t>(factor) + 50000) / 100000;
  return t > kNanoCapUs ? kNanoCapUs : static_cast<uint32_t>(t);
}

void JobRunner::count(uint32_t nowUs) {
  elapsedUs_ += nowUs - since_;
  since_ = nowUs;
  elapsedS_ += elapsedUs_ / 1000000;
  elapsedUs_ %= 1000000;
}

bool JobRunner::doseSettled() {
  if (doseFor_ != DoseFor::Done && doseFor_ != DoseFor::DoneAgain) return true;
  if (!head_.doseDrained()) return false;
  doseFor_ = DoseFor::None;
  return true;
}

void JobRunner::confirmed(uint32_t nowUs) {
  stopInHand_ = false;
  if (doseFor_ != DoseFor::Done && doseFor_ != DoseFor::DoneAgain) doseFor_ = DoseFor::None;
  done_++;
  progress_.done = done_;
  if (lit_) progress_.fires++;  // the Nano counted it
  if (!source_ && !checkpoint_.write(progress_)) return fail(uv::kFileError);
  // A card job's dose file reaches the card's directory every kDoseSyncStops stops (and at each
  // stop of the job: halt), not at every stop: a sync is a card write or two, of a stop's 20 ms.
  if (dose_ >= 0 && done_ % kDoseSyncStops == 0 && !sd_.sync(dose_)) return fail(uv::kFileError);
  phase_ = Phase::Load;
  // A stream's next stop is loaded in this same pass: a pass is about 200 µs on the board. A card
  // job's has the checkpoint's write behind it in this one, and waits for the next.
  if (source_) poll(nowUs);
}

bool JobRunner::attribute(const uv::NanoReply& r, uv::DoseReport& d) {
  if (doseFor_ == DoseFor::None || doseFor_ == DoseFor::Again || doseFor_ == DoseFor::Resuming) return false;
  d = uv::DoseReport{};
  d.exposure = r.exposure;
  d.program = r.program;
  memcpy(d.onUs, r.onUs, sizeof d.onUs);
  d.cut = doseFor_ == DoseFor::Cut || doseFor_ == DoseFor::CutResumed;
  if (phase_ == Phase::Drain) {
    // Found at a resume: only the exposure the checkpoint expected next is the stop that was next.
    if (r.exposure != checkpointed_.fires + 1) return false;
    d.stop = checkpointed_.done;
    return true;
  }
  // A card job knows the Nano's count (read at its start and after every pause): its stop's exposure
  // is the next, or, for the stop just confirmed, the last. An older record was no stop's of this job.
  const bool confirmed = doseFor_ == DoseFor::Done || doseFor_ == DoseFor::DoneAgain;
  if (!source_ && r.exposure != progress_.fires + (confirmed ? 0 : 1)) return false;
  d.stop = confirmed ? done_ - 1 : done_;
  d.again = doseFor_ == DoseFor::StopAgain || doseFor_ == DoseFor::DoneAgain;
  if (d.cut && lit_) {  // a cut F: what it was to give, compensated as it was (readings change twice a second)
    d.hasPlan = true;
    for (uint8_t i = 0; i < 4; i++) d.planUs[i] = compensate(i, stop_.us[i]);
  }
  return true;
}

void JobRunner::poll(uint32_t nowUs) {
  now_ = nowUs;
  if (dose_ == kDoseRefused) {
    dose_ = -1;
    if (state_ == RunState::Running || state_ == RunState::Paused) return fail(uv::kFileError);
  }
  if (state_ != RunState::Running) return;
  count(nowUs);  // every pass: a job outlasts the 71 minutes a 32-bit µs count holds
  switch (phase_) {
    case Phase::Sync: {
      if (!head_.online()) return fail(uv::kNanoTimeout);
      // A cut stop's records are its own, counted against the count before it: reported first.
      if (!head_.countersAnswered() || !head_.doseDrained()) return;
      progress_.boot = head_.boot();
      progress_.fires = head_.fires();
      if (doseFor_ == DoseFor::Resuming) {
        doseFor_ = DoseFor::None;
        // The checkpoint holds the count before stop `done` was sent. One more, in the same start
        // of the Nano, means it was sent and carried out; `whole` says if it ran its full time.
        const Checkpointed& cp = checkpointed_;
        if (progress_.boot != cp.boot) resumed_ = Resumed::PrintheadRestarted;
        else if (progress_.fires == cp.fires) resumed_ = Resumed::NotSent;
        else if (progress_.fires == cp.fires + 1 && head_.lastWhole()) resumed_ = Resumed::Exposed;
        else resumed_ = Resumed::CutShort;
        if (resumed_ == Resumed::Exposed) done_++;
        // The light of the stop that was next, if the Nano still holds its record: whole, or cut and
        // so exposed again. A Nano that restarted lost its records, and its light is unknown.
        if (resumed_ == Resumed::Exposed) doseFor_ = DoseFor::Resumed;
        if (resumed_ == Resumed::CutShort) doseFor_ = DoseFor::CutResumed;
        if (resumed_ == Resumed::PrintheadRestarted) doseFor_ = DoseFor::Again;
      } else {
        // Continued after a pause: the cut stop's records came meanwhile, and it is exposed again.
        doseFor_ = doseFor_ == DoseFor::Cut || doseFor_ == DoseFor::Again ? DoseFor::Again : DoseFor::None;
      }
      progress_.done = done_;
      if (!checkpoint_.begin(progress_)) return fail(uv::kFileError);
      head_.requestDose();  // the records waiting: the resumed stop's light, or older (not this job's)
      phase_ = Phase::Drain;
      return;
    }
    case Phase::Drain:
      if (!head_.doseDrained()) return;
      doseFor_ = doseFor_ == DoseFor::CutResumed || doseFor_ == DoseFor::Again ? DoseFor::Again : DoseFor::None;
      phase_ = Phase::Load;
      return;
    case Phase::Load: {
      if (pauseWanted_) {
        pauseWanted_ = false;
        count(nowUs);
        return halt(RunState::Paused, pauseReason_);
      }
      if (stopInHand_) {
        // The stop a fault interrupted, or the one a pause came before: go to it again.
      } else if (source_) {
        NextStop n = source_->next(done_, stop_);
        waiting_ = n == NextStop::Wait;
        if (waiting_) return;  // the rows its next stops read are still on their way
        if (n == NextStop::Error) {
          count(nowUs);
          head_.allOff();
          return halt(RunState::Aborted, 0);
        }
        if (n == NextStop::End) {
          if (!doseSettled()) return;  // the last stop's DOSE: line before JOB:done
          count(nowUs);
          return halt(RunState::Done, 0);
        }
        if (n == NextStop::Scan) {
          phase_ = Phase::Scan;  // exposed on the move, pass by pass
          return;
        }
        // The job's geometry is known by its first stop: the header came before any row.
        header_.originUm[0] = streamHeader_->originUm[0];
        header_.originUm[1] = streamHeader_->originUm[1];
        header_.pitchUm[0] = streamHeader_->pitchUm[0];
        header_.pitchUm[1] = streamHeader_->pitchUm[1];
        header_.thermalCoeff = streamHeader_->thermalCoeff;
        header_.thermalRefDeciC = streamHeader_->thermalRefDeciC;
      } else {
        if (done_ >= header_.count) {
          if (!doseSettled()) return;  // the last stop's DOSE: line before JOB:done
          count(nowUs);
          checkpoint_.clear();
          if (stops_ >= 0) sd_.close(stops_);
          stops_ = -1;
          return halt(RunState::Done, 0);
        }
        if (card_) {
          card_->seek(done_);  // the step that is next, planned again if need be
          if (!card_->nextStop(stop_)) {  // not a mixed job's stop: a pass on the move
            phase_ = Phase::Scan;
            return;
          }
        } else if (!readStop(sd_, stops_, done_, stop_)) {
          return fail(uv::kFileError);
        }
      }
      stopInHand_ = true;
      // In steps, each µm figure converted once: on the board each conversion is a 64-bit division.
      int32_t here[3], to[3];
      motion_.targetSteps(here);
      const int32_t xUm = static_cast<int32_t>(header_.originUm[0]) + stop_.hx * static_cast<int32_t>(header_.pitchUm[0]);
      const int32_t yUm = static_cast<int32_t>(header_.originUm[1]) + stop_.hy * static_cast<int32_t>(header_.pitchUm[1]);
      to[0] = motion_.toSteps(0, xUm);
      to[1] = motion_.toSteps(1, yUm);
      to[2] = motion_.toSteps(2, zBase_ + (mesh_ ? mesh_->offsetAt(xUm, yUm) : 0));  // the bed's height under the stop
      bool moves = to[0] != here[0] || to[1] != here[1] || to[2] != here[2];
      // A stop off the bed (any host's job, checked here whatever planned it): the head never goes there.
      if (!motion_.onBed(0, to[0]) || !motion_.onBed(1, to[1])) return fail(uv::kSoftLimit);
      if (moves && !motion_.moveToSteps(to)) return;  // the queue is full: next pass
      settleUntil_ = moves ? static_cast<uint32_t>(config_.whole(Key::SettleMs)) * 1000 : 0;
      phase_ = Phase::Move;
      return;
    }
    case Phase::Move:
      if (!motion_.idle()) return;
      settleUntil_ += nowUs;
      phase_ = Phase::Settle;
      return;
    case Phase::Settle: {
      // The stop before's record first (it is asked as the move begins, and has come long before).
      if (!due(nowUs, settleUntil_) || !doseSettled()) return;
      if (uint8_t why = exposureBlocked()) return fail(why);
      if (paced_ && paceWaits(false)) {
        phase_ = Phase::Cool;  // LEDs off, the head still, until the readings show it cool
        changed_ = true;
        return;
      }
      uint32_t us[4];
      uint8_t mask = 0;
      for (uint8_t i = 0; i < 4; i++) {
        us[i] = compensate(i, stop_.us[i]);
        if (us[i]) mask = static_cast<uint8_t>(mask | (1 << i));
      }
      lit_ = mask != 0;
      if (!mask) {
        phase_ = Phase::Wait;  // nothing to light: confirmed as it is
        return;
      }
      if (!head_.fire(mask, us, nowUs)) return;  // the link is busy: next pass
      doseStarts();
      phase_ = Phase::Fire;
      return;
    }
    case Phase::Cool:
    case Phase::CoolFirst:
      return cool(nowUs);
    case Phase::Fire:
      if (head_.fireState() == FireState::Firing) return;
      if (head_.fireState() == FireState::Failed) {
        uint8_t code = head_.fireError() ? head_.fireError() : static_cast<uint8_t>(uv::kExposureRefused);
        head_.clearFire();
        return fail(code);  // the stop is not counted: it is exposed again on continue
      }
      head_.clearFire();
      head_.requestDose();  // its record, asked while the head moves to the next stop
      doseFor_ = doseFor_ == DoseFor::StopAgain ? DoseFor::DoneAgain : DoseFor::Done;
      phase_ = Phase::Wait;
      return confirmed(nowUs);
    case Phase::Scan:
      return pollScan(nowUs);
    case Phase::Wait:
      return confirmed(nowUs);
  }
}

}  // namespace mega
