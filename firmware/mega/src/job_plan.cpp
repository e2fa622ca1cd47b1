// Plans a spooled job into its stop file, a few stops each main-loop pass.
#include "job_plan.h"

#include <new>

#include "error_codes.h"
#include "job_files.h"
#include "kept_pass.h"
#include "le_bytes.h"
#include "nano_codec.h"
#include "printhead_link.h"
#include "scan_program.h"
#include "scan_stroke.h"
#include "step_profile.h"

namespace mega {

uv::MotionModel plannerMachine(const Config& config, int32_t x, int32_t y, uint32_t linkBaud) {
  uv::MotionModel m{};
  for (uint8_t a = 0; a < 2; a++) {
    // speed.travel, or what the step engine runs on this axis if that is less (Motion::rateFor
    // holds every move to it): a plan that assumed more would fly a scan pass's blank stretches
    // faster than the head can step.
    const uint32_t engine = static_cast<uint32_t>(static_cast<uint64_t>(kMaxStepRate) * 1000000u / static_cast<uint32_t>(config.milli(a ? Key::StepsY : Key::StepsX)));
    const uint32_t travel = static_cast<uint32_t>(config.milli(Key::SpeedTravel));
    m.vmaxUmS[a] = travel < engine ? travel : engine;
  }
  m.accelUmS2[0] = static_cast<uint32_t>(config.milli(Key::AccelX));
  m.accelUmS2[1] = static_cast<uint32_t>(config.milli(Key::AccelY));
  m.settleUs = static_cast<uint32_t>(config.whole(Key::SettleMs)) * 1000;
  m.overheadUs = static_cast<uint32_t>(config.whole(Key::StopOverheadUs));
  m.startUm[0] = x;
  m.startUm[1] = y;
  m.stepsMilli[0] = static_cast<uint32_t>(config.milli(Key::StepsX));
  m.stepsMilli[1] = static_cast<uint32_t>(config.milli(Key::StepsY));
  m.linkBaud = linkBaud;  // the speed the passes run at (ScanRun waits for it)
  return m;
}

JobPlan::JobPlan(Storage& sd, const uv::JobHeader& header, const uv::MotionModel& machine)
    : sd_(sd), header_(header), machine_(machine), clock_(header_, machine_) {}

JobPlan::~JobPlan() { close(); }

void JobPlan::close() {
  if (planner_) planner_->~Planner();
  if (scan_) scan_->~ScanPlanner();
  scan_ = nullptr;
  if (source_) source_->~SdCellsWith();  // placed in the arena as exactly an SdCells
  planner_ = nullptr;
  source_ = nullptr;
  FileHandle* files[] = {&cells_, &index_, &stops_};
  for (FileHandle* f : files) {
    if (*f >= 0) sd_.close(*f);
    *f = -1;
  }
}

uint8_t JobPlan::begin(const char* name) {
  // A scan job's passes as planned go into its index file, after the rows (kept_pass.h).
  const bool keep = header_.strategy == uv::Strategy::Scan;
  openCellFiles(sd_, name, cells_, index_, keep ? Storage::Mode::Update : Storage::Mode::Read);  // checked with the stop file's below
  char work[kWorkNameMax + 1];
  workFileName(name, JobFile::Stops, work);
  stops_ = sd_.open(work, Storage::Mode::Create);
  StopFileHeader placeholder = {};
  if (cells_ < 0 || index_ < 0 || stops_ < 0 || !writeStopHeader(sd_, stops_, placeholder)) {
    error_ = uv::kFileError;
    close();
    return error_;
  }
  source_ = new (sourceMem_) SdCellsWith<uv::kPlannerCursors>(sd_, cells_, index_);
  bool supported;
  if (header_.strategy == uv::Strategy::Scan || header_.strategy == uv::Strategy::Mixed) {
    scan_ = new (plannerMem_) uv::ScanPlanner(header_, *source_, machine_);
    scan_->sliceBands();
    supported = scan_->supported();
  } else {
    planner_ = new (plannerMem_) uv::Planner(header_, *source_, machine_);
    supported = planner_->supported();
  }
  if (!supported) {  // the LEDs' rows span 1024 rows or more: planner.md "Memory on the Mega"
    error_ = uv::kJobMalformed;
    close();
    return error_;
  }
  return 0;
}

bool JobPlan::finish(uint64_t estimateUs) {
  StopFileHeader h = {};
  h.count = count_;
  h.estimateS = static_cast<uint32_t>((estimateUs + 500000) / 1000000);
  h.originUm[0] = header_.originUm[0];
  h.originUm[1] = header_.originUm[1];
  h.pitchUm[0] = header_.pitchUm[0];
  h.pitchUm[1] = header_.pitchUm[1];
  h.thermalCoeff = header_.thermalCoeff;
  h.thermalRefDeciC = header_.thermalRefDeciC;
  h.scan = scan_ != nullptr;
  const uint32_t kept = header_.strategy == uv::Strategy::Scan ? count_ : 0;
  if (source_->failed() || (kept && !sd_.sync(index_)) || !writeStopHeader(sd_, stops_, h) ||
      (h.scan && !writeScanHeader(sd_, stops_, header_, machine_.linkBaud, kept)) || !sd_.sync(stops_))
    error_ = uv::kFileError;
  close();
  done_ = true;
  return true;
}

bool JobPlan::passEvent(void* ctx, uint32_t& t, uint8_t& m) {
  JobPlan* plan = static_cast<JobPlan*>(ctx);
  if (!plan->scan_->nextEvent(t, m)) return false;
  plan->passUs_ = t;
  return true;
}

// One pass: opened, and its events written as the Nano's program lines, for the count and the
// time, and to check the printhead link can carry them (uv::LinkLoad, as the planner's link cap):
// the whole chain while the pass plays, and each program after the first two while the one before
// it plays. A pass that would outrun it is refused here, before any light.
bool JobPlan::stepScan() {
  uv::ScanPass p;
  if (!scan_->nextPass(p)) {
    if (scan_->pricing()) return false;  // a mixed job's band, priced a pass a step
    if (!scan_->refused()) return finish(scan_->estimateUs());
    error_ = uv::kScanUnsupported;  // a window the step engine cannot run: refused before any light
    close();
    return true;
  }
  if (p.stops) {  // a mixed job's pass of stops: each stop is a step of the job
    uv::Stop s;
    while (scan_->nextStop(s)) count_++;
    return false;
  }
  uv::ProgramLines lines(passEvent, this);
  uv::LinkLoad load(machine_.linkBaud);
  char line[uv::kNanoMaxLine + 2];
  passUs_ = 0;
  for (uint8_t n; (n = lines.next(line)) != 0;) load.add(line, n, lines.lastUs());
  uint64_t need, have;
  // Failed: events 2²⁸ µs apart or more. And a pass too long for its stroke's tick count.
  if (lines.failed() || !load.fits(passUs_, need, have) || passUs_ >= kScanLongestPassUs) {
    error_ = uv::kScanUnsupported;
    close();
    return true;
  }
  if (header_.strategy == uv::Strategy::Scan) {  // the pass as planned here, for the run (kept_pass.h)
    uv::KeptPass k;
    scan_->keep(p, k);
    char b[kKeptPassBytes];
    putKeptPass(k, b);
    if (!sd_.seek(index_, keptPassAt(header_.rows, count_)) || !sd_.write(index_, b, sizeof b)) {
      error_ = uv::kFileError;
      close();
      return true;
    }
  }
  count_++;
  return false;
}

bool JobPlan::step(uint16_t stops) {
  if (done_ || error_) return true;
  if (scan_) return stepScan();
  uv::Stop s;
  for (uint16_t i = 0; i < stops; i++) {
    if (!planner_->next(s)) return finish(clock_.totalUs());
    clock_.add(s);
    if (!writeStop(sd_, stops_, s)) {
      error_ = uv::kFileError;
      close();
      return true;
    }
    count_++;
  }
  return false;
}

}  // namespace mega
