// The scan planner (protocol/planner.md "Scan mode"): passes exposed on the move, one pass at a time from a CellSource.
#pragma once
#include <stdint.h>

#include "cell_source.h"
#include "job_types.h"
#include "planner.h"
#include "scan_program.h"
#include "time_model.h"

namespace uv {

// The speed of every pass: one cell pitch per window.
struct ScanMotion {
  uint32_t windowUs;    // 0 when nothing is lit
  uint32_t speedUmS;    // round(pitch × 10⁶ / window), for display
  uint32_t accelUs;     // from rest to the speed
  uint32_t overscanUm;  // the distance that takes
};

ScanMotion scanMotion(const JobHeader& h, const Durations& dose, const MotionModel& m);
// The motion of a window of `windowUs`: its speed, time to reach it and the distance that takes.
ScanMotion passMotion(const JobHeader& h, const MotionModel& m, uint32_t windowUs);

struct ScanPass {
  int32_t hy;
  bool descending;        // towards −X
  int32_t first, last;    // head columns of the first and last lit cell; last − first + 1 windows
  int32_t runUpUm, runOutUm;  // bed X where the pass starts and ends at rest
  // The pass as the Mega runs it (planner.md "The stroke"): the step engine's move to the stroke's
  // start, µs; the stroke's X ends in steps; its µs from rest to idle, and the start mark's µs in it.
  uint32_t moveUs;
  int32_t startSteps, stopSteps;
  uint32_t strokeUs, markUs;
  // The run-out, µs from the last window's end to rest; what the pass takes past that rest to be
  // confirmed, kScanPassEndUs from its last window's end less the run-out.
  uint32_t runOutUs, endUs;
  // Mixed mode (planner.md "Mixed mode"): the pass priced as a scan pass and as stops, and the way
  // taken. A stop pass's stops come from nextStop(); its scan fields above say what it would have been.
  uint64_t scanUs, stopsUs;
  bool stops;
  // A band of stops (planner.md "Bands"): its passes (0: one pass, as above). Then hy is its first
  // pass's, descending the columns' direction, first and last its extent, scanUs the band priced pass
  // by pass and stopsUs as this band of stops, whose stops nextStop() hands out column by column.
  uint8_t band;
};

// What a pass does, in the order the planner finds it: an LED's interval of light (merged runs), or
// a blank stretch flown. Each LED's intervals come in time order.
struct ScanEvent {
  bool jump;
  uint8_t led;              // interval: LED `led` is on from `onUs` to `offUs` after the start mark
  uint32_t onUs, offUs;
  uint32_t window, windows;  // jump: the first blank window, how many, and the fly's µs
  uint32_t flyUs;
};

// A pass flies at most this many of its blank stretches (planner.md "Blank stretches"): the Mega
// holds them while the pass runs, for the head's moves.
constexpr uint8_t kMaxJumps = 8;
// A mixed job's band (planner.md "Bands"): this many passes, as `shortest`'s, taken as one group of
// stops column by column when that is cheaper than the passes one by one.
constexpr uint8_t kMixedBand = kShortestBand;

// A scan pass's stroke as the Mega runs it (planner.md "The stroke", firmware/mega/src/scan_stroke.h):
// the G step comes at least this long before the start mark: the G's two bytes at the link's speed
// (linkByteUs: 85 µs at 115200, 40 at 250000), then the Nano's lead (scan_stroke.h markLeadUs).
constexpr uint32_t strokeMarkLeadUs(uint32_t baud) { return kProgramStartLeadUs + 2 * linkByteUs(baud); }
// From a pass's last window's end until the Mega has it confirmed: its Q as the chain's last event is
// due, the Nano's whole answer, and the last program's dose record (scan_run.h kScanEndMarginUs). The
// stroke runs out meanwhile, so the pass costs only what this outlasts the run-out.
constexpr uint32_t kScanPassEndUs = 2000;
// µs the Mega takes to start a pass once its move is done (planner.md "Scan mode"): not a stop's overheadUs.
constexpr uint32_t kScanPassLoadUs = 400;
// The step of a pass at window W, as 16.16 timer ticks; false when the step engine cannot run it
// (over kEngineMaxRate steps/s, or a step of 2¹⁶ ticks, 32.768 ms, or more).
bool engineStep(const MotionModel& m, uint32_t pitchUm, uint32_t windowUs, uint64_t& q16);
// The stroke of a pass at the step `q16` (engineStep) whose start mark and last window's end are at
// twice the bed X `markX2Um` and `endX2Um` (µm), as scan_stroke.cpp lays it out: where it starts and
// stops (X steps), its µs from rest to idle (the ramps as the engine runs them, the middle at the
// exact step, less the flown stretches' `savedUs`), the mark's µs after it starts, and its endUs.
void planStroke(const MotionModel& m, int32_t markX2Um, int32_t endX2Um, bool descending, uint64_t q16, uint32_t savedUs, ScanPass& out);

// CellSource cursors the scan planner opens: one an LED, numbered as the LEDs.
constexpr uint8_t kScanCursors = 4;

// A pass as its planning found it: its window (the link cap's, planner.md "The printhead link"), head
// row, extent and the blank stretches it flies. M29 keeps one for each pass of a scan job on the card
// (firmware/mega/src/kept_pass.h), and the run opens each pass from it: nextPass() then neither reads
// the pass's cells to lay it out (some 63 µs a cell on the Mega) nor walks its events for the link.
struct KeptPass {
  uint32_t windowUs;
  int32_t hy, first, last;
  // The flown stretches by column ascending: each one's lowest column less `first`, and its windows
  // (0: no stretch; a kept one has at least one).
  uint16_t jumpCol[kMaxJumps], jumpG[kMaxJumps];
};

class ScanPlanner {
 public:
  ScanPlanner(const JobHeader& h, CellSource& cells, const MotionModel& m);

