// The SD card as the Mega's logic sees it: a few open files by handle. SdFat implements it on the
// board (hw/sd_storage), a directory of real files in the host tests (storage_fake.h).
#pragma once
#include <stdint.h>

namespace mega {

using FileHandle = int8_t;  // -1: no file
constexpr uint8_t kFileNameMax = 31;
// Files open at once: the board's SdStorage has this many (a FatFile each, some 40 B of the Mega's
// RAM: 32 B in the full build), and the host's fake card no more, so a job that needs one more fails
// in the tests as on the board. A scan job on the card holds four: its cells (~c), their index (~i),
// its checkpoint and its dose file (~d); a stop job three (its ~s for ~c and ~i).
constexpr uint8_t kCardFiles = 4;

class Storage {
 public:
  enum class Mode : uint8_t { Read, Create /* truncates */, Update /* read and write, kept */ };

  virtual bool present() = 0;
  virtual FileHandle open(const char* name, Mode mode) = 0;
  // Reads up to n bytes at the file's position; returns how many (0 at the end), or -1 on an error.
  virtual int16_t read(FileHandle f, char* buf, uint16_t n) = 0;
  virtual bool write(FileHandle f, const char* buf, uint16_t n) = 0;
  virtual bool seek(FileHandle f, uint32_t pos) = 0;
  virtual uint32_t size(FileHandle f) = 0;
  // Makes what was written survive a power cut.
  virtual bool sync(FileHandle f) = 0;
  virtual void close(FileHandle f) = 0;
  virtual bool exists(const char* name) = 0;
  virtual bool remove(const char* name) = 0;
  virtual bool rename(const char* from, const char* to) = 0;
  // The index-th file of the root directory, in directory order; false past the last one.
  virtual bool entry(uint16_t index, char* name, uint32_t& size) = 0;
  // 512 bytes the Mega may use while nothing touches the card: stream mode's buffer. With SdFat
  // it is the card's sector cache; the caller keeps every card command away meanwhile.
  virtual uint8_t* scratch() = 0;
};

constexpr uint16_t kScratchBytes = 512;

// Reads a file line by line through a small buffer, without a heap.
class LineReader {
 public:
  LineReader(Storage& sd, FileHandle f) : sd_(sd), f_(f) {}
  // The next line into out (without '\n' or a final '\r', NUL-terminated). A line longer than
  // max is cut to max and flagged. Returns false at the end of the file or on a read error.
  bool next(char* out, uint8_t max, uint8_t& len, bool& tooLong);
  bool failed() const { return failed_; }

 private:
  bool fill();

  Storage& sd_;
  FileHandle f_;
  char buf_[32];
  uint8_t pos_ = 0, end_ = 0;
  bool eof_ = false, failed_ = false;
};

}  // namespace mega
