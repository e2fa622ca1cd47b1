// The hand-over between the ESP's network task and loop(), one side at a time: the rings keep
// order and refuse when full; every request is answered once, on the network task, or dropped if
// its client left; a POST's client may leave at any step and its job then never starts unless
// it was already accepted; the spool is only ever one side's.
#include "hand_over.h"

#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "hand_over_fakes.h"

using namespace handover;
using uv::esp::HandOver;
using uv::esp::SpscRing;
using uv::esp::Work;

TEST(SpscRing, KeepsOrderRefusesWhenFullAndWraps) {
  SpscRing<int, 4> ring;
  EXPECT_EQ(ring.front(), nullptr);
  for (int i = 1; i <= 4; i++) EXPECT_TRUE(ring.push(i));
  EXPECT_FALSE(ring.push(5));
  EXPECT_EQ(ring.room(), 0);
  std::vector<int> seen;
  for (int round = 0; round < 10; round++) {  // round the ring several times
    seen.push_back(*ring.front());
    ring.pop();
    int* slot = ring.claim();  // filled in place
    ASSERT_NE(slot, nullptr);
    *slot = 5 + round;
    ring.publish();
  }
  while (const int* v = ring.front()) {
    seen.push_back(*v);
    ring.pop();
  }
  std::vector<int> want;
  for (int i = 1; i <= 14; i++) want.push_back(i);
  EXPECT_EQ(seen, want);
  EXPECT_EQ(ring.room(), 4);
}

TEST(HandOver, AStatusIsAnsweredOnceByTicketThroughThePump) {
  Rig rig;
  uint16_t t;
  auto r = rig.ask(Ask::Status, t);
  EXPECT_NE(t, 0);
  rig.pass();
  EXPECT_EQ(r->sends, 0);  // loop() never touches the request
  rig.pump();
  EXPECT_EQ(r->sends, 1);
  EXPECT_EQ(r->status, 200);
  EXPECT_NE(r->body.find("\"mega\""), std::string::npos);
  rig.settle();
  EXPECT_EQ(r->sends, 1);
  EXPECT_EQ(rig.network.waiting(), 0);
}

TEST(HandOver, MoreThanEightWaitingAreRefusedAtOnce) {
  Rig rig;
  std::vector<std::shared_ptr<Request>> waiting;
  uint16_t t;
  for (int i = 0; i < HandOver::kWaiting; i++) {
    waiting.push_back(rig.ask(Ask::Status, t));
    EXPECT_NE(t, 0) << i;
  }
  auto ninth = rig.ask(Ask::Status, t);
  EXPECT_EQ(t, 0);  // the caller answers 503 overloaded itself
  rig.settle();
  for (auto& r : waiting) EXPECT_EQ(r->sends, 1);
  EXPECT_EQ(ninth->sends, 0);
  rig.ask(Ask::Status, t);
  EXPECT_NE(t, 0);
}

TEST(HandOver, AnswersWaitInOrderWhenTheNetworkHasNotTakenThem) {
  Rig rig;
  uint16_t t;
  std::vector<std::shared_ptr<Request>> r;
  for (int i = 0; i < 4; i++) r.push_back(rig.ask(Ask::Status, t));
  rig.pass();  // two answers fit; two wait
  rig.pass();
  rig.pump();
  EXPECT_EQ(r[0]->sends + r[1]->sends, 2);
  EXPECT_EQ(r[2]->sends + r[3]->sends, 0);
  rig.pass();
  rig.pump();
  for (auto& q : r) EXPECT_EQ(q->sends, 1);
}

// A POST's client leaves at each step of its life; the job starts only if it was accepted before
// loop() heard of the leaving, nothing is ever sent twice or to a gone request, and in the end
// every slot is free and the spool is the network task's again.
TEST(HandOver, APostsClientMayLeaveAtEveryStep) {
  enum Step { WhileArriving, BeforeLoopTakesIt, WhileChecked, AnsweredNotSent, WhileSent, AfterSent, Never };
  for (int step = WhileArriving; step <= Never; step++) {
    SCOPED_TRACE(step);
    Rig rig;
    rig.pass();
    rig.pump();  // the Mega's admission is heard
    std::shared_ptr<Request> r;
    uint16_t t = 0;
    if (step == WhileArriving) {
      ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);
      rig.network.bodyAbandoned(rig.network.arriving());  // the request goes with its client; nothing was handed
    } else {
      r = rig.post("{}", t);
      ASSERT_TRUE(r);
      ASSERT_NE(t, 0);
    }
    std::weak_ptr<Request> watch = r;
    auto leave = [&] {
      r.reset();
      rig.network.left(t);
    };
    if (step == BeforeLoopTakesIt) leave();
    rig.pass();  // loop() takes the check and reads a first share
    if (step == WhileChecked) leave();
    while (rig.loop.checking()) rig.pass();
    if (step == AnsweredNotSent) leave();
    Request* seen = r.get();
    int sends = 0;
    rig.network.pump([&](Request& q, const Answer& a) {
      sends++;
      EXPECT_EQ(&q, seen);
      EXPECT_EQ(a.status, 202);
      if (step == WhileSent) leave();  // the send closed the connection (ESPAsyncTCP does it at once)
    });
    if (step == AfterSent) leave();
    rig.settle();
    bool accepted = step >= AnsweredNotSent;  // decided before loop() could hear of the leaving
    EXPECT_EQ(rig.hub.uploadsStarted, accepted ? 1 : 0);
    EXPECT_EQ(sends, step >= WhileSent ? 1 : 0);
    EXPECT_TRUE(watch.expired() || step == Never);
    EXPECT_FALSE(rig.hub.reserved);
    EXPECT_EQ(rig.network.waiting(), 0);
    EXPECT_FALSE(rig.network.spoolLent());
    EXPECT_FALSE(rig.check.bodyOpen);
    EXPECT_EQ(rig.rings.work.front(), nullptr);
    EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);  // the next body may be stored
  }
}

