// The hand-over on the ESP8266, where the network callbacks also run inside loop()'s step: the
// flash yields while loop() reads the spool (flash_gate.h). Whatever the network does there (a
// second POST, requests handed and answered, a client leaving, a DELETE) keeps the spool loop()'s,
// answers every request once and starts no job that nobody was told of.
#include <gtest/gtest.h>

#include <vector>

#include "hand_over_fakes.h"

using namespace handover;

namespace {

struct Rig : Desks {
  uint32_t ids = 0, ms = 0;
  std::shared_ptr<Request> ask(Ask a, uint16_t& ticket) {
    auto r = std::make_shared<Request>();
    ticket = network.hand(r, a);
    return r;
  }
  void pump() {
    network.pump([](Request& r, const Answer& a) {
      r.sends++;
      r.status = a.status;
    });
  }
  void settle() {
    for (int i = 0; i < 50; i++) {
      loop.poll(ms += 10, [this] { return ++ids; });
      hub.poll();
      pump();
    }
  }
};

TEST(HandOverYield, RequestsHandedAndAnsweredInsideTheCheckLeaveTheSpoolAndTheJobAlone) {
  Rig rig;
  rig.settle();  // loop()'s first note: the Mega admits a job
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);
  rig.spool.text = "{job}";
  uint16_t ticket = 0;
  auto post = rig.ask(Ask::CheckBody, ticket);
  std::vector<std::shared_ptr<Request>> inside;
  int yields = 0;
  rig.check.yield = [&] {
    yields++;
    EXPECT_EQ(rig.network.admitBody(), Admission::Busy);  // a second POST: 409 on its headers, no byte kept
    uint16_t t = 0;
    inside.push_back(rig.ask(Ask::Status, t));
    if (yields == 2) rig.network.left(t);  // its client gone at once
    rig.pump();  // answers loop() gave at an earlier step go out from inside this one
    EXPECT_EQ(rig.spool.text, "{job}");
  };
  rig.settle();
  rig.check.yield = nullptr;
  rig.settle();
  EXPECT_GE(yields, 3);
  EXPECT_EQ(post->sends, 1);
  EXPECT_EQ(post->status, 202);
  EXPECT_EQ(rig.hub.uploadsStarted, 1);
  for (size_t i = 0; i < inside.size(); i++) EXPECT_EQ(inside[i]->sends, i == 1 ? 0 : 1) << i;
}

TEST(HandOverYield, ADeleteInsideTheCheckCancelsItAndAnswersBoth) {
  Rig rig;
  rig.settle();  // loop()'s first note: the Mega admits a job
  ASSERT_EQ(rig.network.admitBody(), Admission::Accepted);
  rig.spool.text = "{job}";
  uint16_t ticket = 0, cancel = 0;
  auto post = rig.ask(Ask::CheckBody, ticket);
  std::shared_ptr<Request> del;
  rig.check.yield = [&] {
    if (!del) del = rig.ask(Ask::Cancel, cancel);
  };
  rig.settle();
  EXPECT_EQ(post->sends, 1);
  EXPECT_EQ(post->status, 409);
  EXPECT_EQ(del->sends, 1);
  EXPECT_EQ(del->status, 200);
  EXPECT_EQ(rig.hub.uploadsStarted, 0);
  EXPECT_EQ(rig.network.admitBody(), Admission::Accepted);  // the spool is free again
}

}  // namespace
