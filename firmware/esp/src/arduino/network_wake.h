// The network task's sends on demand. Everything that touches the web libraries runs on the
// network task; loop() only publishes (the hand-over's answers, the live channel's messages) and
// says so. On the ESP32 the answer would otherwise wait for AsyncTCP's poll of its connection,
// every 500 ms: wakeNetwork() has lwIP's thread poll the connections now (tcpip_callback), which
// AsyncTCP turns into a poll event on its own task. On the ESP8266 the network callbacks run only
// between loop()'s passes, so loop() sends itself at the end of each pass, and waking is nothing.
#pragma once

namespace uv {
namespace esp {

// The network task: what it sends when woken or polled (set once in setup()).
void onNetworkPump(void (*pumpAnswers)(), void (*pumpLive)());
void pumpNetwork();
// loop(): something new was published for the network task to send.
void wakeNetwork();

}  // namespace esp
}  // namespace uv
