// The ESP8266's file system, kept from being re-entered (protocol/esp.md "The flash"). The core's
// flash calls yield (flash_hal.cpp calls optimistic_yield(10000) before each read, write and erase),
// and yield() runs the network callbacks, which use LittleFS too, between two of loop()'s calls
// into it: LittleFS has no lock, and its caches and open-file list would be corrupted. So loop()
// holds the gate across each of its file operations, and a network callback that finds it held
// touches no file: a request is answered 503 flash_busy with Retry-After, a file being sent sends
// its next part at the connection's next poll. On the ESP32 the network task is a task of its own
// and LittleFS (esp_littlefs) locks itself: the glue does not ask the gate there.
#pragma once
#include <stdint.h>

namespace uv {
namespace esp {

class FlashGate {
 public:
  // loop()'s: the gate is held while one lives (they nest).
  class Hold {
   public:
    explicit Hold(FlashGate& g) : g_(g) { g_.depth_++; }
    ~Hold() { g_.depth_--; }
    Hold(const Hold&) = delete;
    Hold& operator=(const Hold&) = delete;

   private:
    FlashGate& g_;
  };
  // The network side's question: is loop() inside a file operation?
  bool held() const { return depth_ != 0; }

 private:
  uint8_t depth_ = 0;
};

// The answer to a request that would touch the flash while loop() is inside a file operation.
constexpr uint16_t kFlashBusyStatus = 503;
constexpr const char* kFlashBusyCode = "flash_busy";
constexpr const char* kFlashBusyMessage = "the ESP is using its flash; try again";
constexpr const char* kFlashRetryAfter = "1";  // seconds: a file operation takes milliseconds

}  // namespace esp
}  // namespace uv
