// Plans a spooled job into its stop file, a few stops each main-loop pass.
#include "job_plan.h"

#include <new>

#include "error_codes.h"
#include "job_files.h"

namespace mega {

JobPlan::JobPlan(Storage& sd, const uv::JobHeader& header, const uv::Machine& machine)
    : sd_(sd), header_(header), machine_(machine), clock_(header_, machine_) {}

JobPlan::~JobPlan() { close(); }

void JobPlan::close() {
  if (planner_) planner_->~Planner();
  if (source_) source_->SdCells::~SdCells();  // placed in the arena as exactly an SdCells
  planner_ = nullptr;
  source_ = nullptr;
  FileHandle* files[] = {&cells_, &index_, &stops_};
  for (FileHandle* f : files) {
    if (*f >= 0) sd_.close(*f);
    *f = -1;
  }
}

uint8_t JobPlan::begin(const char* name) {
  char work[kWorkNameMax + 1];
  workFileName(name, JobFile::Cells, work);
  cells_ = sd_.open(work, Storage::Mode::Read);
  workFileName(name, JobFile::Index, work);
  index_ = sd_.open(work, Storage::Mode::Read);
  workFileName(name, JobFile::Stops, work);
  stops_ = sd_.open(work, Storage::Mode::Create);
  StopFileHeader placeholder = {};
  if (cells_ < 0 || index_ < 0 || stops_ < 0 || !writeStopHeader(sd_, stops_, placeholder)) {
    error_ = uv::kFileError;
    close();
    return error_;
  }
  if (header_.strategy == uv::Strategy::Scan) {  // this firmware plans stops only: refused before any light
    error_ = uv::kScanUnsupported;
    close();
    return error_;
  }
  source_ = new (sourceMem_) SdCells(sd_, cells_, index_);
  planner_ = new (plannerMem_) uv::Planner(header_, *source_, machine_);
  if (!planner_->supported()) {  // the LEDs' rows span 1024 rows or more: planner.md "Memory on the Mega"
    error_ = uv::kJobMalformed;
    close();
    return error_;
  }
  return 0;
}

bool JobPlan::step(uint16_t stops) {
  if (done_ || error_) return true;
  uv::Stop s;
  for (uint16_t i = 0; i < stops; i++) {
    if (!planner_->next(s)) {
      StopFileHeader h = {};
      h.count = count_;
      h.estimateS = static_cast<uint32_t>((clock_.totalUs() + 500000) / 1000000);
      h.originUm[0] = header_.originUm[0];
      h.originUm[1] = header_.originUm[1];
      h.pitchUm[0] = header_.pitchUm[0];
      h.pitchUm[1] = header_.pitchUm[1];
      h.thermalCoeff = header_.thermalCoeff;
      h.thermalRefDeciC = header_.thermalRefDeciC;
      if (source_->failed() || !writeStopHeader(sd_, stops_, h) || !sd_.sync(stops_)) error_ = uv::kFileError;
      close();
      done_ = true;
      return true;
    }
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
