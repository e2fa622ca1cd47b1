// The planner's CellSource over a spooled job on the SD card.
#include "sd_cells.h"

namespace mega {

bool SdCells::readRow(uint16_t row, Row& out) {
  if (row == cachedRow_) {
    out = cached_;
    return true;
  }
  uint8_t e[8];
  if (!sd_.seek(index_, static_cast<uint32_t>(row) * 8) || sd_.read(index_, reinterpret_cast<char*>(e), 8) != 8) {
    failed_ = true;
    return false;
  }
  out.offset = static_cast<uint32_t>(e[0]) | static_cast<uint32_t>(e[1]) << 8 | static_cast<uint32_t>(e[2]) << 16 |
               static_cast<uint32_t>(e[3]) << 24;
  out.first = static_cast<uint16_t>(e[4] | e[5] << 8);
  out.last = static_cast<uint16_t>(e[6] | e[7] << 8);
  cachedRow_ = row;
  cached_ = out;
  return true;
}

bool SdCells::rowNonEmpty(uint16_t row) {
  Row r;
  return readRow(row, r) && r.first <= r.last;
}

bool SdCells::rowExtent(uint16_t row, uint16_t& first, uint16_t& last) {
  Row r;
  if (!readRow(row, r) || r.first > r.last) return false;
  first = r.first;  // the spool indexes the first and last non-zero columns
  last = r.last;
  return true;
}

void SdCells::open(uint8_t cursor, uint16_t row, bool descending) {
  Cursor& c = cursors_[cursor];
  Row r;
  c.flags = descending ? kDescending : 0;
  if (!readRow(row, r) || r.first > r.last) {
    c.flags = 0;  // walking up from 1 to 0: nothing
    c.pos = 1;
    c.bound = 0;
    return;
  }
  c.base = r.offset - r.first;
  c.bound = descending ? r.first : r.last;
  c.pos = static_cast<int16_t>(descending ? r.last : r.first);  // the index's ends are non-zero cells
}

void SdCells::openAt(uint8_t cursor, uint16_t row, bool descending, uint16_t col) {
  open(cursor, row, descending);
  Cursor& c = cursors_[cursor];
  const bool down = c.flags & kDescending;  // an empty row's cursor walks up, whatever was asked
  const int32_t bound = c.bound, at = col;
  if (down ? c.pos < bound : c.pos > bound) return;  // an empty row
  if (down ? at >= c.pos : at <= c.pos) return;      // the row's first non-zero cell that way is at or past col
  if (down ? at < bound : at > bound) {
    c.pos = static_cast<int16_t>(down ? bound - 1 : bound + 1);  // past the row's last non-zero cell
    return;
  }
  c.pos = static_cast<int16_t>(at);  // straight there: the cells file is read at any column
  c.flags &= static_cast<uint8_t>(~kChunkHeld);
  uint16_t here;
  uint8_t value;
  if (this->at(cursor, here, value) && !value) step(cursor);
}

bool SdCells::fill(uint8_t cursor) {
  Cursor& c = cursors_[cursor];
  // The aligned chunk that holds pos, cut to the cells still ahead of the walk (so never outside
  // the row: pos is inside it, and bound is its far end).
  int32_t at = c.pos & ~static_cast<int32_t>(kChunk - 1);
  int32_t start = at, end = at + kChunk - 1;
  if (c.flags & kDescending) {
    if (start < c.bound) start = c.bound;
    if (end > c.pos) end = c.pos;
  } else {
    if (start < c.pos) start = c.pos;
    if (end > c.bound) end = c.bound;
  }
  uint8_t n = static_cast<uint8_t>(end - start + 1);
  if (!sd_.seek(cells_, c.base + static_cast<uint32_t>(start)) ||
      sd_.read(cells_, reinterpret_cast<char*>(c.chunk) + (start - at), n) != n) {
    failed_ = true;
    return false;
  }
  c.flags |= kChunkHeld;
  return true;
}

bool SdCells::at(uint8_t cursor, uint16_t& col, uint8_t& value) {
  Cursor& c = cursors_[cursor];
  const int32_t bound = c.bound;  // int is 16 bits on the AVR: compare as int32, not unsigned
  if ((c.flags & kDescending) ? c.pos < bound : c.pos > bound) return false;
  if (!(c.flags & kChunkHeld) && !fill(cursor)) return false;
  col = static_cast<uint16_t>(c.pos);
  value = c.chunk[c.pos & (kChunk - 1)];
  return true;
}

void SdCells::step(uint8_t cursor) {
  Cursor& c = cursors_[cursor];
  const bool down = c.flags & kDescending;
  const int32_t bound = c.bound;
  while (down ? c.pos >= bound : c.pos <= bound) {
    int16_t p = c.pos;
    c.pos = static_cast<int16_t>(p + (down ? -1 : 1));
    if ((c.pos & ~(kChunk - 1)) != (p & ~(kChunk - 1))) c.flags &= static_cast<uint8_t>(~kChunkHeld);  // left the chunk
    if (down ? c.pos < bound : c.pos > bound) return;  // walked past the row's last non-zero cell
    if (!(c.flags & kChunkHeld) && !fill(cursor)) {
      c.pos = static_cast<int16_t>(down ? bound - 1 : bound + 1);  // a failed read ends the walk (failed())
      return;
    }
    if (c.chunk[c.pos & (kChunk - 1)]) return;
  }
}

}  // namespace mega
