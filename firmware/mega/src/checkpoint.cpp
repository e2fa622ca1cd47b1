// A running job's progress on the SD card: two slots written in turn, each with a CRC-32.
#include "checkpoint.h"

#include <string.h>

#include "crc32.h"
#include "dialect_command.h"
#include "job_files.h"
#include "le_bytes.h"
#include "progmem.h"

namespace mega {

namespace {
constexpr uint8_t kSlot = 64;
const char kMagic[4] UV_FLASH = {'U', 'V', 'K', '1'};

// magic 4, seq 4, done 4, count 4, file 32, crc 4 (over the 48 bytes before it), boot 2, fires 4
// (covered by a second CRC), padding.
void encode(const Progress& p, uint32_t seq, char* b) {
  memset(b, 0, kSlot);
  uvMemcpyP(b, kMagic, 4);
  putLe32(seq, b + 4);
  putLe32(p.done, b + 8);
  putLe32(p.count, b + 12);
  strncpy(b + 16, p.file, kFileNameMax);
  putLe32(uv::crc32Update(0, b, 48), b + 48);
  putLe32(p.boot, b + 52);
  putLe32(p.fires, b + 56);
  putLe32(uv::crc32Update(0, b, 60), b + 60);
}

bool decode(const char* b, Progress& p, uint32_t& seq) {
  if (uvMemcmpP(b, kMagic, 4) != 0 || getLe32(b + 48) != uv::crc32Update(0, b, 48)) return false;
  if (getLe32(b + 60) != uv::crc32Update(0, b, 60)) return false;
  seq = getLe32(b + 4);
  p.boot = static_cast<uint16_t>(getLe32(b + 52));
  p.fires = getLe32(b + 56);
  p.done = getLe32(b + 8);
  p.count = getLe32(b + 12);
  memcpy(p.file, b + 16, kFileNameMax);
  p.file[kFileNameMax] = 0;
  // A CRC proves the bytes are as written, not that they make sense: the name must be one the
  // dialect takes, or M1000 S would print whatever bytes it holds to the hosts.
  return p.done <= p.count && uv::validFileName(p.file, static_cast<uint8_t>(strlen(p.file)));
}
}  // namespace

bool Checkpoint::begin(const Progress& p) {
  close();
  if (sd_.exists(kCheckpointFile)) sd_.remove(kCheckpointFile);
  f_ = sd_.open(kCheckpointFile, Storage::Mode::Create);
  if (f_ < 0) return false;
  char zero[kSlot * 2] = {};
  seq_ = 0;
  return sd_.write(f_, zero, sizeof zero) && write(p);
}

bool Checkpoint::write(const Progress& p) {
  if (f_ < 0) return false;
  seq_++;
  char b[kSlot];
  encode(p, seq_, b);
  return sd_.seek(f_, (seq_ & 1) * kSlot) && sd_.write(f_, b, kSlot) && sd_.sync(f_);
}

void Checkpoint::close() {
  if (f_ >= 0) sd_.close(f_);
  f_ = -1;
}

void Checkpoint::clear() {
  close();
  if (sd_.exists(kCheckpointFile)) sd_.remove(kCheckpointFile);
}

bool Checkpoint::read(Storage& sd, Progress& out) {
  FileHandle f = sd.open(kCheckpointFile, Storage::Mode::Read);
  if (f < 0) return false;
  bool found = false;
  uint32_t best = 0;
  for (uint8_t slot = 0; slot < 2; slot++) {
    char b[kSlot];
    Progress p;
    uint32_t seq;
    if (sd.read(f, b, kSlot) == kSlot && decode(b, p, seq) && (!found || seq > best)) {
      out = p;
      best = seq;
      found = true;
    }
  }
  sd.close(f);
  return found;
}

}  // namespace mega
