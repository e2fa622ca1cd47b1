// A scan job's passes as planning at M29 kept them (uv::KeptPass: window, head row, extent, flown
// stretches), on the card after the rows of the job's index file: written as each pass is planned
// (job_plan.h) and read as it opens (card_scan.h), so that the run lays out no pass and makes no
// link check's search again, and reads no cell to open a pass. Each record carries a CRC-16: the
// run trusts what it holds (a stretch it flies is blank, its first column lit), so one the card
// garbled is a file error before the pass, not light out of place.
#pragma once
#include <stdint.h>

#include "crc16.h"
#include "le_bytes.h"
#include "scan.h"

namespace mega {

// 4 bytes each: window, head row, first and last column; 2 each: the stretches' columns, then
// windows; then the CRC-16 (crc16.h) of all that.
constexpr uint8_t kKeptPassBytes = 16 + 4 * uv::kMaxJumps + 2;

// Where pass `pass`'s record starts in the index file of a job of `rows` rows (8 bytes a row).
inline uint32_t keptPassAt(uint16_t rows, uint32_t pass) { return static_cast<uint32_t>(rows) * 8u + static_cast<uint32_t>(kKeptPassBytes) * pass; }

inline void putKeptPass(const uv::KeptPass& k, char* out) {
  putLe32(k.windowUs, out);
  putLe32(static_cast<uint32_t>(k.hy), out + 4);
  putLe32(static_cast<uint32_t>(k.first), out + 8);
  putLe32(static_cast<uint32_t>(k.last), out + 12);
  for (uint8_t i = 0; i < uv::kMaxJumps; i++) {
    putLe16(k.jumpCol[i], out + 16 + 2 * i);
    putLe16(k.jumpG[i], out + 16 + 2 * (uv::kMaxJumps + i));
  }
  putLe16(uv::crc16(out, kKeptPassBytes - 2), out + kKeptPassBytes - 2);
}

// False when the record's CRC is not that of what it holds.
inline bool getKeptPass(const char* in, uv::KeptPass& k) {
  if (uv::crc16(in, kKeptPassBytes - 2) != getLe16(in + kKeptPassBytes - 2)) return false;
  k.windowUs = getLe32(in);
  k.hy = static_cast<int32_t>(getLe32(in + 4));
  k.first = static_cast<int32_t>(getLe32(in + 8));
  k.last = static_cast<int32_t>(getLe32(in + 12));
  for (uint8_t i = 0; i < uv::kMaxJumps; i++) {
    k.jumpCol[i] = getLe16(in + 16 + 2 * i);
    k.jumpG[i] = getLe16(in + 16 + 2 * (uv::kMaxJumps + i));
  }
  return true;
}

}  // namespace mega
