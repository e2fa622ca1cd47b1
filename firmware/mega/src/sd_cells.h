// The planner's CellSource over a spooled job on the SD card (the ~c cells and ~i index files).
// Each cursor keeps a few cells of its row in RAM, so walking a row costs one card read per
// kChunk cells, however many cursors the strategy walks side by side.
#pragma once
#include <stdint.h>

#include "cell_source.h"
#include "planner.h"
#include "storage.h"

namespace mega {

class SdCells : public uv::CellSource {
 public:
  static constexpr uint8_t kChunk = 2;  // a power of two; RAM is the limit (32 cursors)

  // 11 bytes a cursor: with the stop planner's 32, the largest part of the planning arena, which is
  // the Mega's largest RAM. So a cursor keeps only what its walk still needs: the bound it walks
  // towards, not the one it left, and whether its chunk still holds the column it is at, not where
  // that chunk began.
  struct Cursor {
    uint32_t base;      // the cells file's offset of column 0 (mod 2^32: the row's first cell, less its column)
    uint16_t bound;     // the row's last column walking up, its first walking down
    int16_t pos;        // the non-zero cell it stands on, or one past its bound once walked
    uint8_t flags;      // kDescending, kChunkHeld
    uint8_t chunk[kChunk];
  };
  // cursors: as many as the planner that reads it opens (SdCellsWith).
  SdCells(Storage& sd, FileHandle cells, FileHandle index, Cursor* cursors) : sd_(sd), cells_(cells), index_(index), cursors_(cursors) {}

  bool rowNonEmpty(uint16_t row) override;
  bool rowExtent(uint16_t row, uint16_t& first, uint16_t& last) override;
  void open(uint8_t cursor, uint16_t row, bool descending) override;
  void openAt(uint8_t cursor, uint16_t row, bool descending, uint16_t col) override;
  bool at(uint8_t cursor, uint16_t& col, uint8_t& value) override;
  void step(uint8_t cursor) override;
  // A read from the card failed at some point: the plan is not to be trusted.
  bool failed() const { return failed_; }

 private:
  struct Row {
    uint32_t offset;
    uint16_t first, last;
  };
  bool readRow(uint16_t row, Row& out);
  bool fill(uint8_t cursor);

  static constexpr uint8_t kDescending = 1, kChunkHeld = 2;  // chunk holds the aligned chunk around pos

  Storage& sd_;
  FileHandle cells_, index_;
  Cursor* const cursors_;
  uint16_t cachedRow_ = 0xffff;
  Row cached_ = {};
  bool failed_ = false;
};

// An SdCells with its cursors beside it: the stop planner opens kPlannerCursors (32) of them, the
// scan planner one an LED, so a scan job on the card does not carry 28 it never opens (308 bytes).
template <uint8_t N>
class SdCellsWith final : public SdCells {
 public:
  SdCellsWith(Storage& sd, FileHandle cells, FileHandle index) : SdCells(sd, cells, index, store_) {}

 private:
  Cursor store_[N];
};

}  // namespace mega
