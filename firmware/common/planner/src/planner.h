// The exposure planner (protocol/planner.md): streams a job's stops one at a time from a CellSource.
#pragma once
#include <stdint.h>

#include "cell_source.h"
#include "job_types.h"
#include "time_model.h"

namespace uv {

constexpr uint16_t kPlannerMaxRows = kJobMaxSide;
// Rows already given to a pass are marked in a ring this many rows long. A pass marks rows from the
// lowest open row up to the LEDs' spread in rows above it, so the C++ planner takes jobs whose LED
// rows (dy) span less than this; supported() says so.
constexpr uint16_t kCoveredWindowRows = 1024;
constexpr uint8_t kRandomBlock = 32;
constexpr uint8_t kShortestBand = 8;                 // passes per band for `shortest`
constexpr uint8_t kPlannerCursors = 4 * kShortestBand;  // CellSource cursors the planner may use
// The bound the host tests hold the planner to: its whole state, at any grid size.
constexpr uint16_t kPlannerMaxBytes = 1400;

// t_k(v) for one LED: round(full_k × gain_k × m(v) / 255000).
class Durations {
 public:
  explicit Durations(const JobHeader& h);
#ifdef __AVR__
  uint32_t us(uint8_t led, uint8_t value) const;
#else
  uint32_t us(uint8_t led, uint8_t value) const { return table_[led][value]; }
#endif
  uint32_t longest(const uint8_t value[4]) const;
  // The four LEDs' durations for a stop's values.
  void each(const uint8_t value[4], uint32_t out[4]) const {
    for (uint8_t k = 0; k < 4; k++) out[k] = us(k, value[k]);
  }

 private:
  // full_k × gain_k = whole_k × 255000 + part_k: a duration is then whole_k × m plus a quotient of at
  // most 255, with no 64-bit division (38 µs each on the Mega, where scan events want durations fast).
  uint32_t whole_[4], part_[4];
  bool linear_;
  uint8_t level_;
#ifndef __AVR__
  uint32_t compute(uint8_t led, uint8_t value) const;
  // Off the AVR, every value's duration worked out once (4 KB): the planners look a cell's up several
  // times a pass, and the division took 14 % of planning a scan of a board. The Nano's and Mega's RAM
  // has no room for it.
  uint32_t table_[4][256];

 public:
  // What the table adds off the AVR: a planner's size bound (kPlannerMaxBytes) is the Mega's.
  static constexpr uint16_t kTableBytes = sizeof(uint32_t) * 4 * 256;
#else

 public:
  static constexpr uint16_t kTableBytes = 0;
#endif
};

class Planner {
 public:
  Planner(const JobHeader& h, CellSource& cells, const MotionModel& m);

  // The next stop in execution order; false when the job is done, or when starved().
  bool next(Stop& out);
  // Stream mode (planner.md "Planning while rows arrive"): rows below `known` have arrived. The
  // planner plans only stops no later row can change; next() then says false with starved() true
  // until more rows are known. Without a call, every row is known.
  void setKnownRows(uint16_t known) { known_ = known; }
  bool starved() const { return starved_; }
  // The lowest row a stop still to come can read (rows below it may be forgotten).
  int32_t lowestRowNeeded() const;
  // The LEDs' rows span less than kCoveredWindowRows; otherwise next() plans nothing.
  bool supported() const { return dyMax_ - dyMin_ < static_cast<int16_t>(kCoveredWindowRows); }
  uint16_t passes() const { return passes_; }

 private:
  // A head row or column: job.md bounds the grid to kJobMaxSide cells a side and the LEDs' offsets
  // to as many again, so every one fits 16 bits. Held that narrow: a band holds kShortestBand passes
  // and a random block kRandomBlock stops, in the Mega's planning arena.
  using Head = int16_t;
  static_assert(2 * static_cast<int32_t>(kJobMaxSide) < INT16_MAX, "head coordinates must fit a Head");
  struct PassInfo {
    Head hy;
    int16_t row[4];     // the row each LED exposes in this pass, or -1
    Head first, last;   // extent of the pass's non-zero cells in head columns
    bool cells;         // it has non-zero cells
    bool lit;           // it has a stop (known after pricing; assumed for single passes)
  };
  struct Compact {
    Head hx;
    uint8_t value[4];
  };
  enum class Order : uint8_t { Rows, Columns };

  enum class Open : uint8_t { Opened, NoMore, NeedRows };
  Open openPass(PassInfo& p);
  bool startBand();
  void openCursors(uint8_t q, bool descending);
  bool passNext(uint8_t q, bool descending, Head& hx, uint8_t value[4]);
  bool startRowPass();
  void openColumns();
  bool nextColumn();
  bool descendingFor(const PassInfo& p, int32_t x) const;
  uint64_t priceRows();
  uint64_t priceColumns();
  bool columnsDescending(int32_t x) const;
  int32_t X(int32_t hx) const { return static_cast<int32_t>(h_.originUm[0]) + hx * static_cast<int32_t>(h_.pitchUm[0]); }
  int32_t Y(int32_t hy) const { return static_cast<int32_t>(h_.originUm[1]) + hy * static_cast<int32_t>(h_.pitchUm[1]); }
  void emit(int32_t hx, int32_t hy, const uint8_t value[4], Stop& out);

  const JobHeader& h_;
  CellSource& cells_;
  const MotionModel& m_;
  Durations dose_;
  bool covered(int32_t row) const { return covered_[(row & (kCoveredWindowRows - 1)) >> 3] & (1 << (row & 7)); }
  void cover(int32_t row) { covered_[(row & (kCoveredWindowRows - 1)) >> 3] |= static_cast<uint8_t>(1 << (row & 7)); }
  void uncoverBelow(uint16_t row);

  uint8_t covered_[kCoveredWindowRows / 8] = {};
  uint16_t scan_ = 0;  // next row that may open a pass
  int16_t dyMin_ = 0, dyMax_ = 0;
  uint16_t known_;            // rows that have arrived (all, unless streaming)
  bool filling_ = false;      // a band is part opened, waiting for rows
  bool starved_ = false;
  int32_t curX_, curY_;  // bed position of the last stop, µm
  uint16_t passes_ = 0;  // passes that emitted a stop
  uint32_t rng_;

  PassInfo band_[kShortestBand];
  uint8_t bandLen_ = 0;
  Order order_ = Order::Rows;
  bool emitting_ = false;
  // Rows order: the pass being emitted and its direction.
  uint8_t q_ = 0;
  bool desc_ = false;
  uint8_t columnLen_ = 0, columnPos_ = 0;
  bool passUsed_[kShortestBand] = {};

  uint8_t blockLen_ = 0, blockPos_ = 0;
  // Only `shortest` reads columns and only `random` shuffles blocks: they share memory.
  union {
    struct {
      bool peek_[kShortestBand];  // each pass's next stop, and the current column
      Compact peekStop_[kShortestBand];
      uint8_t column_[kShortestBand];
      Compact columnStop_[kShortestBand];
    } col;
    Compact block_[kRandomBlock];
  } shared_;
};

}  // namespace uv
