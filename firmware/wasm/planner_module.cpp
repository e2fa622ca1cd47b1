// The exposure planners (firmware/common/planner) as a WebAssembly reactor for the app's work worker:
// a job's header and cells in, its plan in any order, the six orders' estimates and a move's time out.
//
// No allocator: the planners keep their state in themselves, the job's cells and the plan's words are
// laid out from the heap's start, and memory grows for them (app/src/planner/planner-wasm.ts reads
// the words; their layout is described there and at each writer below).
#include <stdint.h>

#include "planner.h"
#include "scan.h"
#include "time_model.h"

extern "C" unsigned char __heap_base;

#define EXPORT(name) extern "C" __attribute__((export_name(name)))

namespace {

constexpr uint32_t kPage = 65536;

// Makes the memory reach `end` (a byte address); false when it cannot grow.
bool reach(uintptr_t end) {
  const uintptr_t have = __builtin_wasm_memory_size(0) * kPage;
  if (end <= have) return true;
  uintptr_t pages = (end - have + kPage - 1) / kPage;
  const uintptr_t more = have / kPage / 4;  // a quarter more at least: a plan's words come one at a time
  if (pages < more) pages = more;
  return __builtin_wasm_memory_grow(0, pages) != static_cast<uintptr_t>(-1);
}

// The job as the app writes it: header words (planner-wasm.ts headerWords), the machine's words, and
// cols × rows cell bytes, row by row, from the heap's start.
int32_t gHeader[32];
int32_t gMachine[12];
uint8_t* const gCells = &__heap_base;
uint16_t gCols = 0, gRows = 0;

uv::JobHeader header(uv::Strategy strategy) {
  const int32_t* w = gHeader;
  uv::JobHeader h{};
  h.cols = static_cast<uint16_t>(w[0]);
  h.rows = static_cast<uint16_t>(w[1]);
  h.pitchUm[0] = static_cast<uint32_t>(w[2]);
  h.pitchUm[1] = static_cast<uint32_t>(w[3]);
  h.originUm[0] = static_cast<uint32_t>(w[4]);
  h.originUm[1] = static_cast<uint32_t>(w[5]);
  h.map = w[6] ? uv::DoseMap::Threshold : uv::DoseMap::Linear;
  h.level = static_cast<uint8_t>(w[7]);
  h.byTarget = w[8] != 0;
  h.fullUs = static_cast<uint32_t>(w[9]);
  h.targetUJcm2 = static_cast<uint32_t>(w[10]);
  for (int k = 0; k < 4; k++) {
    h.irradianceUWcm2[k] = static_cast<uint32_t>(w[11 + k]);
    h.gainPermille[k] = static_cast<uint16_t>(w[15 + k]);
    h.offsets[k][0] = static_cast<int16_t>(w[19 + 2 * k]);
    h.offsets[k][1] = static_cast<int16_t>(w[20 + 2 * k]);
  }
  h.strategy = strategy;
  h.seed = static_cast<uint32_t>(w[28]);
  h.thermalCoeff = static_cast<int16_t>(w[29]);
  h.thermalRefDeciC = static_cast<int16_t>(w[30]);
  return h;
}

uv::MotionModel machine() {
  const int32_t* w = gMachine;
  uv::MotionModel m{};
  for (int a = 0; a < 2; a++) {
    m.vmaxUmS[a] = static_cast<uint32_t>(w[a]);
    m.accelUmS2[a] = static_cast<uint32_t>(w[2 + a]);
    m.startUm[a] = w[6 + a];
    m.stepsMilli[a] = static_cast<uint32_t>(w[8 + a]);
  }
  m.settleUs = static_cast<uint32_t>(w[4]);
  m.overheadUs = static_cast<uint32_t>(w[5]);
  m.linkBaud = static_cast<uint32_t>(w[10]);
  return m;
}

// The cells in memory as the planners read them: a row at a time, through cursors.
class MemoryCells : public uv::CellSource {
 public:
  bool rowNonEmpty(uint16_t row) override {
    const uint8_t* r = rowAt(row);
    for (uint16_t c = 0; c < gCols; c++)
      if (r[c]) return true;
    return false;
  }
  bool rowExtent(uint16_t row, uint16_t& first, uint16_t& last) override {
    const uint8_t* r = rowAt(row);
    int32_t lo = 0, hi = gCols - 1;
    while (lo < gCols && !r[lo]) lo++;
    if (lo == gCols) return false;
    while (!r[hi]) hi--;
    first = static_cast<uint16_t>(lo);
    last = static_cast<uint16_t>(hi);
    return true;
  }
  void open(uint8_t cursor, uint16_t row, bool descending) override {
    openAt(cursor, row, descending, descending ? static_cast<uint16_t>(gCols - 1) : 0);
  }
  // Straight to the column, as the card and the stream go.
  void openAt(uint8_t cursor, uint16_t row, bool descending, uint16_t col) override {
    Cursor& c = cursors_[cursor];
    c.row = rowAt(row);
    c.step = descending ? -1 : 1;
    c.pos = col;
    settle(c);
  }
  bool at(uint8_t cursor, uint16_t& col, uint8_t& value) override {
    const Cursor& c = cursors_[cursor];
    if (!inside(c)) return false;
    col = static_cast<uint16_t>(c.pos);
    value = c.row[c.pos];
    return true;
  }
  void step(uint8_t cursor) override {
    Cursor& c = cursors_[cursor];
    if (!inside(c)) return;
    c.pos += c.step;
    settle(c);
  }