TEST(HandOver, TheSpoolIsLoopsFromTheCheckToTheUploadsEnd) {
  Rig rig;
  rig.settle();
  uint16_t t;
  auto first = rig.post("{}", t);
  ASSERT_TRUE(first);
  EXPECT_EQ(rig.network.admitBody(), Admission::Busy);  // 409 before a byte of a second body is kept
  rig.pass();
  while (rig.loop.checking()) rig.pass();
  rig.pump();
  EXPECT_EQ(first->status, 202);
  EXPECT_TRUE(rig.hub.uploading());
  EXPECT_EQ(rig.network.admitBody(), Admission::Busy);  // the upload still reads the body
  rig.settle();
  EXPECT_FALSE(rig.hub.uploading());
  EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);
}

TEST(HandOver, ARefusedBodyGivesTheSpoolBack) {
  Rig rig;
  rig.settle();
  uint16_t t;
  auto r = rig.post("bad", t);
  rig.settle();
  EXPECT_EQ(r->status, 400);
  EXPECT_EQ(rig.hub.uploadsStarted, 0);
  EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);
}

TEST(HandOver, TheMegaIsAdmittedAgainWhenTheBodyIsWhole) {
  Rig rig;
  EXPECT_EQ(rig.network.admitBody(), Admission::MegaOffline);  // nothing heard from loop() yet
  rig.settle();
  uint16_t t;
  auto r = rig.post("{}", t);
  rig.hub.mega = Admission::Busy;  // a console M24 started a job while the body arrived
  rig.settle();
  EXPECT_EQ(r->status, 409);
  EXPECT_NE(r->body.find("\"busy\""), std::string::npos);
  EXPECT_EQ(rig.hub.uploadsStarted, 0);
  EXPECT_EQ(rig.network.admitBody(), Admission::Busy);  // and the network task has heard
  rig.hub.mega = Admission::MegaOffline;
  rig.settle();
  EXPECT_EQ(rig.network.admitBody(), Admission::MegaOffline);
}

TEST(HandOver, AStoreThatFailedIsRefusedWithoutTheMega) {
  Rig rig;
  rig.settle();
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);
  auto r = std::make_shared<Request>();
  ASSERT_NE(rig.network.hand(r, Ask::CheckBody, true), 0);
  rig.settle();
  EXPECT_EQ(r->status, 503);
  EXPECT_NE(r->body.find("spool_failed"), std::string::npos);
  EXPECT_FALSE(rig.hub.reserved);
  EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);
}

TEST(HandOver, ADeleteDuringTheCheckAnswersBoth) {
  Rig rig;
  rig.settle();
  rig.check.steps = 10;
  uint16_t t;
  auto post = rig.post("{}", t);
  rig.pass();
  auto del = rig.ask(Ask::Cancel, t);
  rig.pass();
  rig.pump();
  EXPECT_EQ(post->status, 409);
  EXPECT_NE(post->body.find("cancelled"), std::string::npos);
  EXPECT_EQ(del->status, 200);
  EXPECT_EQ(rig.hub.uploadsStarted, 0);
  auto again = rig.ask(Ask::Cancel, t);
  rig.settle();
  EXPECT_EQ(again->status, 409);  // nothing left to cancel
  EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);
}

// A DELETE while a POST's body still arrives: the network task answers it at once, and the POST
// 409 once its body is whole; loop() never sees that body, and the spool is free again.
TEST(HandOver, ADeleteWhileTheBodyArrivesCancelsItsPost) {
  Rig rig;
  rig.settle();
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);
  uint32_t body = rig.network.arriving();
  EXPECT_TRUE(rig.network.cancelArriving());     // the DELETE, answered by the network task
  EXPECT_EQ(rig.network.arriving(), 0u);         // the spool is free at once, the body still on its way
  EXPECT_TRUE(rig.network.bodyCancelled(body));  // the body whole: its POST is answered 409, not handed
  EXPECT_FALSE(rig.network.bodyCancelled(body));  // once
  EXPECT_FALSE(rig.network.cancelArriving());     // nothing arrives now: the next DELETE is loop()'s
  rig.settle();
  EXPECT_EQ(rig.hub.uploadsStarted, 0);
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);  // the next body may come
  EXPECT_FALSE(rig.network.bodyCancelled(rig.network.arriving()));  // and it is not the cancelled one
}

