// loop()'s half of the hand-over (hand_over.h): takes the network task's requests in order,
// answers them by ticket, checks a POST /print's body a step a pass (print_intake.h), and tells
// the network task what it needs to judge the next POST: the Mega's admission, and the spool
// once loop() has let go of it. Everything here runs in loop() only.
//
// Hub: the bridge (printAdmission, admitPrint, cancel, uploading, writeStatus). Check: the print
// intake (begin, busy, step, cancel, status, response, closeBody).
#pragma once
#include <stdint.h>
#include <string.h>

#include "hand_over.h"
#include "http_rules.h"
#include "json_writer.h"
#include "print_intake.h"

namespace uv {
namespace esp {

template <class Hub, class Check>
class LoopDesk {
 public:
  LoopDesk(HandOver& rings, Hub& hub, Check& check) : rings_(rings), hub_(hub), check_(check) {}

  // One pass. nextId: the job id for an accepted body (PrintIntake::step).
  template <class NextId>
  void poll(uint32_t nowMs, NextId nextId) {
    for (const Work* w; (w = rings_.work.front()) != nullptr; rings_.work.pop())
      if (!serve(*w, nowMs)) break;  // no room for its answer yet: it waits, and those behind it
    // A step only when its verdict has somewhere to go; the body is read a share at a time.
    if (checking_ && rings_.answers.room() > 0 && check_.step(nextId) != Intake::Working) {
      accepted_ = check_.status() == 202 ? checking_ : 0;
      answer(checking_, check_.status(), check_.response());
      checking_ = 0;
    }
    tell(nowMs);
  }

  bool checking() const { return checking_ != 0; }

 private:
  // False when the request's answer has no room: it stays first in the ring.
  bool serve(const Work& w, uint32_t nowMs) {
    switch (w.ask) {
      case Ask::Status: {
        Answer* a = rings_.answers.claim();
        if (!a) return false;
        JsonWriter json(a->body, sizeof a->body);
        hub_.writeStatus(json, nowMs);
        fill(*a, w.ticket, 200, json);
        rings_.answers.publish();
        return true;
      }
      case Ask::Cancel:
        if (rings_.answers.room() < (checking_ ? 2 : 1)) return false;  // the check's POST is answered too
        if (checking_) {
          check_.cancel();
          answer(checking_, check_.status(), check_.response());
          checking_ = 0;
        } else if (!hub_.cancel()) {
          return refuse(w.ticket, {409, "busy", "nothing to cancel"});
        }
        return answer(w.ticket, 200, kCancelledJson);
      case Ask::CheckBody: {
        if (!rings_.answers.room()) return false;
        spoolHeld_ = true;  // whatever comes of it, the spool is loop()'s until tell() gives it back
        if (w.spoolFailed) return refuse(w.ticket, {503, "spool_failed", "the ESP could not store the job; its flash may be full"});
        // The network task judged the headers by what it last heard; the Mega is admitted here.
        HttpError e = checking_ ? HttpError{409, "busy", "a job is being checked"} : admissionError(hub_.admitPrint(nowMs));
        if (e.status) return refuse(w.ticket, e);
        check_.begin();
        checking_ = w.ticket;
        return true;
      }
      case Ask::Left:
        if (checking_ == w.ticket) {  // a job nobody was told about does not start
          check_.cancel();
          checking_ = 0;
        }
        // Gone before its 202 reached it: the upload it started is cancelled (the Mega keeps
        // nothing), and `upload` on /ws says so to whoever listens.
        if (accepted_ == w.ticket) {
          if (hub_.uploading()) hub_.cancel();
          accepted_ = 0;
        }
        return true;
    }
    return true;
  }

  bool refuse(uint16_t ticket, const HttpError& e) {
    Answer* a = rings_.answers.claim();
    JsonWriter json(a->body, sizeof a->body);
    writeError(json, e.code, e.message);
    fill(*a, ticket, e.status, json);
    rings_.answers.publish();
    return true;
  }

  // serve() and poll() made sure of the room first.
  bool answer(uint16_t ticket, uint16_t status, const char* json) {
    Answer* a = rings_.answers.claim();
    a->ticket = ticket;
    a->status = status;
    a->plainText = false;
    strncpy(a->body, json, sizeof a->body - 1);
    a->body[sizeof a->body - 1] = 0;
    rings_.answers.publish();
    return true;
  }

  static void fill(Answer& a, uint16_t ticket, uint16_t status, const JsonWriter& json) {
    a.ticket = ticket;
    a.status = status;
    a.plainText = !json.ok();
    if (a.plainText) {
      a.status = 500;
      strncpy(a.body, "the answer did not fit", sizeof a.body);
    }
  }

  // The network task's view of the Mega and the spool, told when it changes. A full ring: told
  // next pass, nothing lost (the spool stays loop()'s until the note that returns it is in).
  void tell(uint32_t nowMs) {
    bool back = spoolHeld_ && !checking_ && !check_.busy() && !hub_.uploading();
    Admission now = hub_.printAdmission(nowMs);
    if (!back && told_ && now == admission_) return;
    HubNote* n = rings_.notes.claim();
    if (!n) return;
    if (back) check_.closeBody();  // nothing of loop()'s reads the file when the network writes it
    n->admission = now;
    n->spoolBack = back;
    rings_.notes.publish();
    spoolHeld_ = spoolHeld_ && !back;
    admission_ = now;
    told_ = true;
  }

  HandOver& rings_;
  Hub& hub_;
  Check& check_;
  uint16_t checking_ = 0;  // the ticket of the POST whose body is being checked
  uint16_t accepted_ = 0;  // the ticket of the last POST answered 202, until its answer is delivered or its client gone
  bool spoolHeld_ = false;
  bool told_ = false;
  Admission admission_ = Admission::MegaOffline;
};

}  // namespace esp
}  // namespace uv