 private:
  struct Cursor {
    const uint8_t* row;
    int32_t pos;  // the non-zero cell it stands on, or past the row's end
    int32_t step;
  };
  static const uint8_t* rowAt(uint16_t row) { return gCells + static_cast<uint32_t>(row) * gCols; }
  static bool inside(const Cursor& c) { return c.pos >= 0 && c.pos < gCols; }
  static void settle(Cursor& c) {
    while (inside(c) && !c.row[c.pos]) c.pos += c.step;
  }
  Cursor cursors_[uv::kPlannerCursors] = {};
};

// The plan's words, after the cells; word 0 says how many there are.
uint32_t* gOut = nullptr;
uint32_t gOutWords = 0, gOutCap = 0;
bool gOutFull = false;  // the memory would not grow: the plan is cut short and says so

void begin() {
  const uintptr_t at = (reinterpret_cast<uintptr_t>(gCells) + static_cast<uint32_t>(gCols) * gRows + 7) & ~uintptr_t{7};
  gOut = reinterpret_cast<uint32_t*>(at);
  gOutCap = static_cast<uint32_t>((__builtin_wasm_memory_size(0) * kPage - at) / 4);
  gOutWords = 1;
  gOutFull = false;
}

void put(uint32_t w) {
  if (gOutWords == gOutCap) {
    if (gOutFull || !reach(reinterpret_cast<uintptr_t>(gOut + gOutWords + 1))) {
      gOutFull = true;
      return;
    }
    gOutCap = static_cast<uint32_t>((__builtin_wasm_memory_size(0) * kPage - reinterpret_cast<uintptr_t>(gOut)) / 4);
  }
  gOut[gOutWords++] = w;
}
void put64(uint64_t w) {
  put(static_cast<uint32_t>(w));
  put(static_cast<uint32_t>(w >> 32));
}
void set64(uint32_t at, uint64_t w) {
  gOut[at] = static_cast<uint32_t>(w);
  gOut[at + 1] = static_cast<uint32_t>(w >> 32);
}
const uint32_t* finish() {
  gOut[0] = gOutFull ? 0 : gOutWords;
  return gOut;
}

void putStop(const uv::Stop& s) {
  put(static_cast<uint32_t>(s.hx));
  put(static_cast<uint32_t>(s.hy));
  for (uint32_t us : s.us) put(us);
}

// A stop plan: count, passes, estimate (2 words), travel X, Y (2 words each), then hx, hy, µs × 4 a stop.
void planStops(const uv::JobHeader& h, const uv::MotionModel& m, uint32_t known) {
  MemoryCells cells;
  uv::Planner planner(h, cells, m);
  if (known < h.rows) planner.setKnownRows(static_cast<uint16_t>(known));
  uv::PlanClock clock(h, m);
  const uint32_t head = gOutWords;
  for (int i = 0; i < 8; i++) put(0);
  uint32_t count = 0;
  uv::Stop s;
  while (planner.next(s)) {
    clock.add(s);
    putStop(s);
    count++;
  }
  if (gOutFull) return;
  gOut[head] = count;
  gOut[head + 1] = planner.passes();
  set64(head + 2, clock.totalUs());
  set64(head + 4, clock.travelUm(0));
  set64(head + 6, clock.travelUm(1));
}

// A pass's events as its link check walks them, for the plan's words (ScanPlanner::keepEvents): room
// for the densest pass of a photo 2048 cells wide (8 switches a window); a denser one is walked again.
constexpr uint32_t kLoggedEvents = 16384;
uint32_t gLogT[kLoggedEvents];
uint8_t gLogState[kLoggedEvents];
uv::ScanPlanner::EventLog gLog{gLogT, gLogState, kLoggedEvents};

// A pass on the move: hy, descending, first, last, its window, accelUs, overscanUm, runUpUm,
// runOutUm, moveUs, startSteps, stopSteps, strokeUs, markUs, its time in the estimate (2 words),
// its chain's bytes and its first two programs' (ScanPlanner::chainBytes); its jumps (count, then
// window, windows, µs each) and its events as the Nano runs them (count, then t, state each).
void putScanPass(uv::ScanPlanner& planner, const uv::ScanPass& p) {
  const uv::ScanMotion& own = planner.passMotion();
  const uint32_t fields[] = {static_cast<uint32_t>(p.hy), p.descending, static_cast<uint32_t>(p.first), static_cast<uint32_t>(p.last),
                             own.windowUs, own.accelUs, own.overscanUm, static_cast<uint32_t>(p.runUpUm), static_cast<uint32_t>(p.runOutUm),
                             p.moveUs, static_cast<uint32_t>(p.startSteps), static_cast<uint32_t>(p.stopSteps), p.strokeUs, p.markUs};
  for (uint32_t f : fields) put(f);
  put64(p.scanUs);
  put(planner.chainBytes());
  put(planner.chainAheadBytes());
  put(planner.jumps());
  for (uint8_t i = 0; i < planner.jumps(); i++) {
    uint32_t window, windows, flyUs;
    planner.jump(i, window, windows, flyUs);
    put(window);
    put(windows);
    put(flyUs);
  }
  const uint32_t count = gOutWords;
  put(0);
  uint32_t t, n = 0;
  uint8_t state;
  while (planner.nextEvent(t, state)) {
    put(t);
    put(state);
    n++;
  }
  if (!gOutFull) gOut[count] = n;
}

// How a scan or mixed plan ended: 0 planned, 1 empty (a window past the 32-bit switch times, or LED
// rows too far apart), 2 refused by the step engine at the window that follows.
void putEnding(uint32_t at, const uv::ScanPlanner& planner) {
  if (gOutFull) return;
  gOut[at] = planner.refused() ? 2 : planner.supported() ? 0 : 1;
  gOut[at + 1] = planner.passMotion().windowUs;
}

// A scan plan: the job's window, speed, accelUs, overscanUm, estimate (2 words), ending (2 words),
// passes, then each pass (putScanPass).
void planScan(const uv::JobHeader& h, const uv::MotionModel& m, uint32_t known, bool neverFly) {
  MemoryCells cells;
  uv::ScanPlanner planner(h, cells, m);
  planner.keepEvents(&gLog);
  if (neverFly) planner.neverFly();
  if (known < h.rows) planner.setKnownRows(static_cast<uint16_t>(known));
  const uv::ScanMotion motion = planner.motion();
  const uint32_t fields[] = {motion.windowUs, motion.speedUmS, motion.accelUs, motion.overscanUm};
  for (uint32_t f : fields) put(f);
  const uint32_t head = gOutWords;
  for (int i = 0; i < 5; i++) put(0);
  uint32_t passes = 0;
  uv::ScanPass p;
  for (; planner.nextPass(p); passes++) putScanPass(planner, p);
  if (gOutFull) return;
  set64(head, planner.estimateUs());
  putEnding(head + 2, planner);
  gOut[head + 4] = passes;
}

// A mixed plan: the job's window, steps, estimate (2 words), ending (2 words), passes, then each
// pass: on the move (bit 0) and descending (bit 1), its band, hy, first, last, scanUs and stopsUs
// (2 words each); then a pass on the move (putScanPass), or stops (count, then as a stop plan's).
void planMixed(const uv::JobHeader& h, const uv::MotionModel& m, uint32_t known) {
  MemoryCells cells;
  uv::ScanPlanner planner(h, cells, m);
  planner.keepEvents(&gLog);
  if (known < h.rows) planner.setKnownRows(static_cast<uint16_t>(known));
  put(planner.motion().windowUs);
  const uint32_t head = gOutWords;
  for (int i = 0; i < 6; i++) put(0);
  uint32_t passes = 0, steps = 0;
  uv::ScanPass p;
  for (; planner.nextPass(p); passes++) {
    put((p.stops ? 0u : 1u) | (p.descending ? 2u : 0u));
    put(p.band);
    put(static_cast<uint32_t>(p.hy));
    put(static_cast<uint32_t>(p.first));
    put(static_cast<uint32_t>(p.last));
    put64(p.scanUs);
    put64(p.stopsUs);
    if (!p.stops) {
      putScanPass(planner, p);
      steps++;
      continue;
    }
    const uint32_t count = gOutWords;
    put(0);
    uint32_t n = 0;
    uv::Stop s;
    for (; planner.nextStop(s); n++) putStop(s);
    if (!gOutFull) gOut[count] = n;
    steps += n;
  }
  if (gOutFull) return;
  gOut[head] = steps;
  set64(head + 1, planner.estimateUs());
  putEnding(head + 3, planner);
  gOut[head + 5] = passes;
}

}  // namespace

