// G-code files on the card, the Marlin way (protocol/mega.md "G-code files on the card"): an upload that
// stores its lines in a working file and shows the file only once it is whole, and a reader that gives
// the command core one line at a time, counting bytes as Marlin's `SD printing byte` does.
#pragma once
#include <stdint.h>

#include "line_ring.h"
#include "storage.h"

namespace mega {

// .gco, .gcode or .g, in any case; every other name on the card is an exposure job.
bool isGcodeName(const char* name);

class GcodeFile {
 public:
  explicit GcodeFile(Storage& sd) : sd_(sd) {}
  ~GcodeFile() { close(); }
  GcodeFile(const GcodeFile&) = delete;
  GcodeFile& operator=(const GcodeFile&) = delete;

  // M28: the lines go to `name~u` until commit(); 0 or an error code.
  uint8_t beginUpload(const char* name);
  uint8_t store(const char* line, uint8_t len);
  // M29: the working file takes the name, replacing an older file of that name. 0 or kFileError.
  uint8_t commit();
  bool uploading() const { return upload_; }

  // M23: opens a file to run; 0 or kFileNotFound.
  uint8_t open(const char* name);
  // The next line to run, without its comment, into slot (its n is -1); false at the end of the file
  // or on a read error. A line longer than the dialect's 96 bytes comes back flagged (slot.overflow).
  bool next(LineSlot& slot);
  // M26: reads on from `pos`; a position inside a line moves on to the next line's start.
  bool seek(uint32_t pos);
  uint32_t pos() const { return pos_; }
  uint32_t size() const { return size_; }
  bool failed() const { return failed_; }

  // Runs (M24) or waits (M23, M25).
  bool running = false;
  // The line the core has read but not yet run (it waited for room or for the queue).
  LineSlot line = {};
  bool pending = false;

 private:
  int16_t byte();  // the next byte, -1 at the end
  void close();

  Storage& sd_;
  FileHandle f_ = -1;
  char name_[kFileNameMax + 1] = {};
  bool upload_ = false, failed_ = false;
  uint32_t pos_ = 0, size_ = 0;
  char buf_[32];
  uint8_t at_ = 0, end_ = 0;
};

}  // namespace mega
