// The files a job keeps on the SD card. The job's text is stored under its own name, byte for byte
// as uploaded (its CRC-32 stays checkable); the Mega's working files carry a `~` and one letter at the
// end, which no job name may hold (a G-code file may have a `~` inside: DOS short names), and are left
// out of M20's list.
#pragma once
#include <stdint.h>
#include <string.h>

#include "storage.h"

namespace mega {

enum class JobFile : char {
  Cells = 'c',   // each non-empty row's cells, from its first to its last non-zero column
  Index = 'i',   // 8 bytes a row: offset into the cells file (LE), first and last column; then a
                 // scan job's passes as planning kept them (kept_pass.h)
  Stops = 's',   // the planned stops, in execution order (stop_file.h)
  Dose = 'd',    // the last run's DOSE: lines, as the hosts got them (protocol/mega.md "Dose reports")
};

constexpr const char* kCheckpointFile = "JOB~CKP";
constexpr uint8_t kWorkNameMax = kFileNameMax + 2;

// `name~c` and so on, NUL-terminated, into out (kWorkNameMax + 1 bytes).
inline void workFileName(const char* job, JobFile kind, char* out) {
  size_t n = strlen(job);
  memcpy(out, job, n);
  out[n] = '~';
  out[n + 1] = static_cast<char>(kind);
  out[n + 2] = 0;
}

// A job's `~c`, `~i`, `~s`, `~d`, a G-code upload's `~u`, and the checkpoint.
inline bool isWorkFile(const char* name) {
  size_t n = strlen(name);
  if (strcmp(name, kCheckpointFile) == 0) return true;
  if (n < 2 || name[n - 2] != '~') return false;
  char k = name[n - 1];  // compared one by one: a string literal would cost RAM on the AVR
  return k == 'c' || k == 'i' || k == 's' || k == 'u' || k == 'd';
}

// Opens a job's cells and index files to read (the index to write too when planning puts the
// kept passes in it); false unless both opened.
inline bool openCellFiles(Storage& sd, const char* job, FileHandle& cells, FileHandle& index, Storage::Mode indexMode = Storage::Mode::Read) {
  char work[kWorkNameMax + 1];
  workFileName(job, JobFile::Cells, work);
  cells = sd.open(work, Storage::Mode::Read);
  workFileName(job, JobFile::Index, work);
  index = sd.open(work, indexMode);
  return cells >= 0 && index >= 0;
}

constexpr JobFile kWorkFiles[] = {JobFile::Cells, JobFile::Index, JobFile::Stops, JobFile::Dose};

// Removes what the Mega built from a job.
inline void removeWorkFiles(Storage& sd, const char* job) {
  char work[kWorkNameMax + 1];
  for (JobFile k : kWorkFiles) {
    workFileName(job, k, work);
    if (sd.exists(work)) sd.remove(work);
  }
}

// Removes a job and its working files.
inline void removeJob(Storage& sd, const char* job) {
  removeWorkFiles(sd, job);
  if (sd.exists(job)) sd.remove(job);
}

}  // namespace mega
