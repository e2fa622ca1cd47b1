// A fixed queue that hands work from one task to another without either waiting for the other:
// the ESP's network task puts HTTP requests in, loop() takes them out and answers them. Lock is a
// type with lock() and unlock() held only to move one entry (a critical section on the ESP32,
// nothing on the ESP8266, where network callbacks never preempt loop(); std::mutex in tests).
#pragma once
#include <stdint.h>

#include <utility>

namespace uv {
namespace esp {

template <class T, uint8_t N, class Lock>
class HandOver {
 public:
  // False when N entries are already waiting: the caller answers at once instead.
  bool put(T&& item) {
    lock_.lock();
    bool room = count_ < N;
    if (room) {
      slots_[(head_ + count_) % N] = std::move(item);
      count_++;
    }
    lock_.unlock();
    return room;
  }
  // The oldest entry, or false when none waits.
  bool take(T& out) {
    lock_.lock();
    bool any = count_ > 0;
    if (any) {
      out = std::move(slots_[head_]);
      slots_[head_] = T{};  // whatever the entry held (a request's pointer) is let go here
      head_ = static_cast<uint8_t>((head_ + 1) % N);
      count_--;
    }
    lock_.unlock();
    return any;
  }
  uint8_t waiting() {
    lock_.lock();
    uint8_t n = count_;
    lock_.unlock();
    return n;
  }

 private:
  Lock lock_;
  T slots_[N];
  uint8_t head_ = 0, count_ = 0;
};

}  // namespace esp
}  // namespace uv
