// The planned stops of a job on the SD card (name~s): a header, then 20 bytes a stop, in the order
// they are exposed. Planning writes it once after the upload verified; running reads it front to
// back, so a running job needs a few bytes of RAM however large it is.
// A scan job's file (issue 19) holds its passes' count and time in the same header, then the job's
// header as this firmware holds it and the printhead link's speed it was planned at (4 bytes): its
// passes are planned again, one at a time, as they run, at that speed; and how many passes planning
// kept in the job's index file (4 bytes: the passes of a scan job, none for a mixed one; kept_pass.h).
#pragma once
#include <stdint.h>

#include "job_types.h"
#include "storage.h"
#include "time_model.h"

namespace mega {

struct StopFileHeader {
  uint32_t count;        // stops
  uint32_t estimateS;    // the planner's time model, whole seconds
  uint32_t originUm[2];
  uint32_t pitchUm[2];
  int16_t thermalCoeff;  // the job's thermal compensation (job.md), applied at exposure time
  int16_t thermalRefDeciC;
  bool scan;             // a scan job: `count` passes, and the job's header follows (readScanHeader)
};

constexpr uint8_t kStopHeaderBytes = 32;
constexpr uint8_t kStopBytes = 20;

// Writes the header at the file's start (placeholder first, the real one at the end of planning).
bool writeStopHeader(Storage& sd, FileHandle f, const StopFileHeader& h);
bool readStopHeader(Storage& sd, FileHandle f, StopFileHeader& h);
bool writeStop(Storage& sd, FileHandle f, const uv::Stop& s);
// A scan job's header, after the file's, and the link speed it was planned at (uv::MotionModel::linkBaud):
// written by the build that reads it (a build whose JobHeader differs in size finds the file's size
// wrong, and the job is planned again at M23). A speed the link cannot take (uv::nanoLinkBaud) is a
// file error.
bool writeScanHeader(Storage& sd, FileHandle f, const uv::JobHeader& h, uint32_t linkBaud, uint32_t kept);
bool readScanHeader(Storage& sd, FileHandle f, uv::JobHeader& h, uint32_t& linkBaud, uint32_t& kept);
// Reads stop i (seeks there first).
bool readStop(Storage& sd, FileHandle f, uint32_t i, uv::Stop& s);

}  // namespace mega
