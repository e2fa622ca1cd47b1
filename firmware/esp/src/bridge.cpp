// The ESP's hub: console lines, uploads and the live channel over one UART to the Mega.
#include "bridge.h"

#include <stdio.h>

namespace uv {
namespace esp {

const char kEspFirmware[] = "UVExposure ESP 0.1.0";

namespace {
char message[LiveChannel::kMaxMessage + 1];  // one live message at a time: static, off the loop's small stack

const char* uploadStateName(UploadState s) {
  return s == UploadState::Started ? "started" : s == UploadState::Failed ? "failed" : "uploading";
}
}  // namespace

void Bridge::begin(uint32_t nowMs, const char* panel) {
  nowMs_ = nowMs;
  if (panel) snprintf(panel_, sizeof panel_, "M117 %s", panel);
  initMega();
}

// The Mega says who it is (its window), reports every second, lists its config (the sensors' soft
// limits, for /status), and shows the Wi-Fi on its OLED.
void Bridge::initMega() {
  static const char* const kInit[] = {"M115", "M155 S1", "M154 S1", "M27 S1", "M503"};
  for (const char* l : kInit) sender_.send(l, kTagInit);
  if (panel_[0]) sender_.send(panel_, kTagPanel);
}

void Bridge::emit(uint8_t to, const JsonWriter& w) {
  if (!w.ok()) return;
  if (to == LiveChannel::kEveryone) live_.broadcast(w.text(), w.length());
  else live_.sendTo(to, w.text(), w.length());
}

void Bridge::poll(uint32_t nowMs) {
  nowMs_ = nowMs;
  upload_.poll();
  sender_.poll(nowMs);
  if (nowMs - heartbeatMs_ >= kHeartbeatMs) {  // an upload's records say it already
    heartbeatMs_ = nowMs;
    if (!upload_.active()) sender_.send("M105", kTagInit);
  }
  bool online = status_.online(nowMs);
  bool changed = status_.changes() != statusChanges_ || online != statusOnline_;
  if (nowMs - statusSentMs_ >= kStatusMs || (changed && nowMs - statusSentMs_ >= kStatusMinMs)) {
    sendStatus(LiveChannel::kEveryone, nowMs);
  }
  if (uploads_) {
    bool stateChanged = static_cast<uint8_t>(upload_.progress().state) != uploadState_;
    bool progressed = upload_.changes() != uploadChanges_;
    if (stateChanged || (upload_.active() && progressed && nowMs - uploadSentMs_ >= kUploadMs)) sendUpload();
  }
}

void Bridge::sendStatus(uint8_t to, uint32_t nowMs) {
  JsonWriter w(message, sizeof message);
  w.beginObject().key("type").string("status").key("status");
  writeStatus(w, nowMs);
  w.endObject();
  emit(to, w);
  if (to == LiveChannel::kEveryone) {
    statusSentMs_ = nowMs;
    statusChanges_ = status_.changes();
    statusOnline_ = status_.online(nowMs);
  }
}

void Bridge::writeStatus(JsonWriter& w, uint32_t nowMs) const { status_.write(w, lastUpload(), live_.count(), nowMs); }

void Bridge::sendUpload() {
  const UploadProgress& p = upload_.progress();
  JsonWriter w(message, sizeof message);
  w.beginObject().key("type").string("upload").key("id").number(p.id);
  w.key("bytesSent").number(p.bytesSent).key("bytesVerified").number(p.bytesVerified).key("bytesTotal").number(p.bytesTotal);
  w.key("state").string(uploadStateName(p.state));
  if (p.state == UploadState::Failed) {
    char why[96];
    if (p.error) snprintf(why, sizeof why, "E%u: %s", p.error, p.message);
    else snprintf(why, sizeof why, "%s", p.message);
    w.key("error").ascii(why, static_cast<uint16_t>(strlen(why)));
  }
  w.endObject();
  emit(LiveChannel::kEveryone, w);
  uploadSentMs_ = nowMs_;
  uploadChanges_ = upload_.changes();
  uploadState_ = static_cast<uint8_t>(p.state);
}

// --- the Mega's side ---

void Bridge::line(const char* text, uint8_t len) {
  status_.line(text, len, nowMs_);
  if (blockEnded_) {
    blockLen_ = 0;
    blockEnded_ = blockTruncated_ = false;
  }
  if (blockLen_ + len + 1u <= kBlock) {
    memcpy(block_ + blockLen_, text, len);
    blockLen_ = static_cast<uint16_t>(blockLen_ + len);
    block_[blockLen_++] = '\n';
  } else {
    blockTruncated_ = true;
  }
  bool ok = len >= 2 && text[0] == 'o' && text[1] == 'k' && (len == 2 || text[2] == ' ');
  if (ok) blockEnded_ = true;
  // The oks of the job's records are the sender's business; the `upload` message counts them.
  // Relayed, they would double the live traffic of an upload for nothing a client uses.
  if (!ok || sender_.oldestSentTag() != JobUpload::kRecordTag) {
    JsonWriter w(message, sizeof message);
    w.beginObject().key("type").string("line").key("line").ascii(text, len).endObject();
    emit(LiveChannel::kEveryone, w);
  }
  if (len == 5 && memcmp(text, "start", 5) == 0) {
    // The Mega restarted: it numbers lines from 0 again, forgot its reports, and lost any upload.
    sender_.restart();
    upload_.megaRestarted();
    initMega();
  }
}

void Bridge::sent(const char* body, uint8_t len, uint16_t tag) {
  if (tag == JobUpload::kRecordTag) return;  // records: the upload message counts them
  // The AP's key goes to the OLED, where the user reads it, and nowhere else: a /ws client may be
  // anyone who is on the home network, or a page the user opened.
  if (tag == kTagPanel) return;
  JsonWriter w(message, sizeof message);
  w.beginObject().key("type").string("sent").key("line").ascii(body, len);
  w.key("from").string(tag < kTagInit ? "ws" : "esp").endObject();
  emit(LiveChannel::kEveryone, w);
}

void Bridge::answered(uint16_t tag, uint16_t code, bool ownBlock) {
  if (JobUpload::owns(tag)) return upload_.answered(tag, code);
  if (tag >= kTagInit) return;
  for (Pending& p : pending_) {
    if (!p.used || p.tag != tag) continue;
    p.used = false;
    if (!p.hasId) return;
    if (code == kRestartDropped) return error(p.client, "mega_restarted", "the Mega restarted before the line was sent", true, p.id);
    return reply(p, ownBlock);
  }
}

// `reply`: the line's reply block, ending in its ok. If that ok was damaged on the wire, the
// block went by as `line` messages and the reply holds only an ok.
void Bridge::reply(const Pending& p, bool ownBlock) {
  JsonWriter w(message, sizeof message);
  w.beginObject().key("type").string("reply").key("id").number(p.id).key("lines").beginArray();
  if (ownBlock) {
    uint16_t from = 0;
    for (uint16_t i = 0; i < blockLen_; i++) {
      if (block_[i] != '\n') continue;
      w.ascii(block_ + from, static_cast<uint16_t>(i - from));
      from = static_cast<uint16_t>(i + 1);
    }
    if (blockTruncated_) w.string("ok");
  } else {
    w.string("ok");
  }
  w.endArray().endObject();
  if (!w.ok()) {  // a block too long for one message: its lines went out as `line` messages
    JsonWriter s(message, sizeof message);
    s.beginObject().key("type").string("reply").key("id").number(p.id).key("lines").beginArray().string("ok").endArray().endObject();
    return emit(p.client, s);
  }
  emit(p.client, w);
}

// --- the clients' side ---

void Bridge::clientJoined(uint8_t client, uint32_t nowMs) {
  JsonWriter w(message, sizeof message);
  w.beginObject().key("type").string("hello").key("protocol").number(1).key("firmware").string(kEspFirmware).endObject();
  emit(client, w);
  sendStatus(client, nowMs);
}

void Bridge::clientLeft(uint8_t client) {
  for (Pending& p : pending_)
    if (p.used && p.client == client) p.hasId = false;  // still answered by the Mega; nobody to tell
}

void Bridge::clientRefused(uint8_t client, const char* code, const char* message) { error(client, code, message, false, 0); }

void Bridge::error(uint8_t client, const char* code, const char* text, bool hasId, int64_t id) {
  JsonWriter w(message, sizeof message);
  w.beginObject().key("type").string("error").key("code").string(code).key("message").string(text);
  if (hasId) w.key("id").number(id);
  w.endObject();
  emit(client, w);
}

void Bridge::console(uint8_t client, const char* text, bool hasId, int64_t id) {
  Pending* slot = nullptr;
  for (Pending& p : pending_)
    if (!p.used && !slot) slot = &p;
  if (!slot || sender_.free() == 0) return error(client, "busy", "too many lines waiting for the Mega; try again", hasId, id);
  uint16_t tag = nextTag_;
  nextTag_ = static_cast<uint16_t>(nextTag_ % (kTagInit - 1) + 1);  // 1 .. kTagInit-1
  if (!sender_.send(text, tag)) return error(client, "line_too_long", "the line does not fit a numbered frame", hasId, id);
  *slot = {true, client, hasId, id, tag};
}

// --- HTTP ---

Admission Bridge::printAdmission(uint32_t nowMs) const {
  if (reserved_ || upload_.active()) return Admission::Busy;
  if (!status_.online(nowMs)) return Admission::MegaOffline;  // what it last said of its job may be stale
  if (status_.jobActive()) return Admission::Busy;
  return Admission::Accepted;
}

Admission Bridge::admitPrint(uint32_t nowMs) {
  Admission a = printAdmission(nowMs);
  if (a == Admission::Accepted) reserved_ = true;
  return a;
}

void Bridge::startUpload(uint32_t id, JobText& text, uint32_t bytesTotal, bool paced) {
  reserved_ = false;
  uploads_++;
  uploadState_ = 0xff;  // report the new upload at once
  upload_.start(id, text, bytesTotal, paced);
}

bool Bridge::cancel() {
  if (upload_.cancel()) return true;
  if (!status_.jobRunning()) return false;
  sender_.send("M524", kTagAbort);
  return true;
}

}  // namespace esp
}  // namespace uv
