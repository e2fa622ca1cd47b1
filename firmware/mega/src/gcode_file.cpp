// G-code files on the card: stored uploads shown whole at M29, and a line reader for M24.
#include "gcode_file.h"

#include <string.h>

#include "error_codes.h"
#include "job_files.h"
#include "progmem.h"

namespace mega {

namespace {
char lower(char c) { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c + 32) : c; }

// Whether name ends in `.` and ext (lower case), with something before the dot. ext is in flash.
bool endsWith(const char* name, const char* ext) {
  size_t n = strlen(name), e = uvStrlenP(ext);
  if (n <= e + 1 || name[n - e - 1] != '.') return false;
  for (size_t i = 0; i < e; i++)
    if (lower(name[n - e + i]) != static_cast<char>(uvFlashByte(ext + i))) return false;
  return true;
}

// The upload's working file: a `~` suffix, which M20 leaves out and no job name may hold.
void uploadName(const char* name, char* out) {
  size_t n = strlen(name);
  memcpy(out, name, n);
  out[n] = '~';
  out[n + 1] = 'u';
  out[n + 2] = 0;
}
}  // namespace

bool isGcodeName(const char* name) {
  return endsWith(name, UV_P("gco")) || endsWith(name, UV_P("gcode")) || endsWith(name, UV_P("g"));
}

void GcodeFile::close() {
  if (f_ >= 0) sd_.close(f_);
  f_ = -1;
  if (upload_) {  // an upload that never reached M29 leaves nothing behind
    char work[kWorkNameMax + 1];
    uploadName(name_, work);
    sd_.remove(work);
    upload_ = false;
  }
}

uint8_t GcodeFile::beginUpload(const char* name) {
  close();
  strncpy(name_, name, kFileNameMax);
  char work[kWorkNameMax + 1];
  uploadName(name_, work);
  f_ = sd_.open(work, Storage::Mode::Create);
  if (f_ < 0) return uv::kFileError;
  upload_ = true;
  return 0;
}

uint8_t GcodeFile::store(const char* line, uint8_t len) {
  const char nl = '\n';
  if (!upload_ || !sd_.write(f_, line, len) || !sd_.write(f_, &nl, 1)) return uv::kFileError;
  return 0;
}

uint8_t GcodeFile::commit() {
  if (!upload_) return uv::kFileError;
  bool ok = sd_.sync(f_);
  sd_.close(f_);
  f_ = -1;
  char work[kWorkNameMax + 1];
  uploadName(name_, work);
  if (ok && sd_.exists(name_)) ok = sd_.remove(name_);
  ok = ok && sd_.rename(work, name_);
  if (!ok) {
    close();  // removes the working file
    return uv::kFileError;
  }
  upload_ = false;
  return 0;
}

uint8_t GcodeFile::open(const char* name) {
  close();
  if (isWorkFile(name)) return uv::kFileNotFound;
  f_ = sd_.open(name, Storage::Mode::Read);
  if (f_ < 0) return uv::kFileNotFound;
  strncpy(name_, name, kFileNameMax);
  size_ = sd_.size(f_);
  pos_ = 0;
  at_ = end_ = 0;
  failed_ = false;
  pending = false;
  return 0;
}

int16_t GcodeFile::byte() {
  if (at_ == end_) {
    int16_t n = f_ >= 0 ? sd_.read(f_, buf_, sizeof buf_) : 0;
    if (n < 0) failed_ = true;
    if (n <= 0) return -1;
    at_ = 0;
    end_ = static_cast<uint8_t>(n);
  }
  pos_++;
  return static_cast<uint8_t>(buf_[at_++]);
}

bool GcodeFile::next(LineSlot& slot) {
  for (;;) {
    slot.len = 0;
    slot.overflow = false;
    slot.dead = false;
    slot.n = -1;
    bool comment = false, any = false;
    int16_t c;
    while ((c = byte()) >= 0 && c != '\n') {
      any = true;
      if (c == ';') comment = true;
      if (comment || c == '\r') continue;
      if (slot.len < uv::kDialectMaxLine) slot.text[slot.len++] = static_cast<char>(c);
      else slot.overflow = true;
    }
    while (slot.len && slot.text[slot.len - 1] == ' ') slot.len--;
    uint8_t lead = 0;
    while (lead < slot.len && slot.text[lead] == ' ') lead++;
    memmove(slot.text, slot.text + lead, slot.len - lead);
    slot.len = static_cast<uint8_t>(slot.len - lead);
    slot.text[slot.len] = 0;
    if (slot.len || slot.overflow) return true;
    if (c < 0 && !any) return false;  // the end of the file
  }
}

bool GcodeFile::seek(uint32_t pos) {
  if (f_ < 0 || upload_ || pos > size_) return false;
  at_ = end_ = 0;
  pending = false;
  if (pos == 0) {
    pos_ = 0;
    return sd_.seek(f_, 0);
  }
  if (!sd_.seek(f_, pos - 1)) return false;
  pos_ = pos - 1;
  int16_t c;
  while ((c = byte()) >= 0 && c != '\n') {
  }
  return true;
}

}  // namespace mega
