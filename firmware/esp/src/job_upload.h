// A POST /print job's way onto the Mega's card (protocol/esp.md): `M28 JOB<n>.UVJ`, every record
// of the job text through the windowed sender, `M29` (the Mega checks the whole job's CRC), and
// only then `M23` and `M24` (`M24 P1` for a paced job). A job never starts half-received. A failed check or a Mega restart
// sends the whole job again, up to kAttempts times. Plain C++: the job text sits behind JobText.
#pragma once
#include <stdint.h>

#include "mega_sender.h"

namespace uv {
namespace esp {

// The converted job text, spooled where it survives a slow Mega (LittleFS on the ESP).
class JobText {
 public:
  virtual bool rewind() = 0;
  // The next record without '\n' into buf (NUL-terminated): its length, or -1 at the end or on a
  // read error (then ok() is false).
  virtual int next(char* buf, uint8_t size) = 0;
  virtual bool ok() const = 0;
};

enum class UploadState : uint8_t { Idle, Uploading, Started, Failed };

struct UploadProgress {
  uint32_t id;
  uint32_t bytesSent, bytesVerified, bytesTotal;
  UploadState state;
  uint16_t error;       // the Mega's code, or 0
  const char* message;  // why it failed, for people
  uint8_t attempt;
};

class JobUpload {
 public:
  static constexpr uint16_t kTagFirst = 0xff00;  // the sender's tags this upload uses
  static constexpr uint16_t kTagLast = 0xff0f;
  static constexpr uint16_t kRecordTag = kTagFirst + 1;  // every job record; the rest are commands
  static constexpr uint8_t kAttempts = 3;

  // The upload leaves `reserve` of the sender's slots to others (the console).
  explicit JobUpload(MegaSender& sender, uint8_t reserve = 0) : sender_(sender), reserve_(reserve) {}

  // Begins uploading `text` (bytesTotal bytes, '\n' included) as JOB<id>.UVJ; once verified it
  // starts with `M24 P1` when `paced` (mega.md "Pacing"), else `M24`.
  void start(uint32_t id, JobText& text, uint32_t bytesTotal, bool paced = false);
  // Feeds the sender as it has room; call every loop pass.
  void poll();
  static bool owns(uint16_t tag) { return tag >= kTagFirst && tag <= kTagLast; }
  void answered(uint16_t tag, uint16_t error);
  // The Mega restarted: whatever it had of the upload is gone, so it begins again.
  void megaRestarted();
  // Stops an upload before its job starts; the Mega deletes what it had. False when there is
  // nothing to cancel (no upload, or the job has already started: abort it with M524).
  bool cancel();

  bool active() const { return progress_.state == UploadState::Uploading; }
  const UploadProgress& progress() const { return progress_; }
  // Counts changes of state and of verified bytes, so the bridge can report on change.
  uint32_t changes() const { return changes_; }

 private:
  enum class Phase : uint8_t { Idle, Open, Records, Close, Select, Start, Cleanup, Done };
  enum Tag : uint16_t { kOpen = kTagFirst, kRecord = kRecordTag, kClose, kSelect, kStart, kCleanup };

  static constexpr uint16_t kReadError = 0xfffe;  // recordError_: the spool, not the Mega
  static constexpr uint16_t kTooLong = 0xfffd;    // recordError_: a record the link can't frame

  void begin();
  uint16_t command(char* body);
  void closeWhenAnswered();
  void takeBackRecords();
  void retryOrFail(uint16_t error, const char* message);
  void fail(uint16_t error, const char* message);
  void fileCommand(const char* verb, char* out);

  MegaSender& sender_;
  uint8_t reserve_;
  JobText* text_ = nullptr;
  UploadProgress progress_{};
  Phase phase_ = Phase::Idle;
  bool pendingSend_ = false;  // phase_'s command still to queue (the sender was full)
  bool textDone_ = false;
  bool cancelled_ = false;
  bool paced_ = false;
  bool cleanupAbort_ = false;  // the cleanup is M524 (the job had started), else M30
  uint16_t recordError_ = 0;
  char line_[kDialectMaxLine];
  int lineLen_ = -1;  // a record read but not yet queued
  // Lengths of the records queued and not yet answered, oldest first (answers come in order).
  uint8_t lens_[MegaSender::kQueue];
  uint8_t lensHead_ = 0, lensCount_ = 0;
  uint32_t changes_ = 0;
};

}  // namespace esp
}  // namespace uv
