// Runs a planned job from its stop file: for each stop, move, settle, expose through the printhead
// link, confirm, and record the progress on the card, so an interrupted job resumes after the last
// confirmed stop. Pause takes effect between stops; no path leaves an LED on.
#pragma once
#include <stdint.h>

#include "card_scan.h"
#include "checkpoint.h"
#include "config.h"
#include "dialect_dose.h"
#include "mesh_store.h"
#include "motion.h"
#include "printhead_link.h"
#include "stop_file.h"
#include "stop_source.h"
#include "storage.h"

namespace mega {

enum class RunState : uint8_t { Running, Paused, Done, Aborted, Failed };

// Pacing (protocol/mega.md "Pacing"): before a stop, or a pass on the move, a paced job waits with the
// LEDs off while a sensor reads within kPaceAtDeciC of its soft limit, until every one reads
// kPaceUntilDeciC below it and the Nano's OVERTEMP flag is clear (job_runner_pacing.cpp).
// The app's dry run and simulated printer use the same numbers (app/src/sim/pacing.ts).
constexpr int16_t kPaceAtDeciC = 20;
constexpr int16_t kPaceUntilDeciC = 30;

// The first sensor (1-6) reading at or over its soft limit (thermal.limit.<i>) now, or 0.
uint8_t sensorAtSoftLimit(const PrintheadLink& head, const Config& config);
// Heat stands in the way of an exposure: a sensor at or over its soft limit, or the Nano's own
// OVERTEMP flag (it clears only 5 °C under the Nano's hard limit, nano.md). Cooling clears both.
bool headHot(const PrintheadLink& head, const Config& config);

class JobRunner {
 public:
  // `mesh`: the bed mesh to follow in Z, or nullptr.
  JobRunner(Storage& sd, Motion& motion, PrintheadLink& head, const Config& config, MeshStore* mesh)
      : sd_(sd), motion_(motion), head_(head), config_(config), mesh_(mesh), checkpoint_(sd) {}
  ~JobRunner();

  // Where a scan job on the card keeps its planner while it runs (the job arena after the runner).
  void setScanMemory(uint8_t* mem, uint16_t bytes) {
    scanMem_ = mem;
    scanBytes_ = bytes;
  }
  // Opens the job's stops (a scan job: its passes) and starts at stop `from`. Returns 0, or 21
  // (not planned) / 22.
  uint8_t start(const char* name, uint32_t from, uint32_t nowUs);
  // Runs a stream (M828): stops come from `source` as they are planned; `header` fills as the job's
  // first records arrive. No checkpoint: a stream cannot resume.
  void startStream(StopSource& source, const uv::JobHeader& header, uint32_t nowUs);
  bool streaming() const { return source_ != nullptr; }
  // Every stop is known (a stream's last row has arrived).
  bool planComplete() const { return !source_ || source_->complete(); }
  // A stream's runner has run out of planned stops and waits for rows.
  bool starved() const { return waiting_; }
  // Resumes an interrupted job from its checkpoint. Before anything moves, the Nano's C reply
  // tells whether the stop that was next had been exposed: if so, whole, it counts as done.
  uint8_t resume(const Progress& checkpoint, uint32_t nowUs);
  // How the resume judged the stop that was next when the job was interrupted.
  enum class Resumed : uint8_t { NotYet, NotSent, Exposed, CutShort, PrintheadRestarted };
  // The verdict once it is known (until cleared).
  Resumed resumedVerdict() const { return resumed_; }
  void clearResumed() { resumed_ = Resumed::NotYet; }
  // The stop the verdict is about.
  uint32_t resumedStop() const { return checkpointed_.done; }
  void poll(uint32_t nowUs);
  // Pauses once the stop under way is confirmed. `reason`: 0 by request, else an error code.
  void pause(uint8_t reason = 0);
  // Continues a paused job. `coolFirst` (a paced continue while the head is hot, mega.md "Pacing"):
  // it waits to cool first, LEDs off and the head still, as a paced job's wait before a stop.
  void resume(uint32_t nowUs, bool coolFirst = false);
  // Stops everything at once: LEDs off, motion stopped, the checkpoint cleared.
  void abort();

  // Paced or not (mega.md "Pacing"); a paced job waiting for the head to cool is `cooling`.
  void setPaced(bool paced) { paced_ = paced; }
  bool paced() const { return paced_; }
  bool cooling() const { return state_ == RunState::Running && (phase_ == Phase::Cool || phase_ == Phase::CoolFirst); }
  // The first sensor (1-6) reading at or over its soft limit now, or 0.
  uint8_t tooHot() const { return sensorAtSoftLimit(head_, config_); }

