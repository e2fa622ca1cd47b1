// The printhead's two scan-program buffers (protocol/nano.md "Scan programs").
#include "scan_store.h"

namespace nano {
namespace {
// Stores the main loop makes before it publishes a buffer's state stay before it.
inline void barrier() { __asm__ __volatile__("" ::: "memory"); }
}  // namespace

bool ScanStore::append(const char* line, uint8_t len) {
  if (line[0] == 'B') return appendPacked(line, len);
  // Read whole first, so a malformed line is told even while a load is spoiled, and nothing of it
  // is kept. A 63-byte line holds at most 15 events (",d,m" takes at least 4 bytes).
  constexpr uint8_t kLineEvents = (uv::kNanoMaxLine - 3) / 4;
  uint32_t d[kLineEvents];
  uint8_t m[kLineEvents], n = 0;
  uv::AppendLine a;
  bool wellFormed = a.begin(line, len);
  while (wellFormed && n < kLineEvents && a.next(d[n], m[n])) n++;
  if (!wellFormed || a.malformed()) {
    spoil(uv::SealCode::NoLoad);
    return false;
  }
  if (a.seq() == 0) openLoad();
  if (loading_ == kNone) return true;  // a spoiled load drops its lines
  if (a.seq() != nextSeq_) {
    spoil(uv::SealCode::NoLoad);
    return true;
  }
  nextSeq_++;
  Buffer& b = buf_[loading_];
  if (b.count + n > uv::kProgramEvents) {
    spoil(uv::SealCode::TooMany);
    return true;
  }
  for (uint8_t i = 0; i < n; i++) {
    b.words[b.count++] = pack(d[i], m[i]);
    check_ = uv::checkEvent(check_, d[i], m[i]);
  }
  return true;
}

// A B line's words are stored as they come (the word d × 16 + m is pack(d, m)), straight into the
// loading buffer past its count, in one pass: count and check move on only for a line that is whole,
// in sequence and fits, so a malformed one still leaves nothing behind.
bool ScanStore::appendPacked(const char* line, uint8_t len) {
  uv::AppendLine a;
  if (!a.begin(line, len)) {
    spoil(uv::SealCode::NoLoad);
    return false;
  }
  if (a.seq() == 0) openLoad();
  Buffer* b = loading_ != kNone && a.seq() == nextSeq_ ? &buf_[loading_] : nullptr;
  uint8_t n = b ? b->count : 0;
  uint16_t check = check_;
  uint32_t w;
  while (a.nextWord(w)) {
    if (b && n < uv::kProgramEvents) {
      b->words[n] = w;
      check = uv::checkWord(check, w);
    }
    n++;  // at most 64 + 59
  }
  if (a.malformed()) {
    spoil(uv::SealCode::NoLoad);
    return false;
  }
  if (loading_ == kNone) return true;
  if (!b) {
    spoil(uv::SealCode::NoLoad);
    return true;
  }
  nextSeq_++;
  if (n > uv::kProgramEvents) {
    spoil(uv::SealCode::TooMany);
    return true;
  }
  b->count = n;
  check_ = check;
  return true;
}

void ScanStore::openLoad() {
  if (loading_ != kNone) buf_[loading_].state = Free;
  loading_ = kNone;
  for (uint8_t i = 0; i < 2; i++)
    if (buf_[i].state == Free) loading_ = i;
  if (loading_ == kNone) {
    loadError_ = uv::SealCode::NoBuffer;
  } else {
    buf_[loading_].state = Loading;
    buf_[loading_].count = 0;
    check_ = uv::kCheckInit;
    nextSeq_ = 0;
  }
}

void ScanStore::spoil(uv::SealCode why) {
  if (loading_ != kNone) buf_[loading_].state = Free;
  loading_ = kNone;
  loadError_ = why;
}

uv::SealCode ScanStore::seal(const uv::Seal& s) {
  uint8_t i = loading_;
  if (i == kNone) {
    uv::SealCode why = loadError_;
    loadError_ = uv::SealCode::NoLoad;
    return why;
  }
  Buffer& b = buf_[i];
  uv::SealCode verdict = uv::SealCode::Armed;
  bool continuation = s.flags & uv::kSealContinuation, more = s.flags & uv::kSealMore;
  bool after = live(newest_) && (buf_[newest_].flags & uv::kSealMore);  // a chain waits for its next
  uint8_t mask = continuation ? chainMask_ : 0;
  uint32_t tail[uv::kLedCount];
  for (uint8_t k = 0; k < uv::kLedCount; k++) tail[k] = continuation ? chainTail_[k] : 0;
  if (b.count != s.events || check_ != s.check) {
    verdict = uv::SealCode::Mismatch;
  } else if (continuation != after || (continuation && delay(b.words[0]) == 0)) {
    verdict = uv::SealCode::BadStart;
  } else {
    for (uint8_t e = 0; e < b.count && verdict == uv::SealCode::Armed; e++) {
      uint32_t d = delay(b.words[e]);
      uint8_t next = state(b.words[e]);
      uint8_t bit = 1;
      for (uint8_t k = 0; k < uv::kLedCount; k++, bit = static_cast<uint8_t>(bit << 1)) {
        if (!(mask & bit)) continue;
        uint32_t t = tail[k] + d;
        if (t > capUs_ || t < d) verdict = uv::SealCode::Capped;  // (t < d: past 2³² µs)
        tail[k] = next & bit ? t : 0;  // runs on, or ends here
      }
      mask = next;
    }
    if (verdict == uv::SealCode::Armed && !more && mask) verdict = uv::SealCode::EndsLit;
  }
  loading_ = kNone;
  loadError_ = uv::SealCode::NoLoad;
  if (verdict != uv::SealCode::Armed) {
    b.state = Free;
    return verdict;
  }
  b.flags = s.flags;
  b.order = order_++;
  chainMask_ = mask;
  for (uint8_t k = 0; k < uv::kLedCount; k++) chainTail_[k] = tail[k];
  newest_ = i;
  barrier();
  b.state = Armed;
  return verdict;
}

uint8_t ScanStore::freeBuffers() const {
  uint8_t n = 0;
  for (uint8_t i = 0; i < 2; i++) n += buf_[i].state == Free || buf_[i].state == Loading;
  return n;
}

uint8_t ScanStore::armed() const { return (buf_[0].state == Armed) + (buf_[1].state == Armed); }

uint8_t ScanStore::oldestIn(uint8_t state) const {
  uint8_t oldest = kNone;
  for (uint8_t i = 0; i < 2; i++)
    if (buf_[i].state == state && (oldest == kNone || static_cast<int8_t>(buf_[i].order - buf_[oldest].order) < 0)) oldest = i;
  return oldest;
}

bool ScanStore::oldestSpent(ProgramView& v) const {
  uint8_t i = oldestIn(Spent);
  if (i == kNone) return false;
  v.words = buf_[i].words;
  v.count = buf_[i].count;
  return true;
}

void ScanStore::freeOldestSpent() {
  uint8_t i = oldestIn(Spent);
  if (i != kNone) buf_[i].state = Free;
}

bool ScanStore::runningProgram(ProgramView& v, uint8_t& made) const {
  uint8_t r = run_;
  if (r == kNone) return false;
  v.words = buf_[r].words;
  v.count = buf_[r].count;
  made = cur_ > buf_[r].words ? static_cast<uint8_t>(cur_ - buf_[r].words - 1) : 0;
  return true;
}

bool ScanStore::startable() const {
  if (run_ != kNone) return false;
  const uint8_t oldest = oldestArmed();
  return oldest != kNone && !(buf_[oldest].flags & uv::kSealContinuation);
}

void ScanStore::start() {
  const uint8_t oldest = oldestArmed();
  if (oldest == kNone) return;
  buf_[oldest].state = Running;
  runFrom(oldest);
  pass_ = uv::PassState::Running;
}

void ScanStore::discard(uv::PassState why) {
  if (run_ != kNone) pass_ = why;
  run_ = kNone;
  left_ = 0;
  loading_ = kNone;
  newest_ = kNone;
  buf_[0].state = Free;
  buf_[1].state = Free;
}

ScanStore::Step ScanStore::nextProgram(uint32_t& d, uint8_t& m) {
  uint8_t r = run_;
  if (r == kNone) return Step::End;
  Buffer& b = buf_[r];
  Buffer& o = buf_[r ^ 1];
  bool more = b.flags & uv::kSealMore;
  b.state = Spent;  // ran to its last event: the dose tally reads it, then frees it
  if (!more || o.state != Armed || !(o.flags & uv::kSealContinuation)) {
    run_ = kNone;
    pass_ = more ? uv::PassState::Underrun : uv::PassState::Whole;
    return more ? Step::Underrun : Step::End;
  }
  o.state = Running;
  runFrom(static_cast<uint8_t>(r ^ 1));
  return next(d, m);
}

}  // namespace nano
