// The network task's half of the hand-over (hand_over.h): the requests waiting for loop(), each
// under a ticket; their answers delivered to those still there and dropped for the rest; and the
// network task's view of the spool and of the Mega, by which a POST /print is judged before a
// byte of its body is kept. Everything here runs on the network task only.
//
// Handle: the library's weak hold on a request (AsyncWebServerRequestPtr, a std::weak_ptr), with
// lock() and expired(). It is made, kept and let go of on the network task alone.
#pragma once
#include <stdint.h>

#include <utility>

#include "hand_over.h"

namespace uv {
namespace esp {

template <class Handle>
class NetworkDesk {
 public:
  explicit NetworkDesk(HandOver& rings) : rings_(rings) {}

  // A POST /print whose headers passed their own rules (printHeaderError): may its body be kept?
  // Busy while another body arrives or loop() has the spool; otherwise what loop() last said of
  // the Mega, which it decides again once the body is whole. Accepted: the body is arriving now,
  // under the number arriving() gives, by which the calls below name it.
  Admission admitBody() {
    Admission a = admission();
    if (a == Admission::Accepted) arriving_ = true, body_++;
    return a;
  }
  // The same judgement for a POST that has no body to keep.
  Admission admission() const { return arriving_ || spoolLent_ ? Admission::Busy : admission_; }
  // The number of the body arriving now; 0 when none is.
  uint32_t arriving() const { return arriving_ ? body_ : 0; }
  // That body's client left, or was cut off at its deadline, before it was whole: the spool is
  // free again. A body already cancelled or handed is not the arriving one: nothing changes.
  void bodyAbandoned(uint32_t body) {
    if (arriving_ && body == body_) arriving_ = false;
  }
  // DELETE /print while a body arrives: that POST is cancelled, the DELETE is answered at once
  // (kCancelledJson), and the spool is free at once, so a client that stalls mid-body holds nothing.
  // Its POST is answered 409 (kCancelledCode) if its body ever comes whole, and its bytes are no
  // longer kept. False: no body arrives, and loop() has the cancel to judge.
  bool cancelArriving() {
    if (!arriving_) return false;
    arriving_ = false;
    cancelled_ = body_;
    return true;
  }
  // The body numbered `body` is whole: true (once) if a DELETE cancelled it while it arrived.
  bool bodyCancelled(uint32_t body) {
    if (!body || body != cancelled_) return false;
    cancelled_ = 0;
    return true;
  }

  // Hands a paused request to loop() and returns its ticket. CheckBody: the arriving body is
  // whole, and the spool goes with it. 0: no room (kWaiting already wait, or the ring is full),
  // and nothing was handed: the caller answers 503 itself.
  uint16_t hand(Handle request, Ask ask, bool spoolFailed = false) {
    if (ask == Ask::CheckBody) arriving_ = false;
    // A check keeps a place for its Left, so its client can always leave.
    uint8_t needed = 1 + (leftOwed_ ? 1 : 0) + (ask == Ask::CheckBody ? 1 : 0);
    Waiting* w = find(0);
    if (!w || rings_.work.room() < needed) return 0;
    uint16_t ticket = nextTicket();
    w->request = std::move(request);
    w->ticket = ticket;
    rings_.work.push(Work{ticket, ask, spoolFailed});
    if (ask == Ask::CheckBody) {
      spoolLent_ = true;
      leftOwed_ = ticket;
    }
    return ticket;
  }

  // The client of a handed request has gone (its onDisconnect). Whatever loop() answers it is
  // dropped; a check's loop() is told, so a job nobody was told about does not start. A ticket
  // already answered or unknown is ignored.
  void left(uint16_t ticket) {
    Waiting* w = ticket ? find(ticket) : nullptr;
    if (!w) return;
    w->ticket = 0;
    w->request = Handle{};  // the weak hold let go here, on the network task, outside any lock
    if (leftOwed_ == ticket) {
      rings_.work.push(Work{ticket, Ask::Left, false});  // its place was kept by hand()
      leftOwed_ = 0;
    }
  }

  // Takes loop()'s notes and answers: deliver(request, answer) for each answered request still
  // there. deliver may end the request's connection, and so reach left() or pump() again.
  template <class Deliver>
  void pump(Deliver deliver) {
    if (pumping_) return;  // reached again from deliver(): the answer in hand is not sent twice
    pumping_ = true;
    for (const HubNote* n; (n = rings_.notes.front()) != nullptr; rings_.notes.pop()) {
      admission_ = n->admission;
      if (n->spoolBack) spoolLent_ = false;
    }
    for (const Answer* a; (a = rings_.answers.front()) != nullptr; rings_.answers.pop()) {
      Waiting* w = a->ticket ? find(a->ticket) : nullptr;
      if (!w) continue;  // its client left: nobody to tell
      Handle request = std::move(w->request);
      w->request = Handle{};
      w->ticket = 0;
      auto r = request.lock();
      if (leftOwed_ == a->ticket) {
        // A job accepted for a client that has gone: loop() is told, so an upload nobody heard of
        // is cancelled (the place for this Left was kept by hand()).
        if (!r && a->status == 202) rings_.work.push(Work{a->ticket, Ask::Left, false});
        leftOwed_ = 0;
      }
      if (r) deliver(*r, *a);
    }
    // A request the library let go of without an onDisconnect counts as left.
    for (Waiting& w : waiting_)
      if (w.ticket && w.request.expired()) left(w.ticket);
    pumping_ = false;
  }

  uint8_t waiting() const {
    uint8_t n = 0;
    for (const Waiting& w : waiting_) n += w.ticket != 0;
    return n;
  }
  bool spoolLent() const { return spoolLent_; }

 private:
  struct Waiting {
    uint16_t ticket = 0;  // 0: a free slot
    Handle request;
  };

  // The request waiting under `ticket`; find(0) is a free slot.
  Waiting* find(uint16_t ticket) {
    for (Waiting& w : waiting_)
      if (w.ticket == ticket) return &w;
    return nullptr;
  }
  // A ticket is never 0 and never one still waiting; the 65535 before it have long been answered.
  uint16_t nextTicket() {
    do ticket_ = static_cast<uint16_t>(ticket_ + 1);
    while (ticket_ == 0 || find(ticket_));
    return ticket_;
  }

  HandOver& rings_;
  Waiting waiting_[HandOver::kWaiting];
  uint16_t ticket_ = 0;
  uint16_t leftOwed_ = 0;  // the check whose client may still leave: its Left has a place kept
  Admission admission_ = Admission::MegaOffline;  // until loop() says otherwise
  uint32_t body_ = 0, cancelled_ = 0;  // the last body admitted; the one a DELETE cancelled
  bool arriving_ = false, spoolLent_ = false, pumping_ = false;
};

}  // namespace esp
}  // namespace uv
