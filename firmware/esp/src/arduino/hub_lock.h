// The locks between the ESP's network task and loop(). Who owns what is written in
// print_endpoint.cpp; this file only says how each chip keeps the two apart.
//
// ESP32: ESPAsyncWebServer's handlers run on AsyncTCP's own FreeRTOS task, beside loop()'s task and
// possibly on the other core. HubLock is a mutex that loop() holds for its whole pass and a
// handler takes only to admit or release a POST /print (a few bytes of the bridge). It cannot
// deadlock: while holding it loop() waits only on lwIP's tcpip thread (a socket write), and that
// thread never waits for AsyncTCP's task (its event list is unbounded). EntryLock is a critical
// section held only to move one queue entry.
//
// ESP8266: ESPAsyncTCP's callbacks run in the SDK's context, which only runs when loop() yields
// (at the end of service()), never in the middle of a bridge or intake operation: both locks are
// empty.
#pragma once

#if defined(ESP32)
#include <freertos/FreeRTOS.h>
#include <freertos/semphr.h>
#endif

namespace uv {
namespace esp {

#if defined(ESP32)
class HubLock {
 public:
  void begin() { mutex_ = xSemaphoreCreateMutexStatic(&store_); }
  void lock() { xSemaphoreTake(mutex_, portMAX_DELAY); }
  void unlock() { xSemaphoreGive(mutex_); }

 private:
  StaticSemaphore_t store_;
  SemaphoreHandle_t mutex_ = nullptr;
};

class EntryLock {
 public:
  void lock() { portENTER_CRITICAL(&mux_); }
  void unlock() { portEXIT_CRITICAL(&mux_); }

 private:
  portMUX_TYPE mux_ = portMUX_INITIALIZER_UNLOCKED;
};
#else
class HubLock {
 public:
  void begin() {}
  void lock() {}
  void unlock() {}
};

class EntryLock {
 public:
  void lock() {}
  void unlock() {}
};
#endif

// Held by loop() over its pass and by the network task around Bridge::admitPrint/release.
extern HubLock hubLock;

class HubGuard {
 public:
  HubGuard() { hubLock.lock(); }
  ~HubGuard() { hubLock.unlock(); }
  HubGuard(const HubGuard&) = delete;
  HubGuard& operator=(const HubGuard&) = delete;
};

}  // namespace esp
}  // namespace uv
