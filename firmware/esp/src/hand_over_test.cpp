// The hand-over of HTTP requests from the network task to loop(): in order, bounded, nothing lost
// or answered twice when both sides run at once, and what an entry holds let go when it is taken.
#include "hand_over.h"

#include <gtest/gtest.h>

#include <memory>
#include <mutex>
#include <thread>
#include <vector>

using uv::esp::HandOver;

namespace {
struct NoLock {
  void lock() {}
  void unlock() {}
};
struct Entry {
  int id = 0;
  std::weak_ptr<int> request;  // as AsyncWebServerRequestPtr: empty once the client is gone
};
}  // namespace

TEST(HandOver, TakesInOrderAndRefusesWhenFull) {
  HandOver<Entry, 3, NoLock> q;
  Entry e;
  EXPECT_FALSE(q.take(e));
  for (int i = 1; i <= 3; i++) EXPECT_TRUE(q.put(Entry{i, {}}));
  EXPECT_FALSE(q.put(Entry{4, {}}));  // the caller answers this one itself
  EXPECT_EQ(q.waiting(), 3);
  ASSERT_TRUE(q.take(e));
  EXPECT_EQ(e.id, 1);
  EXPECT_TRUE(q.put(Entry{5, {}}));  // round the ring
  std::vector<int> order;
  while (q.take(e)) order.push_back(e.id);
  EXPECT_EQ(order, (std::vector<int>{2, 3, 5}));
}

TEST(HandOver, ARequestWhoseClientLeftIsSeenGoneWhenTaken) {
  HandOver<Entry, 4, NoLock> q;
  auto request = std::make_shared<int>(7);
  q.put(Entry{1, request});
  request.reset();  // the library deleted the request: the client disconnected
  Entry e;
  ASSERT_TRUE(q.take(e));
  EXPECT_TRUE(e.request.expired());
  EXPECT_FALSE(e.request.lock());
}

TEST(HandOver, KeepsNoHoldOnWhatItHandedOver) {
  HandOver<Entry, 2, NoLock> q;
  auto request = std::make_shared<int>(1);
  std::weak_ptr<int> watch = request;
  q.put(Entry{1, request});
  {
    Entry e;
    q.take(e);
  }
  request.reset();
  EXPECT_TRUE(watch.expired());
}

// One task puts, another takes, as on the ESP32's two cores: every entry is taken exactly once.
TEST(HandOver, EveryEntryIsTakenOnceWhenBothSidesRunAtOnce) {
  HandOver<Entry, 8, std::mutex> q;
  constexpr int kEntries = 20000;
  std::vector<int> seen(kEntries + 1, 0);
  int refused = 0;
  std::thread network([&] {
    for (int i = 1; i <= kEntries; i++)
      while (!q.put(Entry{i, {}})) refused++;  // the test retries; the ESP answers 503 instead
  });
  int taken = 0, last = 0;
  bool inOrder = true;
  Entry e;
  while (taken < kEntries) {
    if (!q.take(e)) continue;
    seen[e.id]++;
    inOrder &= e.id == last + 1;
    last = e.id;
    taken++;
  }
  network.join();
  EXPECT_TRUE(inOrder);
  for (int i = 1; i <= kEntries; i++) ASSERT_EQ(seen[i], 1) << i;
  EXPECT_EQ(q.waiting(), 0);
}