  RunState state() const { return state_; }
  uint8_t reason() const { return reason_; }
  uint32_t done() const { return done_; }
  uint32_t count() const { return source_ ? source_->count() : header_.count; }
  uint32_t elapsedS(uint32_t nowUs) const { return elapsedS_ + (elapsedUs_ + (state_ == RunState::Running ? nowUs - since_ : 0)) / 1000000; }
  uint32_t remainingS() const;
  const char* file() const { return progress_.file; }
  // The state changed since the last call (for JOB: reports).
  bool changed() const { return changed_; }
  void clearChanged() { changed_ = false; }
  // A dose record from the Nano (protocol/mega.md "Dose reports"): the stop (or pass and program) it
  // belongs to, into `d`. False for a record that belongs to none of this job's stops (one from
  // before the job, or from before a restart that the checkpoint cannot place): it is not reported.
  bool attribute(const uv::NanoReply& record, uv::DoseReport& d);
  // A card job keeps its DOSE: lines, as the hosts got them, in its dose file (name~d): started
  // afresh by a run from the first stop, added to by a resume. It reaches the card's directory at
  // each pass's checkpoint, every 16 stops, and whenever the job stops (pause, fault, end): a power
  // cut may take the last few stops' lines from it (the hosts had them). A line the card will not
  // take stops the job as any card error (E22: paused, LEDs off). Nothing for a stream.
  void keepDose(const char* line);

  // What the last failure was about, for its FAULT line: the stop index.
  uint32_t faultStop() const { return done_; }

 private:
  // Cool: a paced job's wait before a stop or a pass. CoolFirst: the same wait, before a paced
  // continue goes on (the phase costs no RAM, where a flag in the runner would).
  enum class Phase : uint8_t { Sync, Drain, Load, Move, Settle, Cool, CoolFirst, Fire, Wait, Scan };
  // Whose light the Nano's records are, and whether the stop exposed next had light before (one byte:
  // the Mega's RAM; it also says a resume waits for its verdict, Resuming). None, Again: no stop's (older than the job; Again: the next stop is exposed
  // again). Stop, StopAgain: the stop under way (its F, or its pass's programs). Done, DoneAgain: the
  // stop just confirmed, whose F's record is asked while the head moves on (the stop cycle does not
  // wait for it). Cut: the stop a fault cut short, exposed again next. Resumed, CutResumed: at M1000,
  // the stop that was next when the Mega restarted, exposed whole or cut short.
  enum class DoseFor : uint8_t { None, Again, Stop, StopAgain, Done, DoneAgain, Cut, Resuming, Resumed, CutResumed };
  // The last stop's record has come (or none will): the next stop may light, or the job end.
  bool doseSettled();
  // The stop under way starts its light.
  void doseStarts() { doseFor_ = doseFor_ == DoseFor::Again || doseFor_ == DoseFor::Cut ? DoseFor::StopAgain : DoseFor::Stop; }
  void fail(uint8_t code);
  void halt(RunState s, uint8_t reason);
  uint32_t compensate(uint8_t led, uint32_t us) const;
  // What stops an exposure from starting now (a broken sensor, too hot, the Nano gone): its error code, or 0.
  uint8_t exposureBlocked() const;
  bool paceWaits(bool cooling) const;
  // A paused job runs on: the Nano's count read again (a card job), the stop in hand again.
  void continueAfterPause();
  // A paced wait to cool, either kind (Cool, CoolFirst): on while only heat stands in the way.
  void cool(uint32_t nowUs);
  // The stop under way is exposed (or had nothing to light): counted, and the next loaded.
  void confirmed(uint32_t nowUs);
  // A scan job's passes (job_runner_scan.cpp).
  void pollScan(uint32_t nowUs);

  Storage& sd_;
  Motion& motion_;
  PrintheadLink& head_;
  const Config& config_;
  MeshStore* mesh_;
  int32_t zBase_ = 0;  // the head's Z when the job started; the mesh offset adds to it
  Checkpoint checkpoint_;
  FileHandle stops_ = -1;
  FileHandle dose_ = -1;  // keepDose()
  static constexpr FileHandle kDoseRefused = -2;  // the card refused a line: the next poll fails the job
  StopSource* source_ = nullptr;
  CardScan* card_ = nullptr;  // a scan job on the card: its passes' planner and runner
  uint8_t* scanMem_ = nullptr;
  uint16_t scanBytes_ = 0;
  const uv::JobHeader* streamHeader_ = nullptr;
  bool waiting_ = false;
  bool stopInHand_ = false;  // stop_ is the next to expose (read, not yet confirmed)
  StopFileHeader header_ = {};
  Progress progress_ = {};
  uv::Stop stop_ = {};
  RunState state_ = RunState::Aborted;
  Phase phase_ = Phase::Load;
  uint8_t reason_ = 0;
  bool pauseWanted_ = false;
  bool lit_ = false;  // the stop under way lights an LED
  DoseFor doseFor_ = DoseFor::None;
  bool paced_ = false;
  uint8_t pauseReason_ = 0;
  bool changed_ = false;
  Resumed resumed_ = Resumed::NotYet;
  // What resume() read off the checkpoint that the resume verdict compares with the Nano's counters,
  // not the whole record (its file name is progress_'s).
  struct Checkpointed {
    uint32_t done;
    uint16_t boot;
    uint32_t fires;
  } checkpointed_ = {};
  uint32_t done_ = 0;
  // Time run: whole seconds, and the µs since the last whole second, folded in at every poll.
  void count(uint32_t nowUs);
  uint32_t since_ = 0, elapsedS_ = 0, elapsedUs_ = 0, settleUntil_ = 0, now_ = 0;
};

}  // namespace mega
