// A fixed ring between exactly two tasks, one that only puts and one that only takes, with no lock:
// the ESP32's network task and loop() hand each other messages through these (hand_over.h). Nothing
// waits: a full ring refuses at once and an empty one says so. Entries are plain data, filled and
// read in place, so a 2 KB answer is never copied onto a small stack.
#pragma once
#include <stdint.h>

#include <atomic>
#include <type_traits>

namespace uv {
namespace esp {

template <class T, uint8_t N>
class SpscRing {
  // Anything with a destructor (a request's shared or weak pointer) would run it on whichever task
  // took the entry: only plain data crosses.
  static_assert(std::is_trivially_copyable<T>::value, "only plain data crosses between the tasks");
  // The counts run free and wrap at 2^32, which a power of two divides: an entry never moves.
  static_assert(N > 0 && N <= 128 && (N & (N - 1)) == 0, "a power of two up to 128");

 public:
  // --- the putting task only ---
  // The next free entry, to fill before publish(); nullptr when the ring is full.
  T* claim() { return room() ? &slots_[written_.load(std::memory_order_relaxed) % N] : nullptr; }
  // The claimed entry is now the taker's: its contents are seen whole, never half-written.
  void publish() { written_.store(written_.load(std::memory_order_relaxed) + 1, std::memory_order_release); }
  bool push(const T& item) {
    T* slot = claim();
    if (!slot) return false;
    *slot = item;
    publish();
    return true;
  }
  // Free entries as the putter sees them: the taker can only add to them meanwhile.
  uint8_t room() const {
    return static_cast<uint8_t>(N - (written_.load(std::memory_order_relaxed) - read_.load(std::memory_order_acquire)));
  }

  // --- the taking task only ---
  // The oldest entry, still the taker's to read until pop(); nullptr when none waits.
  const T* front() const {
    uint32_t at = read_.load(std::memory_order_relaxed);
    return written_.load(std::memory_order_acquire) != at ? &slots_[at % N] : nullptr;
  }
  // Gives the entry front() showed back to the putter.
  void pop() { read_.store(read_.load(std::memory_order_relaxed) + 1, std::memory_order_release); }

 private:
  T slots_[N];
  // Free-running counts: each is written by one task only and read by the other.
  std::atomic<uint32_t> written_{0}, read_{0};
};

}  // namespace esp
}  // namespace uv
