// Where the planner reads a job's cells: a row at a time through cursors, never the whole grid.
#pragma once
#include <stdint.h>

namespace uv {

// A cursor stands on one non-zero cell of its row at a time. The planners look at that cell several
// times before they move on (the stop planner merges a band's 32 cursors by head column), so the
// cursor itself is where it is kept: there is no second copy of each cursor's cell in the planner.
class CellSource {
 public:
  // Any cell of the row above 0.
  virtual bool rowNonEmpty(uint16_t row) = 0;
  // First and last column with a value above 0; false for an empty row.
  virtual bool rowExtent(uint16_t row, uint16_t& first, uint16_t& last) = 0;
  // Puts a cursor on a row's first non-zero cell, walking up, or its last, walking down.
  virtual void open(uint8_t cursor, uint16_t row, bool descending) = 0;
  // The cell the cursor stands on; false once it has walked past the row's last non-zero cell.
  virtual bool at(uint8_t cursor, uint16_t& col, uint8_t& value) = 0;
  // Moves the cursor on to the next non-zero cell of its row in its direction.
  virtual void step(uint8_t cursor) = 0;

  // Puts a cursor on a row's first non-zero cell at column `col` or beyond it in its direction (a
  // mixed job's band of stops reopens a pass where it left it: planner.md "Bands"). This walks from
  // the row's end; a source that can go straight to a column (the card, the stream) does.
  virtual void openAt(uint8_t cursor, uint16_t row, bool descending, uint16_t col) {
    open(cursor, row, descending);
    uint16_t c;
    uint8_t v;
    while (at(cursor, c, v) && (descending ? c > col : c < col)) step(cursor);
  }

  // The cell the cursor stands on, and the cursor moved on past it.
  bool next(uint8_t cursor, uint16_t& col, uint8_t& value) {
    if (!at(cursor, col, value)) return false;
    step(cursor);
    return true;
  }
};

}  // namespace uv