  // The job's motion; a pass's own window may be longer (the link cap: planner.md "The printhead
  // link"), and passMotion() is the open pass's.
  // (Worked out when asked: on the Mega, RAM is dearer than the divisions.)
  ScanMotion motion() const { return scanMotion(h_, dose_, m_); }
  const ScanMotion& passMotion() const { return pass_; }
  // The printhead link's speed the plan is made for (MotionModel::linkBaud): its passes need the link at it.
  uint32_t linkBaud() const { return m_.linkBaud; }
  // Opens the next pass with a lit cell and adds its time to the estimate; false when done.
  // `kept`: that pass as planning kept it (keep(); a card job's, kept at M29): opened from it, with
  // no layout and no link check (a walk of every event of the pass, and more when the link caps it).
  // One that is not that pass's, or not one planning could keep, is laid out and searched for here, as
  // without it, and a pass planning dropped (no lit cell) is passed over as planning passed it over.
  // A mixed job's passes are always found here.
  bool nextPass(ScanPass& out, const KeptPass* kept = nullptr);
  // The pass nextPass() just opened (`p`), as nextPass() takes it back.
  void keep(const ScanPass& p, KeptPass& out) const;
  // The current pass's next event; false at its end.
  bool next(ScanEvent& out);
  // Or, instead of next(): the pass as the Nano runs it (protocol/nano.md "Scan programs"), one
  // event per moment an LED switches, in time order: t µs after the start mark, and the state of
  // the four LEDs from then on. false at the pass's end (its last event leaves every LED off).
  bool nextEvent(uint32_t& t, uint8_t& m);
  // The open pass's flown stretches, in its direction: jump i's first blank window, its windows and
  // its µs (the ScanEvent jump's fields), as next() hands them out.
  uint8_t jumps() const { return jumpCount_; }
  void jump(uint8_t i, uint32_t& window, uint32_t& windows, uint32_t& flyUs);
  uint64_t estimateUs() const { return estimate_; }
  uint16_t passes() const { return passes_; }
  // A mixed job's open stop pass (ScanPass::stops): its next stop in the pass's direction, the very
  // stop the stop planner gives; false at the pass's end, and always for a scan pass.
  bool nextStop(Stop& out);
  // A stop pass is open, and nextStop() has not yet said false for it.
  bool inStopPass() const { return live_ & kStopPassBit; }
  // A mixed job's band is priced a pass at a time (planner.md "Bands"): nextPass() says false with
  // pricing() true after each, until the band is priced (the Mega's main loop runs between). Without
  // this call, nextPass() prices a whole band at once. Before the first nextPass().
  void sliceBands() { live_ |= kSlicedBit; }
  bool pricing() const { return bandNext_ == kFilling && bandPriced_ > 0; }
  // As Planner::supported(): the LEDs' rows span less than kCoveredWindowRows. And every switch
  // time fits 32 bits: (cols + the LEDs' spread in X) × window < 2³² µs.
  bool supported() const;
  // The step engine cannot run the job's window, or a pass's (engineStep): nextPass() said false for
  // it, and the Mega refuses the job with E29 (mega.md M29).
  bool refused() const { return refusal_ == Refusal::Engine; }
  // The speed is below the X axis's maximum, so a blank stretch may be flown (planner.md "Blank stretches").
  bool mayFly() const;
  // A machine that cannot fly crosses every blank stretch at the pass's speed: no jumps, S(j) = j·W,
  // and the estimate to match. Before the first nextPass(). (P10's figure without flying.)
  void neverFly() {
    mode_ |= kNeverFly;
    flies_ = false;
  }
  // The Mega runs a scan job's passes and never reads their price: nextPass() then leaves a scan
  // pass's stroke, hop and time unworked (ScanPass's moveUs to endUs, scanUs, startSteps and
  // stopSteps, and estimateUs()), which was most of what opening a kept pass took there (its own
  // stroke and hop are the step engine's: scan_run.cpp). A mixed job's passes are priced, as its
  // choice between scan and stops needs. Before the first nextPass().
  void unpriced() { mode_ |= kUnpriced; }
  // Stream mode, as Planner's: rows below `known` have arrived. nextPass() opens a pass only once
  // every row it reads has arrived; until then it says false with starved() true.
  void setKnownRows(uint16_t known) { known_ = known; }
  bool starved() const { return starved_; }
#ifndef __AVR__
  // Off the AVR a caller may lend the planner a log for a pass's events, `cap` of them (t, state). The
  // link check walks each pass's events once (outrunsLink); with a log, nextEvent() then hands them out
  // from it instead of walking the pass a second time (the app's planner module: that walk was some
  // 45 % of a PCB's scan plan). A pass with more events than the log holds is walked again, as without
  // one. Not on the Mega, whose RAM has no room for it. Before the first nextPass().
  struct EventLog {
    uint32_t* t;
    uint8_t* state;
    uint32_t cap;
  };
  void keepEvents(EventLog* log) { log_ = log; }
  // The pass's chain of programs as the Mega sends it (nano.md "Scan programs"), from its link check
  // at the window it kept: every line's bytes, and those of the first two programs, which load before
  // the pass starts (the bench's link load, P11).
  uint32_t chainBytes() const { return chainBytes_; }
  uint32_t chainAheadBytes() const { return chainAheadBytes_; }
#endif
  // The lowest row a later call may still read: rows below it may be dropped.
  int32_t lowestRowNeeded() const { return bandLen_ && bandHy_[0] + dyMin_ < low_ ? bandHy_[0] + dyMin_ : low_; }

