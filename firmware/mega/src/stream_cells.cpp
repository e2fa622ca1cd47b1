// Stream mode's buffer: segments of arrived rows, and the planner's CellSource over them.
#include "stream_cells.h"

#include <string.h>

namespace mega {

bool StreamCells::add(uint16_t row, uint16_t col, const uint8_t* cells, uint8_t n) {
  if (used_ + kHead + n > size_) return false;
  uint8_t* p = buf_ + used_;
  p[0] = static_cast<uint8_t>(row);
  p[1] = static_cast<uint8_t>(row >> 8);
  p[2] = static_cast<uint8_t>(col);
  p[3] = static_cast<uint8_t>(col >> 8);
  p[4] = n;
  memcpy(p + kHead, cells, n);
  used_ = static_cast<uint16_t>(used_ + kHead + n);
  cells_ = static_cast<uint16_t>(cells_ + n);
  return true;
}

void StreamCells::freeBelow(uint16_t row) {
  uint16_t at = 0;
  uint16_t freed = 0;
  while (at < used_ && segRow(at) < row) {
    freed = static_cast<uint16_t>(freed + segLen(at));
    at = static_cast<uint16_t>(at + kHead + segLen(at));
  }
  if (!at) return;
  memmove(buf_, buf_ + at, used_ - at);  // segments are in row order: the freed ones are in front
  used_ = static_cast<uint16_t>(used_ - at);
  cells_ = static_cast<uint16_t>(cells_ - freed);
  for (Cursor& c : cursors_) {
    if (c.seg == 0xffff) continue;
    c.seg = c.seg >= at ? static_cast<uint16_t>(c.seg - at) : 0xffff;  // a cursor in a freed row is done
  }
}

uint16_t StreamCells::find(uint16_t row) const {
  uint16_t at = 0;
  while (at < used_ && segRow(at) < row) at = static_cast<uint16_t>(at + kHead + segLen(at));
  return at < used_ && segRow(at) == row ? at : used_;
}

uint16_t StreamCells::before(uint16_t at, uint16_t row) const {
  uint16_t prev = 0xffff;
  for (uint16_t s = find(row); s < at; s = static_cast<uint16_t>(s + kHead + segLen(s))) prev = s;
  return prev;
}

bool StreamCells::rowNonEmpty(uint16_t row) {
  for (uint16_t at = find(row); at < used_ && segRow(at) == row; at = static_cast<uint16_t>(at + kHead + segLen(at)))
    for (uint8_t i = 0; i < segLen(at); i++)
      if (buf_[at + kHead + i]) return true;
  return false;
}

bool StreamCells::rowExtent(uint16_t row, uint16_t& first, uint16_t& last) {
  bool any = false;
  for (uint16_t at = find(row); at < used_ && segRow(at) == row; at = static_cast<uint16_t>(at + kHead + segLen(at))) {
    for (uint8_t i = 0; i < segLen(at); i++) {
      if (!buf_[at + kHead + i]) continue;
      uint16_t c = static_cast<uint16_t>(segCol(at) + i);
      if (!any) first = c;
      last = c;
      any = true;
    }
  }
  return any;
}

void StreamCells::open(uint8_t cursor, uint16_t row, bool descending) {
  Cursor& c = cursors_[cursor];
  c.row = row;
  c.descending = descending;
  uint16_t at = find(row);
  if (at == used_) {
    c.seg = 0xffff;
    return;
  }
  if (descending) {  // the row's last segment, from its last cell
    uint16_t last = at;
    for (uint16_t s = at; s < used_ && segRow(s) == row; s = static_cast<uint16_t>(s + kHead + segLen(s))) last = s;
    at = last;
  }
  c.seg = at;
  c.pos = descending ? static_cast<uint8_t>(segLen(at) - 1) : 0;
  settle(c);
}

void StreamCells::openAt(uint8_t cursor, uint16_t row, bool descending, uint16_t col) {
  open(cursor, row, descending);
  Cursor& c = cursors_[cursor];
  // From segment to segment, not cell to cell, until the one that holds col or the first beyond it.
  while (c.seg != 0xffff) {
    const uint16_t first = segCol(c.seg), n = segLen(c.seg), here = static_cast<uint16_t>(first + c.pos);
    if (descending ? here <= col : here >= col) return;
    if (descending ? col >= first : col < first + n) {
      c.pos = static_cast<uint8_t>(col - first);
    } else {
      c.pos = descending ? static_cast<uint8_t>(0xff) : static_cast<uint8_t>(n);  // past this segment
    }
    settle(c);
  }
}

bool StreamCells::at(uint8_t cursor, uint16_t& col, uint8_t& value) {
  const Cursor& c = cursors_[cursor];
  if (c.seg == 0xffff) return false;
  col = static_cast<uint16_t>(segCol(c.seg) + c.pos);
  value = buf_[c.seg + kHead + c.pos];
  return true;
}

void StreamCells::step(uint8_t cursor) {
  Cursor& c = cursors_[cursor];
  if (c.seg == 0xffff) return;
  c.pos = c.descending ? static_cast<uint8_t>(c.pos - 1) : static_cast<uint8_t>(c.pos + 1);
  settle(c);
}

void StreamCells::settle(Cursor& c) const {
  while (c.seg != 0xffff) {
    uint8_t n = segLen(c.seg);
    if (c.pos < n) {  // pos wraps to 255 past the front when descending
      if (buf_[c.seg + kHead + c.pos]) return;
      c.pos = c.descending ? static_cast<uint8_t>(c.pos - 1) : static_cast<uint8_t>(c.pos + 1);
      continue;
    }
    if (c.descending) {
      c.seg = before(c.seg, c.row);
      if (c.seg != 0xffff) c.pos = static_cast<uint8_t>(segLen(c.seg) - 1);
    } else {
      uint16_t s = static_cast<uint16_t>(c.seg + kHead + n);
      c.seg = s < used_ && segRow(s) == c.row ? s : 0xffff;
      c.pos = 0;
    }
  }
}

}  // namespace mega
