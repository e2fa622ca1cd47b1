// A CellSource over a grid held in memory: the host tests' and the golden tool's view of a job.
#pragma once
#include <cstdint>
#include <vector>

#include "cell_source.h"
#include "planner.h"

namespace uvtest {

// Reads rows in place: no allocation after construction, so tests can count the planner's own.
class GridCells : public uv::CellSource {
 public:
  explicit GridCells(const std::vector<std::vector<uint8_t>>& rows) : rows_(rows) {}

  bool rowNonEmpty(uint16_t row) override {
    for (uint8_t v : rows_[row])
      if (v) return true;
    return false;
  }
  bool rowExtent(uint16_t row, uint16_t& first, uint16_t& last) override {
    const auto& r = rows_[row];
    int lo = -1, hi = -1;
    for (size_t c = 0; c < r.size(); c++)
      if (r[c]) {
        if (lo < 0) lo = static_cast<int>(c);
        hi = static_cast<int>(c);
      }
    if (lo < 0) return false;
    first = static_cast<uint16_t>(lo);
    last = static_cast<uint16_t>(hi);
    return true;
  }
  void open(uint8_t cursor, uint16_t row, bool descending) override {
    Cursor& c = cursors_[cursor];
    c.row = row;
    c.descending = descending;
    c.pos = descending ? static_cast<int>(rows_[row].size()) - 1 : 0;
    settle(c);
    rowsOpened++;
  }
  bool at(uint8_t cursor, uint16_t& col, uint8_t& value) override {
    const Cursor& c = cursors_[cursor];
    if (!inside(c)) return false;
    col = static_cast<uint16_t>(c.pos);
    value = rows_[c.row][c.pos];
    return true;
  }
  void step(uint8_t cursor) override {
    Cursor& c = cursors_[cursor];
    if (!inside(c)) return;
    c.pos += c.descending ? -1 : 1;
    settle(c);
  }

  int rowsOpened = 0;

 private:
  struct Cursor {
    uint16_t row = 0;
    int pos = 0;  // the non-zero cell it stands on, or past the row's end
    bool descending = false;
  };
  bool inside(const Cursor& c) const { return c.pos >= 0 && c.pos < static_cast<int>(rows_[c.row].size()); }
  // Walks on from pos to the first non-zero cell.
  void settle(Cursor& c) {
    while (inside(c) && !rows_[c.row][c.pos]) c.pos += c.descending ? -1 : 1;
  }
  const std::vector<std::vector<uint8_t>>& rows_;
  Cursor cursors_[uv::kPlannerCursors];
};

}  // namespace uvtest
