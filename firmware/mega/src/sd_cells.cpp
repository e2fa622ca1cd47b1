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
  c.descending = descending;
  c.chunkAt = -1;
  if (!readRow(row, r) || r.first > r.last) {
    c.first = 1;
    c.last = 0;
    c.pos = -1;
    return;
  }
  c.offset = r.offset;
  c.first = r.first;
  c.last = r.last;
  c.pos = static_cast<int16_t>(descending ? r.last : r.first);
}

bool SdCells::fill(uint8_t cursor) {
  Cursor& c = cursors_[cursor];
  // The chunk that holds pos, reaching forwards or backwards as the cursor walks.
  int32_t first = c.first, last = c.last;
  // The aligned chunk that holds pos, cut to the row's cells.
  int32_t at = c.pos & ~static_cast<int32_t>(kChunk - 1);
  int32_t start = at < first ? first : at;
  int32_t end = at + kChunk - 1;
  if (end > last) end = last;
  uint8_t n = static_cast<uint8_t>(end - start + 1);
  if (!sd_.seek(cells_, c.offset + static_cast<uint32_t>(start - first)) ||
      sd_.read(cells_, reinterpret_cast<char*>(c.chunk) + (start - at), n) != n) {
    failed_ = true;
    return false;
  }
  c.chunkAt = static_cast<int16_t>(at);
  return true;
}

bool SdCells::next(uint8_t cursor, uint16_t& col, uint8_t& value) {
  Cursor& c = cursors_[cursor];
  int32_t first = c.first, last = c.last;
  while (c.pos >= first && c.pos <= last) {
    int32_t p = c.pos;
    if (c.chunkAt < 0 || p < c.chunkAt || p >= c.chunkAt + kChunk) {
      if (!fill(cursor)) return false;
    }
    c.pos = static_cast<int16_t>(c.pos + (c.descending ? -1 : 1));
    uint8_t v = c.chunk[p - c.chunkAt];
    if (v) {
      col = static_cast<uint16_t>(p);
      value = v;
      return true;
    }
  }
  return false;
}

}  // namespace mega
