// What each board's network stack allows, read from the pinned libraries, so the glue and the host
// hub (which models the ESP8266) apply the same limits.
#pragma once
#include <stdint.h>

namespace uv {
namespace esp {

struct Board {
  uint8_t tcpSockets;  // lwIP's MEMP_NUM_TCP_PCB (core 3.1.2's lwipopts.h: 5) / ESP-IDF's default 16
  uint8_t wsClients;   // /ws clients let in: the rest of the sockets stay for HTTP
  uint8_t wsQueue;     // ESPAsyncWebServer 3.12's WS_MAX_QUEUED_MESSAGES: a client's queued frames
};

// ESP8266: three /ws clients leave two sockets for HTTP (a POST's body, and a status or a DELETE).
constexpr Board kEsp8266{5, 3, 8};
constexpr Board kEsp32{16, 4, 32};

#if defined(ESP32)
constexpr Board kBoard = kEsp32;
#else
constexpr Board kBoard = kEsp8266;
#endif

}  // namespace esp
}  // namespace uv
