// A running job's progress on the SD card (JOB~CKP), so an interrupted job can resume: two 64-byte
// slots written in turn, each with a sequence number and a CRC-32, so a write cut short by a power
// failure leaves the other slot, one stop older, intact.
#pragma once
#include <stdint.h>

#include "storage.h"

namespace mega {

struct Progress {
  char file[kFileNameMax + 1];
  uint32_t done;   // stops exposed and confirmed: the next to run
  uint32_t count;  // stops in the job
  uint16_t boot;   // the Nano's start number (its C reply) ...
  uint32_t fires;  // ... and its exposure count before stop `done` is sent
};

class Checkpoint {
 public:
  explicit Checkpoint(Storage& sd) : sd_(sd) {}
  ~Checkpoint() { close(); }

  // Starts a job's checkpoint (a new file).
  bool begin(const Progress& p);
  // Records progress; durable when it returns true.
  bool write(const Progress& p);
  void close();
  // The job ended (done or aborted): nothing to resume.
  void clear();
  // The latest intact record, if any.
  static bool read(Storage& sd, Progress& out);

 private:
  Storage& sd_;
  FileHandle f_ = -1;
  uint32_t seq_ = 0;
};

}  // namespace mega