// Where the app writes the job's header words (31) and the machine's (11).
EXPORT("planner_header") int32_t* plannerHeader() { return gHeader; }
EXPORT("planner_machine") int32_t* plannerMachine() { return gMachine; }

// Where the app writes the job's cells, cols × rows bytes row by row; 0 when memory cannot hold them.
EXPORT("planner_cells") uint8_t* plannerCells(uint32_t cols, uint32_t rows) {
  if (cols > uv::kJobMaxSide || rows > uv::kJobMaxSide || !reach(reinterpret_cast<uintptr_t>(gCells) + cols * rows + 8)) return nullptr;
  gCols = static_cast<uint16_t>(cols);
  gRows = static_cast<uint16_t>(rows);
  return gCells;
}

// The job planned in the header's order (0-5, uv::Strategy), with rows from `known` on yet to come;
// `neverFly` for a scan that crosses every blank stretch. The plan's words; word 0 their count, or 0
// when memory could not hold them.
EXPORT("planner_plan") const uint32_t* plannerPlan(uint32_t strategy, uint32_t known, uint32_t neverFly) {
  const uv::Strategy s = static_cast<uv::Strategy>(strategy);
  const uv::JobHeader h = header(s);
  const uv::MotionModel m = machine();
  begin();
  if (s == uv::Strategy::Scan) planScan(h, m, known, neverFly != 0);
  else if (s == uv::Strategy::Mixed) planMixed(h, m, known);
  else planStops(h, m, known);
  return finish();
}

