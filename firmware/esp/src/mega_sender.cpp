// The ESP's windowed, checksummed sender to the Mega (protocol/mega.md §1-3).
#include "mega_sender.h"

#include <string.h>

namespace uv {
namespace esp {

namespace {
// mega.md §5: long commands answer when they finish; their silence is not a lost line.
bool isLong(const char* body, uint8_t len) {
  auto word = [&](const char* w) {
    size_t n = strlen(w);
    return len >= n && strncmp(body, w, n) == 0 && (len == n || body[n] == ' ');
  };
  return word("G28") || word("G29") || word("G30") || word("G4") || word("M822") || word("M29") || word("M23");
}
}  // namespace

bool MegaSender::send(const char* body, uint16_t tag) {
  size_t len = strlen(body);
  if (count_ == kQueue || len >= kDialectMaxLine) return false;
  char probe[kDialectMaxLine + 1];
  if (!encodeFrame(next_ + 1000000u, body, probe, sizeof probe)) return false;  // room for the N and checks
  Item& it = items_[(head_ + count_) % kQueue];
  it.n = 0;
  it.numbered = false;  // numbered when first sent
  it.tag = tag;
  it.sent = false;
  it.firstMs = 0;
  it.announced = false;
  it.len = static_cast<uint8_t>(len);
  memcpy(it.body, body, len);
  it.body[len] = 0;
  count_++;
  return true;
}

void MegaSender::restart() {
  jobFormat_ = 1;  // until its M115 says again
  next_ = 0;
  lastAccepted_ = -1;
  inflight_ = 0;
  busySinceOk_ = false;
  blockError_ = 0;
  for (uint8_t i = 0; i < count_; i++) {
    at(i).sent = false;
    at(i).numbered = false;
    at(i).announced = false;
  }
  if (count_ == kQueue) {  // no room: the newest line is answered as failed
    count_--;
    listener_.answered(items_[(head_ + count_) % kQueue].tag, kRestartDropped, false);
  }
  head_ = static_cast<uint8_t>((head_ + kQueue - 1) % kQueue);
  count_++;
  Item& m = items_[head_];
  m = Item{};
  m.len = 7;
  memcpy(m.body, "M110 N0", 8);
}

uint16_t MegaSender::oldestSentTag() const {
  for (uint8_t i = 0; i < count_; i++) {
    const Item& it = items_[(head_ + i) % kQueue];
    if (it.numbered) return it.tag;  // on the wire at least once: a rewind to resend it keeps its number
  }
  return 0xffff;
}

uint8_t MegaSender::withdraw(uint16_t lo, uint16_t hi) {
  uint8_t kept = 0, taken = 0;
  for (uint8_t i = 0; i < count_; i++) {
    Item& it = at(i);
    if (!it.numbered && it.tag >= lo && it.tag <= hi) {
      taken++;
      continue;
    }
    if (kept != i) at(kept) = it;
    kept++;
  }
  count_ = kept;
  return taken;
}

void MegaSender::rewindTo(uint32_t n) {
  for (uint8_t i = 0; i < count_; i++)
    if (at(i).sent && at(i).n >= n) at(i).sent = false;
}

void MegaSender::endBlock(const Reply& ok, uint32_t nowMs) {
  if (inflight_) inflight_--;
  if (!ok.hasFlow || !ok.hasN || static_cast<int64_t>(ok.n) <= lastAccepted_) {
    // No line named (a skipped line, a resend request, an old duplicate, a damaged ok): it ends no
    // line's block, so an error already heard stays with the line still running (a resent line that
    // runs gets its bare ok in the middle of its own reply: mega.md §2). Once every line out has
    // been answered, the ones unconfirmed go again at once.
    bool anySent = false;
    for (uint8_t i = 0; i < count_; i++) anySent |= at(i).sent;
    if (!inflight_ && anySent) rewindTo(static_cast<uint32_t>(lastAccepted_ + 1));
    return;
  }
  uint16_t error = blockError_;
  blockError_ = 0;
  // Lines run in order: every line up to N is done, and N's block was this one.
  while (count_ && at(0).sent && at(0).n <= ok.n) {
    Item& it = at(0);
    bool ran = it.n == ok.n;
    uint32_t rtt = nowMs - it.firstMs;
    health_.rttMs = health_.rttMs ? (health_.rttMs * 9 + rtt) / 10 : rtt;
    uint16_t tag = it.tag;
    head_ = static_cast<uint8_t>((head_ + 1) % kQueue);
    count_--;
    listener_.answered(tag, ran ? error : 0, ran);
  }
  lastAccepted_ = ok.n;
}

void MegaSender::received(char c, uint32_t nowMs) {
  nowMs_ = nowMs;
  if (!splitter_.push(c) || splitter_.overflow()) return;
  const char* text = splitter_.text();
  uint8_t len = splitter_.length();
  listener_.line(text, len);
  Reply r{};
  if (!parseReply(text, len, r)) return;
  if (r.kind == ReplyKind::Ok || r.kind == ReplyKind::Error || r.kind == ReplyKind::Resend || r.kind == ReplyKind::Busy) lastReplyMs_ = nowMs;
  if (r.kind == ReplyKind::Busy) busySinceOk_ = true;
  if (r.kind == ReplyKind::Cap && r.textLen == 9 && strncmp(r.text, "RX_WINDOW", 9) == 0) {
    window_ = static_cast<uint8_t>(r.value < 1 ? 1 : r.value > 8 ? 8 : r.value);
  }
  // An M115 answer starts with FIRMWARE_NAME: a Mega that then says no Cap:JOB_FORMAT reads format 1.
  if (r.kind == ReplyKind::Firmware) jobFormat_ = 1;
  if (r.kind == ReplyKind::Cap && r.textLen == 10 && strncmp(r.text, "JOB_FORMAT", 10) == 0) {
    jobFormat_ = static_cast<uint8_t>(r.value >= 2 ? 2 : 1);
  }
  if (r.kind == ReplyKind::Ok) {
    busySinceOk_ = false;
    endBlock(r, nowMs);
  } else if (r.kind == ReplyKind::Resend) {
    if (static_cast<int64_t>(r.n) > lastAccepted_) {
      health_.resends++;
      rewindTo(r.n);
    }
  } else if (r.kind == ReplyKind::Error && (r.code < 1 || r.code > 6) && !blockError_) {
    blockError_ = r.code;
  }
}

uint32_t MegaSender::timeoutMs() const {
  if (busySinceOk_) return kReplyTimeoutMs;
  for (uint8_t i = 0; i < count_; i++) {
    const Item& it = items_[(head_ + i) % kQueue];
    if (it.sent && isLong(it.body, it.len)) return kReplyTimeoutMs;
  }
  uint32_t t = 4 * health_.rttMs;
  return t < 250 ? 250 : t > kReplyTimeoutMs ? kReplyTimeoutMs : t;
}

void MegaSender::poll(uint32_t nowMs) {
  nowMs_ = nowMs;
  // Replies still owed: a line out, or an answer whose ok was lost (the window still counts it).
  bool waiting = inflight_ > 0;
  for (uint8_t i = 0; i < count_; i++) waiting |= at(i).sent;
  if (waiting && nowMs - lastReplyMs_ >= timeoutMs()) {
    // Lost bytes took a line or its reply: everything after the last accepted line goes again. An
    // error heard since the last ok stays: it is the oldest unanswered line's, whose ok is to come.
    health_.timeouts++;
    inflight_ = 0;
    rewindTo(static_cast<uint32_t>(lastAccepted_ + 1));
    lastReplyMs_ = nowMs;
  }
  while (inflight_ < window_) {
    Item* it = nullptr;
    for (uint8_t i = 0; i < count_ && !it; i++)
      if (!at(i).sent) it = &at(i);
    if (!it) break;
    if (!it->numbered) {
      it->n = next_++;
      it->numbered = true;
    }
    char frame[kDialectMaxLine + 2];
    size_t n = encodeFrame(it->n, it->body, frame, sizeof frame);
    frame[n++] = '\n';
    if (!wire_.write(frame, static_cast<uint16_t>(n))) break;  // the UART is full: next pass
    if (!it->firstMs) it->firstMs = nowMs;
    if (!it->announced) {
      it->announced = true;
      listener_.sent(it->body, it->len, it->tag);
    }
    if (!waiting) lastReplyMs_ = nowMs;
    waiting = true;
    it->sent = true;
    inflight_++;
    health_.linesSent++;
  }
}

}  // namespace esp
}  // namespace uv