// A client that stalls mid-body (a byte every 2.9 s, under the library's 3 s idle timeout) holds
// the only spool until a DELETE frees it, at once; its own late end changes nothing.
TEST(HandOver, ADeleteFreesTheSpoolAStalledBodyHolds) {
  Rig rig;
  rig.settle();
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);
  uint32_t stalled = rig.network.arriving();
  EXPECT_EQ(rig.network.admitBody(), Admission::Busy);  // the spool is held
  EXPECT_TRUE(rig.network.cancelArriving());
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);  // a new body, at once
  uint32_t next = rig.network.arriving();
  EXPECT_NE(next, stalled);
  rig.network.bodyAbandoned(stalled);  // cut off at its deadline later: the new body keeps the spool
  EXPECT_EQ(rig.network.arriving(), next);
  EXPECT_EQ(rig.network.admitBody(), Admission::Busy);
  rig.network.bodyAbandoned(next);
  EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);
}

// A client that leaves after its body was cancelled: the next body is judged afresh.
TEST(HandOver, ACancelledBodysClientMayLeave) {
  Rig rig;
  rig.settle();
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);
  uint32_t body = rig.network.arriving();
  EXPECT_TRUE(rig.network.cancelArriving());
  rig.network.bodyAbandoned(body);
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);
  EXPECT_FALSE(rig.network.bodyCancelled(rig.network.arriving()));
}

// The check's Left has its place kept: requests that fill the ring never crowd it out.
TEST(HandOver, AChecksClientCanLeaveWhenTheRingIsFull) {
  Rig rig;
  rig.settle();
  uint16_t check;
  auto post = rig.post("{}", check);
  uint16_t t;
  for (int i = 0; i < 40; i++) {  // clients that ask and leave at once, before loop() runs
    rig.ask(Ask::Status, t);
    if (t) rig.network.left(t);
  }
  EXPECT_EQ(rig.rings.work.room(), 1);  // full, but for the Left's place
  post.reset();
  rig.network.left(check);
  EXPECT_EQ(rig.rings.work.room(), 0);
  rig.settle();
  EXPECT_EQ(rig.hub.uploadsStarted, 0);
  EXPECT_FALSE(rig.network.spoolLent());
}

// A send that ends its connection at once may reach the pump again: the answer is sent once.
TEST(HandOver, APumpReachedFromADeliveryDoesNotSendTwice) {
  Rig rig;
  uint16_t t;
  auto r = rig.ask(Ask::Status, t);
  rig.pass();
  int sends = 0;
  std::function<void(Request&, const Answer&)> deliver = [&](Request&, const Answer&) {
    sends++;
    rig.network.pump(deliver);
  };
  rig.network.pump(deliver);
  EXPECT_EQ(sends, 1);
}

// The library can let go of a request without an onDisconnect (a server that ends): the pump
// counts it as left, so its slot and a check's Mega come back.
TEST(HandOver, ARequestGoneWithoutANoticeIsCountedAsLeft) {
  Rig rig;
  rig.settle();
  rig.check.steps = 10;
  uint16_t t;
  auto r = rig.post("{}", t);
  rig.pass();
  r.reset();  // no left(): the pump finds its hold expired
  rig.settle();
  EXPECT_EQ(rig.hub.uploadsStarted, 0);
  EXPECT_EQ(rig.network.waiting(), 0);
  EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);
}

// A client that leaves once its job was accepted but before the 202 reached it: the upload it
// started is cancelled, whether it left before the network task took the answer or the library
// had let go of its request by then.
TEST(HandOver, AClientGoneBeforeIts202HasItsUploadCancelled) {
  for (bool noticed : {true, false}) {
    Rig rig;
    rig.settle();
    uint16_t t;
    auto r = rig.post("{}", t);
    ASSERT_TRUE(r);
    rig.pass();
    while (rig.loop.checking()) rig.pass();  // the 202 is in the ring, not yet sent
    ASSERT_TRUE(rig.hub.uploading());
    if (noticed) rig.network.left(t);  // its onDisconnect
    r.reset();                         // the library lets go of the request either way
    rig.pump();
    rig.pass();
    EXPECT_FALSE(rig.hub.uploading()) << noticed;
    EXPECT_EQ(rig.hub.uploadsStarted, 1);
    rig.settle();
    EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);  // the spool came back
  }
}

// One that got its 202 and then closed, as every client does: the upload goes on.
TEST(HandOver, AClientThatGotIts202MayLeave) {
  Rig rig;
  rig.settle();
  uint16_t t;
  auto r = rig.post("{}", t);
  rig.pass();
  while (rig.loop.checking()) rig.pass();
  rig.pump();
  EXPECT_EQ(r->status, 202);
  rig.network.left(t);
  r.reset();
  rig.pass();
  EXPECT_TRUE(rig.hub.uploading());
}
