// The host's model of the ESP8266's flash under LittleFS, for the host hub and the tests
// (flash_gate_test.cpp): every flash operation yields in its middle, as the core's flash_hal does
// (optimistic_yield, whenever 10 ms have gone since the last yield; here always, the worst case),
// and the yield runs the network callbacks that are pending. An operation begun while another is
// under way is the re-entry that corrupts LittleFS: counted, and the host hub stops on it.
#pragma once
#include <stdint.h>

#include <functional>

namespace uvtest {

class HostFlash {
 public:
  // What yield() runs: the network callbacks (the host hub: its io_context's ready handlers).
  std::function<void()> yield;

  // loop()'s operation: it yields in its middle.
  template <class F>
  auto loopOperation(F f) -> decltype(f()) {
    return operation(f, true);
  }
  // A network callback's: in the SDK's context yield does nothing (optimistic_yield checks can_yield).
  template <class F>
  auto callbackOperation(F f) -> decltype(f()) {
    return operation(f, false);
  }
  uint64_t reentered() const { return reentered_; }
  uint64_t operations() const { return operations_; }

 private:
  template <class F>
  auto operation(F f, bool yields) -> decltype(f()) {
    operations_++;
    if (depth_) reentered_++;
    depth_++;
    struct Leave {
      int& depth;
      ~Leave() { depth--; }
    } leave{depth_};
    if (yields && yield && !yielding_) {
      yielding_ = true;
      yield();
      yielding_ = false;
    }
    return f();
  }

  int depth_ = 0;
  bool yielding_ = false;
  uint64_t reentered_ = 0;
  uint64_t operations_ = 0;
};

}  // namespace uvtest
