// The Mega's side of the printhead link: background polls of the Nano and what it last said.
#include "nano_link.h"

namespace {
constexpr uint32_t kPollMs = 500;
constexpr uint32_t kReplyTimeoutMs = 50;
constexpr uint8_t kMissesOffline = 3;
}  // namespace

void NanoLink::poll(uint32_t nowMs) {
  while (stream_.available()) {
    if (!splitter_.push(static_cast<char>(stream_.read())) || splitter_.overflow()) continue;
    char reply[uv::kNanoMaxLine + 2];
    uint8_t n = splitter_.length();
    memcpy(reply, splitter_.text(), n);
    reply[n++] = '\n';
    uv::NanoReply r{};
    if (uv::parseNanoReply(reply, n, r)) handle(r);
  }
  if (awaiting_ && nowMs - lastPollMs_ > kReplyTimeoutMs) {
    awaiting_ = false;
    if (++missed_ >= kMissesOffline) online_ = false;
  }
  if (!awaiting_ && nowMs - lastPollMs_ >= kPollMs) {
    uv::NanoCommand c{};
    c.op = 'T';
    char out[8];
    stream_.write(out, uv::formatNanoCommand(c, out, sizeof out));
    lastPollMs_ = nowMs;
    awaiting_ = true;
  }
}

void NanoLink::handle(const uv::NanoReply& r) {
  awaiting_ = false;
  missed_ = 0;
  online_ = true;
  lastReplyMs_ = millis();
  if (r.op == 'T') memcpy(deciC_, r.deciC, sizeof deciC_);
}