// Each of the six orders (uv::Strategy's): its estimate (2 words), its steps (stops, or passes on the
// move and stops), its ending (putEnding's code), whether it has strokes on the move, and their
// lowest and highest X step. The app weighs them (job-plan.ts orderEstimates).
EXPORT("planner_estimates") const uint32_t* plannerEstimates() {
  const uv::MotionModel m = machine();
  begin();
  for (uint8_t o = 0; o < uv::kStrategyCount; o++) {
    const uv::Strategy s = static_cast<uv::Strategy>(o);
    const uv::JobHeader h = header(s);
    MemoryCells cells;
    uint64_t estimate = 0;
    uint32_t steps = 0, ending = 0, strokes = 0;
    int32_t lo = 0, hi = 0;
    if (s == uv::Strategy::Scan || s == uv::Strategy::Mixed) {
      uv::ScanPlanner planner(h, cells, m);
      uv::ScanPass p;
      uv::Stop stop;
      while (planner.nextPass(p)) {
        if (p.stops) {
          while (planner.nextStop(stop)) steps++;
          continue;
        }
        steps++;
        const int32_t a = p.startSteps < p.stopSteps ? p.startSteps : p.stopSteps;
        const int32_t b = p.startSteps < p.stopSteps ? p.stopSteps : p.startSteps;
        if (!strokes++ || a < lo) lo = a;
        if (strokes == 1 || b > hi) hi = b;
      }
      estimate = planner.estimateUs();
      ending = planner.refused() ? 2 : planner.supported() ? 0 : 1;
    } else {
      uv::Planner planner(h, cells, m);
      uv::PlanClock clock(h, m);
      uv::Stop stop;
      for (; planner.next(stop); steps++) clock.add(stop);
      estimate = clock.totalUs();
    }
    put64(estimate);
    put(steps);
    put(ending);
    put(strokes != 0);
    put(static_cast<uint32_t>(lo));
    put(static_cast<uint32_t>(hi));
  }
  return finish();
}

// The time model: a move of d µm on one axis from rest to rest on the continuous trapezoid, and the
// step engine's move by (dx, dy) steps on the machine's words.
EXPORT("planner_move_time_us") uint32_t plannerMoveTimeUs(uint32_t d, uint32_t v, uint32_t a) { return uv::moveTimeUs(d, v, a); }
EXPORT("planner_engine_move_us") uint32_t plannerEngineMoveUs(uint32_t dx, uint32_t dy) { return uv::engineMoveUs(machine(), dx, dy); }
// A stop's cost in the time model after a move of (dx, dy) steps, lighting the LEDs for us0 … us3 µs
// (stopCostStepsUs), and an axis's position in steps for `um` µm, on the machine's words.
EXPORT("planner_stop_cost_us") uint32_t plannerStopCostUs(int32_t dx, int32_t dy, uint32_t us0, uint32_t us1, uint32_t us2, uint32_t us3) {
  const uint32_t us[4] = {us0, us1, us2, us3};
  return uv::stopCostStepsUs(machine(), dx, dy, us);
}
EXPORT("planner_axis_steps") int32_t plannerAxisSteps(uint32_t axis, int32_t um) { return uv::axisSteps(machine(), axis ? 1 : 0, um); }
