// Where the planner reads a job's cells: a row at a time through one cursor per LED, never the whole grid.
#pragma once
#include <stdint.h>

namespace uv {

class CellSource {
 public:
  // Any cell of the row above 0.
  virtual bool rowNonEmpty(uint16_t row) = 0;
  // First and last column with a value above 0; false for an empty row.
  virtual bool rowExtent(uint16_t row, uint16_t& first, uint16_t& last) = 0;
  // Points cursor 0-3 at a row; next() then yields its non-zero cells ascending, or descending.
  virtual void open(uint8_t cursor, uint16_t row, bool descending) = 0;
  virtual bool next(uint8_t cursor, uint16_t& col, uint8_t& value) = 0;
};

}  // namespace uv
