// The upload of a POST /print job to the Mega's card, checked whole before it starts.
#include "job_upload.h"

#include <stdio.h>
#include <string.h>

namespace uv {
namespace esp {

void JobUpload::start(uint32_t id, JobText& text, uint32_t bytesTotal, bool paced) {
  text_ = &text;
  paced_ = paced;
  progress_ = UploadProgress{};
  progress_.id = id;
  progress_.bytesTotal = bytesTotal;
  progress_.state = UploadState::Uploading;
  progress_.message = "";
  progress_.attempt = 1;
  cancelled_ = false;
  begin();
}

void JobUpload::begin() {
  sender_.withdraw(kTagFirst, kTagLast);
  progress_.bytesSent = progress_.bytesVerified = 0;
  textDone_ = false;
  recordError_ = 0;
  lineLen_ = -1;
  lensHead_ = lensCount_ = 0;
  changes_++;
  if (!text_->rewind()) return fail(0, "the spooled job could not be read");
  phase_ = Phase::Open;
  pendingSend_ = true;
}

void JobUpload::fileCommand(const char* verb, char* out) {
  snprintf(out, kDialectMaxLine, "%s JOB%lu.UVJ", verb, static_cast<unsigned long>(progress_.id % 100000));
}

// The command the phase sends, into body; its tag, or 0 for none.
uint16_t JobUpload::command(char* body) {
  switch (phase_) {
    case Phase::Open: fileCommand("M28", body); return kOpen;
    case Phase::Close: strcpy(body, "M29"); return kClose;
    case Phase::Select: fileCommand("M23", body); return kSelect;
    case Phase::Start: strcpy(body, paced_ ? "M24 P1" : "M24"); return kStart;
    case Phase::Cleanup:
      if (cleanupAbort_) strcpy(body, "M524");
      else fileCommand("M30", body);
      return kCleanup;
    default: return 0;
  }
}

void JobUpload::poll() {
  if (progress_.state != UploadState::Uploading) return;
  if (pendingSend_) {
    char body[kDialectMaxLine];
    uint16_t tag = command(body);
    if (!tag) return;
    if (sender_.send(body, tag)) pendingSend_ = false;
    return;
  }
  if (phase_ != Phase::Records) return;
  bool stopping = cancelled_ || recordError_;
  while (!stopping && !textDone_ && sender_.free() > reserve_) {
    if (lineLen_ < 0) {
      lineLen_ = text_->next(line_, sizeof line_);
      if (lineLen_ < 0) {
        textDone_ = true;
        if (!text_->ok()) recordError_ = kReadError;
        break;
      }
    }
    if (!sender_.send(line_, kRecord)) {
      if (sender_.free() > 0) recordError_ = kTooLong;  // room, yet refused: the record can't be framed
      break;
    }
    lens_[(lensHead_ + lensCount_) % MegaSender::kQueue] = static_cast<uint8_t>(lineLen_);
    lensCount_++;
    progress_.bytesSent += static_cast<uint32_t>(lineLen_) + 1;
    lineLen_ = -1;
  }
  closeWhenAnswered();
}

// Once every record out has been answered, `M29` ends the upload: it verifies a whole job, and
// deletes a partial one (a cancel, a failed record, a spool read error).
void JobUpload::closeWhenAnswered() {
  if (phase_ != Phase::Records || lensCount_) return;
  if (!textDone_ && !cancelled_ && !recordError_) return;
  phase_ = Phase::Close;
  pendingSend_ = true;
}

void JobUpload::takeBackRecords() {
  uint8_t n = sender_.withdraw(kRecord, kRecord);
  for (; n && lensCount_; n--) {
    lensCount_--;
    progress_.bytesSent -= lens_[(lensHead_ + lensCount_) % MegaSender::kQueue] + 1u;
  }
}

void JobUpload::answered(uint16_t tag, uint16_t error) {
  if (progress_.state != UploadState::Uploading || error == kRestartDropped) return;
  switch (tag) {
    case kOpen:
      if (error) return fail(error, cancelled_ ? "cancelled" : "the Mega refused the upload");
      phase_ = cancelled_ ? Phase::Close : Phase::Records;
      pendingSend_ = cancelled_;
      break;
    case kRecord:
      if (!lensCount_) return;
      if (error && !recordError_) {
        recordError_ = error;
        takeBackRecords();
      }
      if (!error) progress_.bytesVerified += lens_[lensHead_] + 1u;
      lensHead_ = static_cast<uint8_t>((lensHead_ + 1) % MegaSender::kQueue);
      lensCount_--;
      changes_++;
      closeWhenAnswered();
      break;
    case kClose:
      if (cancelled_) {
        if (error) return fail(0, "cancelled");
        cleanupAbort_ = false;  // it verified before the cancel: delete it
        phase_ = Phase::Cleanup;
        pendingSend_ = true;
        return;
      }
      if (recordError_ == kReadError) return fail(0, "the spooled job could not be read");
      if (recordError_ == kTooLong) return fail(0, "a job record is too long for the link");
      if (recordError_ || error) return retryOrFail(recordError_ ? recordError_ : error, "the Mega's check of the job failed");
      progress_.bytesVerified = progress_.bytesTotal;
      phase_ = Phase::Select;
      pendingSend_ = true;
      changes_++;
      break;
    case kSelect:
      if (error) return fail(error, "the Mega could not open the job");
      phase_ = cancelled_ ? Phase::Cleanup : Phase::Start;
      cleanupAbort_ = false;
      pendingSend_ = true;
      break;
    case kStart:
      if (error) return fail(error, "the job did not start");
      if (cancelled_) {
        cleanupAbort_ = true;
        phase_ = Phase::Cleanup;
        pendingSend_ = true;
        return;
      }
      phase_ = Phase::Done;
      progress_.state = UploadState::Started;
      changes_++;
      break;
    case kCleanup: fail(0, "cancelled"); break;
    default: break;
  }
}

void JobUpload::megaRestarted() {
  if (progress_.state != UploadState::Uploading) return;
  if (cancelled_) return fail(0, "cancelled");
  retryOrFail(0, "the Mega kept restarting during the upload");
}

bool JobUpload::cancel() {
  if (progress_.state != UploadState::Uploading || cancelled_) return false;
  cancelled_ = true;
  if (phase_ == Phase::Open && (pendingSend_ || sender_.withdraw(kOpen, kOpen))) {  // never reached the Mega
    fail(0, "cancelled");
    return true;
  }
  if (phase_ == Phase::Records) {
    takeBackRecords();
    closeWhenAnswered();
  }
  return true;
}

void JobUpload::retryOrFail(uint16_t error, const char* message) {
  if (progress_.attempt >= kAttempts) return fail(error, message);
  progress_.attempt++;
  begin();
}

void JobUpload::fail(uint16_t error, const char* message) {
  sender_.withdraw(kTagFirst, kTagLast);
  progress_.state = UploadState::Failed;
  progress_.error = error;
  progress_.message = message;
  phase_ = Phase::Done;
  pendingSend_ = false;
  changes_++;
}

}  // namespace esp
}  // namespace uv