 private:
  bool readLit(uint8_t led, int32_t& hx, uint32_t& us);
  void peek(uint8_t led) { setLive(led, readLit(led, hx_[led], us_[led])); }
  // Bit k for LED k (flags kept as bits: the planner lives in the Mega's job arena).
  bool isLive(uint8_t k) const { return live_ >> k & 1; }
  void setLive(uint8_t k, bool on) { live_ = static_cast<uint8_t>(on ? live_ | (1 << k) : live_ & ~(1 << k)); }
  bool isPending(uint8_t k) const { return u_.iv.pending >> k & 1; }
  void setPending(uint8_t k, bool on) { u_.iv.pending = static_cast<uint8_t>(on ? u_.iv.pending | (1 << k) : u_.iv.pending & ~(1 << k)); }
  // intervals: for next() (its intervals and jumps), else for nextEvent() (the window's on-times).
  bool nextLitWindow(uint32_t& j, bool intervals);
  uint32_t fly(uint32_t g);
  void consider(int32_t col, uint16_t g);
  void stretch(uint8_t i, uint32_t& window, uint32_t& windows) const;  // jump() without its time
  void flush(uint8_t led, ScanEvent& out);
  bool covered(int32_t row) const { return covered_[(row & (kCoveredWindowRows - 1)) >> 3] & (1 << (row & 7)); }
  void cover(int32_t row) { covered_[(row & (kCoveredWindowRows - 1)) >> 3] |= static_cast<uint8_t>(1 << (row & 7)); }
  void uncover(int32_t row) { covered_[(row & (kCoveredWindowRows - 1)) >> 3] &= static_cast<uint8_t>(~(1 << (row & 7))); }
  int32_t X(int32_t hx) const { return static_cast<int32_t>(h_.originUm[0]) + hx * static_cast<int32_t>(h_.pitchUm[0]); }
  int32_t Y(int32_t hy) const { return static_cast<int32_t>(h_.originUm[1]) + hy * static_cast<int32_t>(h_.pitchUm[1]); }

