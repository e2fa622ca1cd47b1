// Waking the network task from loop() (network_wake.h).
#include "network_wake.h"

#if defined(ESP32)
#include <atomic>

#include <lwip/priv/tcp_priv.h>  // tcp_active_pcbs: lwIP's thread's own list
#include <lwip/tcpip.h>
#endif

namespace uv {
namespace esp {

namespace {
void (*answers)() = nullptr;
void (*liveMessages)() = nullptr;
}  // namespace

void onNetworkPump(void (*pumpAnswers)(), void (*pumpLive)()) {
  answers = pumpAnswers;
  liveMessages = pumpLive;
}

void pumpNetwork() {
  if (answers) answers();
  if (liveMessages) liveMessages();
}

#if defined(ESP32)
namespace {
std::atomic<bool> pending{false};

// On lwIP's thread: each connection of the web server polled now, as tcp_slowtmr would at its next
// 500 ms tick. For AsyncTCP's connections that queues a poll event for its task, which runs the
// connection's onPoll there: our pump for the requests waiting for loop() (print_endpoint.cpp) and
// for /ws (live_socket.cpp), the library's own for the others (it sends what remains of a
// response, harmless when nothing does). A connection AsyncTCP let go of has no poll callback any
// more: that is done on this same thread (tcpip_api_call), so never halfway through this walk.
void poll(void*) {
  pending.store(false, std::memory_order_relaxed);
  for (tcp_pcb* p = tcp_active_pcbs; p; p = p->next)
    if (p->local_port == 80 && p->poll) p->poll(p->callback_arg, p);
}
}  // namespace

void wakeNetwork() {
  if (pending.exchange(true, std::memory_order_relaxed)) return;  // one wake in flight is enough
  if (tcpip_callback(poll, nullptr) != ERR_OK) pending.store(false, std::memory_order_relaxed);
}
#else
void wakeNetwork() {}
#endif

}  // namespace esp
}  // namespace uv
