// Receives a job upload onto the SD card: text, cells and index, each record checked on arrival.
#include "job_spool.h"

#include <new>

#include "error_codes.h"
#include "le_bytes.h"

namespace mega {

uint8_t JobSpool::begin(const char* name) {
  strncpy(name_, name, kFileNameMax);
  name_[kFileNameMax] = 0;
  removeJob(sd_, name_);  // an upload under an old name replaces it whole
  char work[kWorkNameMax + 1];
  text_ = sd_.open(name_, Storage::Mode::Create);
  workFileName(name_, JobFile::Cells, work);
  cells_ = sd_.open(work, Storage::Mode::Create);
  workFileName(name_, JobFile::Index, work);
  index_ = sd_.open(work, Storage::Mode::Create);
  if (text_ < 0 || cells_ < 0 || index_ < 0) {
    fail(uv::kFileError);
    return error_;
  }
  return 0;
}

uint8_t JobSpool::beginPrepared(const char* name) {
  strncpy(name_, name, kFileNameMax);
  name_[kFileNameMax] = 0;
  prepared_ = true;
  char work[kWorkNameMax + 1];
  text_ = sd_.open(name_, Storage::Mode::Read);
  if (text_ < 0) return error_ = uv::kFileNotFound;
  reader_ = new (readerMem_) LineReader(sd_, text_);
  workFileName(name_, JobFile::Cells, work);
  cells_ = sd_.open(work, Storage::Mode::Create);
  workFileName(name_, JobFile::Index, work);
  index_ = sd_.open(work, Storage::Mode::Create);
  if (cells_ < 0 || index_ < 0) fail(uv::kFileError);
  return error_;
}

bool JobSpool::prepareStep(uint8_t lines) {
  char line[uv::kDialectMaxLine + 1];
  for (uint8_t i = 0; i < lines && !error_; i++) {
    uint8_t len;
    bool tooLong;
    if (!reader_->next(line, uv::kDialectMaxLine, len, tooLong)) {
      if (reader_->failed()) fail(uv::kFileError);
      return true;
    }
    if (tooLong) fail(uv::kJobMalformed);
    else record(line, len);
  }
  return error_ != 0;
}

void JobSpool::fail(uint8_t code) {
  if (!error_) error_ = code;
}

uint8_t JobSpool::record(const char* text, uint8_t len) {
  if (error_) return error_;
  uint8_t err = verifier_.push(text, len);  // calls segment() for each good `r` record
  if (err) {
    fail(err);
    return error_;
  }
  if (error_) return error_;  // segment() could not write
  if (!prepared_ && (!sd_.write(text_, text, len) || !sd_.write(text_, "\n", 1))) fail(uv::kFileError);
  bytes_ += static_cast<uint32_t>(len) + 1;
  return error_;
}

bool JobSpool::zeros(uint16_t n) {
  const char kZero[16] = {};  // on the stack: static RAM is the Mega's scarcest resource
  while (n) {
    uint8_t k = n > sizeof kZero ? sizeof kZero : static_cast<uint8_t>(n);
    if (!sd_.write(cells_, kZero, k)) return false;
    cellBytes_ += k;
    n = static_cast<uint16_t>(n - k);
  }
  return true;
}

bool JobSpool::writeIndex(uint16_t upTo) {
  // Index entries for every row before `upTo` not written yet: the open row's, then empty ones.
  char entry[8];
  while (indexed_ < upTo) {
    if (static_cast<int32_t>(indexed_) == row_ && started_) {
      putLe32(rowOffset_, entry);
      putLe16(first_, entry + 4);  // the first and last non-zero columns
      putLe16(last_, entry + 6);
    } else {
      putLe32(cellBytes_, entry);
      putLe16(0xffff, entry + 4);  // empty: first after last
      putLe16(0, entry + 6);
    }
    if (!sd_.write(index_, entry, sizeof entry)) return false;
    indexed_++;
  }
  return true;
}

void JobSpool::segment(uint16_t row, uint16_t col, const uint8_t* buf, uint8_t cells) {
  if (error_) return;
  if (static_cast<int32_t>(row) != row_) {
    if (!writeIndex(row)) return fail(uv::kFileError);  // rows before this one are complete
    row_ = row;
    started_ = false;
  }
  uint8_t s = 0;
  for (uint8_t i = 0; i < cells; i++)
    if (buf[i]) last_ = static_cast<uint16_t>(col + i);
  if (!started_) {
    // A row's cells start at its first non-zero one (a non-canonical upload may lead with zeros).
    while (s < cells && !buf[s]) s++;
    if (s == cells) return;
    started_ = true;
    rowOffset_ = cellBytes_;
    first_ = next_ = static_cast<uint16_t>(col + s);
  }
  uint16_t at = static_cast<uint16_t>(col + s);
  if (at > next_ && !zeros(static_cast<uint16_t>(at - next_))) return fail(uv::kFileError);
  if (!sd_.write(cells_, reinterpret_cast<const char*>(buf + s), static_cast<uint16_t>(cells - s))) return fail(uv::kFileError);
  cellBytes_ += cells - s;
  next_ = static_cast<uint16_t>(col + cells);
}

void JobSpool::closeAll() {
  FileHandle* files[] = {&text_, &cells_, &index_};
  for (FileHandle* f : files) {
    if (*f >= 0) sd_.close(*f);
    *f = -1;
  }
}

uint8_t JobSpool::finish() {
  if (!error_) {
    uint8_t err = verifier_.finish();
    if (err) fail(err);
  }
  if (!error_ && !writeIndex(verifier_.header().rows)) fail(uv::kFileError);
  if (!error_) {
    if ((!prepared_ && !sd_.sync(text_)) || !sd_.sync(cells_) || !sd_.sync(index_)) fail(uv::kFileError);
  }
  closeAll();
  if (error_) abandon();  // a partial or unverified job never stays
  return error_;
}

void JobSpool::abandon() {
  closeAll();
  if (prepared_) removeWorkFiles(sd_, name_);  // a job a PC put on the card stays; only what was built goes
  else removeJob(sd_, name_);
}

}  // namespace mega