  const JobHeader& h_;
  CellSource& cells_;
  const MotionModel& m_;
  Durations dose_;
  uint8_t covered_[kCoveredWindowRows / 8] = {};
  uint16_t scan_ = 0;  // next row that may open a pass
  uint16_t known_;     // rows that have arrived (all, unless streaming)
  bool starved_ = false;
  int32_t low_ = 0;    // the open pass's lowest row, or the next that may open one
  int16_t dyMin_ = 0, dyMax_ = 0;
  int32_t curX_, curY_;  // where the last pass ended: X in steps, Y in µm
  // The last pass's run-out (µs, 1 to 65535), beside which the next one's hop glides; 0 when the
  // head is at rest (the start, after stops), where the hop is a move as any.
  uint16_t runOut_ = 0;
  uint64_t estimate_ = 0;
  uint16_t passes_ = 0;
  bool flies_;  // the open pass's speed is below the maximum: blank stretches may be flown
  static constexpr uint8_t kNeverFly = 1, kUnpriced = 2;
  uint8_t mode_ = 0;  // neverFly(), unpriced()
  // Why the plan stopped short: a pass the link cap slowed until its switch times outgrew 32 bits
  // (not supported()), or a window the step engine cannot run (refused()).
  enum class Refusal : uint8_t { None, TooLong, Engine };
  Refusal refusal_ = Refusal::None;
  ScanMotion pass_;       // the open pass's motion
  bool layout(int32_t& first, int32_t& last, uint64_t& span);
  // S(n − 1) + W of the open pass from `first` to `last` with its stretches (jumpG_): false when one
  // of them would not fly at the pass's window.
  bool flownSpan(int32_t first, int32_t last, uint64_t& span);
  uint64_t priceStops(int32_t hy, int32_t& endX);
  // Bands (planner.md "Bands", scan_band.cpp): a mixed job's passes, kMixedBand at a time, each band
  // priced pass by pass and as one group of stops column by column, and taken the cheaper way.
  // `kept`: nextPass()'s; `restored`: whether it gave the pass (restore()).
  bool collect(int32_t& hy, int32_t& first, int32_t& last, uint64_t& span, const KeptPass* kept = nullptr, bool* restored = nullptr);
  bool restore(const KeptPass& k, int32_t& first, int32_t& last, uint64_t& span);
  // `found`: the pass's window is known (restored), so the link cap's search is not made.
  bool planPass(int32_t hy, int32_t first, int32_t last, uint64_t span, ScanPass& out, bool found = false);
  bool layOutAt(uint64_t w, int32_t& first, int32_t& last, uint64_t& span);
  // The windows a pass's switch times may span: cols + the LEDs' spread in X (supported()).
  uint64_t switchSpan() const;
  bool nextBand(ScanPass& out);
  void bandRows(uint8_t q);
  int32_t bandPeek(uint8_t q, int32_t from);
  void openBand(int32_t& first, int32_t& last);
  uint64_t priceBand(uint64_t limit, int32_t& endX, int32_t& endY);
  bool bandNextStop(Stop& out);
  // The band's passes: each one's head row, and bit k of its nibble in bandLeds_ when LED k has a row
  // in it; how many; the next to plan pass by pass (kFilling while the band is gathered).
  static constexpr uint8_t kFilling = 0xff;
  static constexpr int16_t kNoColumn = INT16_MIN;
  static constexpr uint8_t kBandBit = 1 << 5;      // live_: the open stop pass is a band of stops
  static constexpr uint8_t kColumnUpBit = 1 << 6;  // live_: its column is taken in descending head row
  int16_t bandHy_[kMixedBand] = {};
  uint32_t bandLeds_ = 0;
  uint8_t bandLen_ = 0, bandNext_ = kFilling;
  // The band being priced: passes priced (bandLen_ + 1 once its stops are too), the head before it,
  // and what its passes priced so far cost (curX_, curY_, estimate_ and passes_ run on meanwhile).
  static constexpr uint8_t kSlicedBit = 1 << 7;  // live_: sliceBands()
  uint8_t bandPriced_ = 0;
  int32_t bandX0_ = 0, bandY0_ = 0;
  uint16_t bandRunOut0_ = 0;
  uint64_t bandUs_ = 0;
  // nextStop() walks the open pass's stops: a flag above the LEDs' bits of live_ (no byte more in
  // the Mega's job arena, whose every byte is spoken for).
  static constexpr uint8_t kStopPassBit = 1 << 4;
  bool stopPass() const { return live_ & kStopPassBit; }
  void setStopPass(bool on) { live_ = static_cast<uint8_t>(on ? live_ | kStopPassBit : live_ & ~kStopPassBit); }
  void openPass();
  bool outrunsLink(uint64_t& need, uint64_t& have);
#ifdef __AVR__
  static bool passEvent(void* ctx, uint32_t& t, uint8_t& m) { return static_cast<ScanPlanner*>(ctx)->nextEvent(t, m); }
#else
  static bool passEvent(void* ctx, uint32_t& t, uint8_t& m);  // and logs them (keepEvents)
  EventLog* log_ = nullptr;
  uint32_t logged_ = 0, logNext_ = 0;  // the open pass's events in log_ (cap + 1: more than it holds), the next to hand out
  bool logging_ = false, replay_ = false;  // the link check is filling log_; nextEvent() hands out log_
  uint32_t chainBytes_ = 0, chainAheadBytes_ = 0;
#endif

