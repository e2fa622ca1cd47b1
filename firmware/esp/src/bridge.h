// The ESP's hub between its web clients and the Mega (protocol/esp.md): console lines from every
// WebSocket client and a POST /print upload share the one UART through the windowed sender; each
// answer goes back to whoever asked; every Mega line, the status and the upload's progress go out
// on the live channel, which never waits for a client. Plain C++: the glue in main.cpp feeds it
// bytes, parsed client messages and HTTP requests.
#pragma once
#include <stdint.h>
#include <string.h>

#include "job_upload.h"
#include "json_writer.h"
#include "live_channel.h"
#include "mega_sender.h"
#include "status_fold.h"

namespace uv {
namespace esp {

constexpr uint8_t kConsoleMaxLine = 72;  // a body that fits the Mega's 96 bytes with any N and both checks
extern const char kEspFirmware[];

enum class Admission : uint8_t { Accepted, Busy, MegaOffline };

class Bridge : public MegaListener {
 public:
  static constexpr uint8_t kPending = 8;        // console lines out at once, all clients together
  static constexpr uint8_t kConsoleReserve = 4;  // sender slots an upload leaves for the console
  static constexpr uint16_t kBlock = 2048;       // the reply block kept for a `reply`
  static constexpr uint32_t kStatusMs = 1000, kStatusMinMs = 250, kUploadMs = 500;
  // The Mega pauses a running job when no host has said anything for 30 s (mega.md §6); its
  // reports come by themselves, so the hub says something on purpose, as Marlin hosts poll.
  static constexpr uint32_t kHeartbeatMs = 10000;

  Bridge(MegaWire& wire, LiveChannel& live) : sender_(wire, *this), upload_(sender_, kConsoleReserve), live_(live) {}

  // Asks the Mega who it is and for its reports; `panel` (optional) goes to its OLED with M117.
  void begin(uint32_t nowMs, const char* panel = nullptr);
  void received(char c, uint32_t nowMs) { sender_.received(c, nowMs); }
  void poll(uint32_t nowMs);

  // --- WebSocket ---
  void clientJoined(uint8_t client, uint32_t nowMs);
  void clientLeft(uint8_t client);
  // A text frame that was not JSON, or too large to parse.
  void clientRefused(uint8_t client, const char* code, const char* message);
  // A parsed text frame: J is a JSON view (print_request.h).
  template <class J>
  void clientMessage(uint8_t client, const J& m);

  // --- HTTP ---
  // Whether a POST /print may go ahead; Accepted holds the Mega for it until startUpload() or
  // release() (its body converts in between).
  Admission admitPrint(uint32_t nowMs);
  // What admitPrint would say now, holding nothing: what the ESP's network task judges a POST's
  // headers by (network_desk.h), before loop() admits it for real.
  Admission printAdmission(uint32_t nowMs) const;
  void release() { reserved_ = false; }
  // The job's id names its file on the Mega's card (JOB<id>.UVJ): the glue keeps a counter that
  // survives restarts, so an interrupted job's file is never overwritten by the next upload.
  // `paced`: the job starts paced (M24 P1, mega.md "Pacing").
  void startUpload(uint32_t id, JobText& text, uint32_t bytesTotal, bool paced = false);
  // DELETE /print: cancels the upload, or aborts the running job. False: nothing to cancel.
  bool cancel();
  void writeStatus(JsonWriter& w, uint32_t nowMs) const;

  const UploadProgress* lastUpload() const { return uploads_ ? &upload_.progress() : nullptr; }
  const SenderHealth& health() const { return sender_.health(); }
  // The job format the hub writes for the Mega: the newest both read (its M115's Cap:JOB_FORMAT).
  uint8_t jobFormat() const { return sender_.jobFormat(); }
  bool uploading() const { return upload_.active(); }

 private:
  // kTagPanel: the M117 that shows the AP's key on the OLED; its echo is never sent on /ws.
  enum : uint16_t { kTagInit = 0xfe00, kTagAbort = 0xfe01, kTagPanel = 0xfe02 };
  struct Pending {
    bool used;
    uint8_t client;
    bool hasId;
    int64_t id;
    uint16_t tag;
  };

  // MegaListener
  void line(const char* text, uint8_t len) override;
  void answered(uint16_t tag, uint16_t code, bool ownBlock) override;
  void sent(const char* body, uint8_t len, uint16_t tag) override;

  void console(uint8_t client, const char* line, bool hasId, int64_t id);
  void error(uint8_t client, const char* code, const char* message, bool hasId, int64_t id);
  void reply(const Pending& p, bool ownBlock);
  void sendStatus(uint8_t to, uint32_t nowMs);
  void sendUpload();
  void initMega();
  void emit(uint8_t to, const JsonWriter& w);

  MegaSender sender_;
  JobUpload upload_;
  LiveChannel& live_;
  StatusFold status_;
  Pending pending_[kPending] = {};
  uint16_t nextTag_ = 1;
  char block_[kBlock];  // the current reply block: its lines, each ending in '\n'
  uint16_t blockLen_ = 0;
  bool blockEnded_ = false, blockTruncated_ = false;
  char panel_[48] = "";
  uint32_t nowMs_ = 0;
  uint32_t uploads_ = 0;
  bool reserved_ = false;
  uint32_t statusSentMs_ = 0, statusChanges_ = 0;
  uint32_t heartbeatMs_ = 0;
  bool statusOnline_ = false;
  uint32_t uploadSentMs_ = 0, uploadChanges_ = 0;
  uint8_t uploadState_ = 0xff;
};

template <class J>
void Bridge::clientMessage(uint8_t client, const J& m) {
  if (!m.isObject() || !m.has("type") || !m.member("type").isString()) {
    return error(client, "bad_message", "expected an object with a type", false, 0);
  }
  bool hasId = m.has("id");
  int64_t id = 0;
  if (hasId) {
    if (!m.member("id").isInteger()) return error(client, "bad_message", "id must be an integer", false, 0);
    id = m.member("id").integer();
  }
  const char* type = m.member("type").string();
  if (strcmp(type, "ping") == 0) {
    char buf[24];
    JsonWriter w(buf, sizeof buf);
    w.beginObject().key("type").string("pong").endObject();
    return emit(client, w);
  }
  if (strcmp(type, "send") != 0) return error(client, "unknown_type", "type must be send or ping", hasId, id);
  if (!m.has("line") || !m.member("line").isString()) return error(client, "bad_message", "send needs a line", hasId, id);
  const char* text = m.member("line").string();
  size_t len = strlen(text);
  if (len == 0 || len > kConsoleMaxLine) return error(client, "line_too_long", "a line is 1-72 bytes", hasId, id);
  for (size_t i = 0; i < len; i++)
    if (text[i] < 0x20 || text[i] > 0x7e) return error(client, "bad_line", "a line is printable ASCII, one line", hasId, id);
  console(client, text, hasId, id);
}

}  // namespace esp
}  // namespace uv
