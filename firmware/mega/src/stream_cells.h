// Stream mode's buffer (M828): the cells of rows that have arrived and that a stop still to come
// may read, kept as segments (row, column, cells) in a fixed byte buffer, and the planner's
// CellSource over them. Rows are freed from the bottom as the planner leaves them behind.
#pragma once
#include <stdint.h>

#include "cell_source.h"
#include "planner.h"

namespace mega {

class StreamCells : public uv::CellSource {
 public:
  // `buffer` holds the segments: 5 bytes of header and the cells each.
  StreamCells(uint8_t* buffer, uint16_t size) : buf_(buffer), size_(size) {}

  // Appends a segment of a row at or above the last one's; false if it does not fit.
  bool add(uint16_t row, uint16_t col, const uint8_t* cells, uint8_t n);
  // Forgets every row below `row`.
  void freeBelow(uint16_t row);
  uint16_t used() const { return used_; }
  uint16_t cells() const { return cells_; }
  uint16_t size() const { return size_; }

  bool rowNonEmpty(uint16_t row) override;
  bool rowExtent(uint16_t row, uint16_t& first, uint16_t& last) override;
  void open(uint8_t cursor, uint16_t row, bool descending) override;
  void openAt(uint8_t cursor, uint16_t row, bool descending, uint16_t col) override;
  bool at(uint8_t cursor, uint16_t& col, uint8_t& value) override;
  void step(uint8_t cursor) override;

 private:
  static constexpr uint8_t kHead = 5;
  uint16_t segRow(uint16_t at) const { return static_cast<uint16_t>(buf_[at] | buf_[at + 1] << 8); }
  uint16_t segCol(uint16_t at) const { return static_cast<uint16_t>(buf_[at + 2] | buf_[at + 3] << 8); }
  uint8_t segLen(uint16_t at) const { return buf_[at + 4]; }
  // The offset of the row's first segment, or used_ if it has none.
  uint16_t find(uint16_t row) const;
  // The segment before `at` within the same row, or 0xffff.
  uint16_t before(uint16_t at, uint16_t row) const;

  struct Cursor {
    uint16_t row;
    uint16_t seg;    // offset of the segment being read, 0xffff when done
    uint8_t pos;     // the non-zero cell it stands on
    bool descending;
  };
  // Walks a cursor on from its cell to the first non-zero one (or to done).
  void settle(Cursor& c) const;

  uint8_t* buf_;
  uint16_t size_;
  uint16_t used_ = 0;
  uint16_t cells_ = 0;
  Cursor cursors_[uv::kPlannerCursors];
};

}  // namespace mega