  // The current pass and each LED's next lit cell in its direction.
  int16_t row_[4] = {-1, -1, -1, -1};
  bool descending_ = false;
  int32_t start_ = 0;  // head column of window 0
  uint8_t live_ = 0;  // bit k: LED k has a next lit cell, hx_[k] and us_[k]; and kStopPassBit
  int32_t hx_[4] = {};
  uint32_t us_[4] = {};
  // Emission: the last lit window and its start S(j).
  bool started_ = false;
  uint32_t lastJ_ = 0, lastS_ = 0;
  // The flown stretches, by head column ascending: each one's lowest column less `first_`, and
  // its windows. jumpNext_: the next one the pass's direction reaches.
  int32_t first_ = 0;
  uint16_t jumpCol_[kMaxJumps] = {}, jumpG_[kMaxJumps] = {};
  uint8_t jumpCount_ = 0, jumpNext_ = 0;
  struct Edge {
    uint32_t t;
    uint8_t led;
    bool on;
  };
  // What a pass hands out is either intervals (next(), the host tests') or events (nextEvent(), the
  // Mega's), never both for one pass; and a band of stops opens no pass at all. So the three share
  // their bytes (the Mega's job arena has none to spare).
  union Out {
    // next(): each LED's interval not yet closed; the intervals the current window closed, waiting
    // to be handed out; a jump flown before it.
    struct {
      uint8_t pending;  // bit k: LED k's interval is open, pendOn[k] to pendOff[k]
      uint8_t ready;    // bit k: LED k's closed interval waits in readyOn/readyOff
      uint32_t pendOn[4], pendOff[4], readyOn[4], readyOff[4];
      bool jumpReady;
      uint32_t jumpWindow, jumpWindows, jumpUs;
    } iv;
    // nextEvent(): each LED's on-time in the window nextLitWindow() last took (0: none); that
    // window's edges, sorted; the moment being gathered and the state after it; the last state
    // handed out.
    struct {
      uint32_t winUs[4];
      Edge edges[8];
      uint8_t edgeCount, edgeNext;
      bool held;
      uint32_t heldT;
      uint8_t state, emitted;
    } ev;
    // A band of stops (planner.md "Bands"): each pass's next stop's head column (kNoColumn: none),
    // the column being taken, and where the head stood before the band (Y, µm) or the pass of the
    // band's last stop.
    struct {
      int16_t nextHx[kMixedBand];
      int16_t colHx;
      int32_t startY;
      uint8_t lastQ;  // 0xff: no stop yet
    } band;
  } u_ = {};
  bool fillEdges();
};

}  // namespace uv
