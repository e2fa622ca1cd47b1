// The host hub's lifeline: its stdin and the stop signals, each watched by a thread of its own.
#include "lifeline.h"

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <thread>

#include "heap_count.h"

namespace hub {

void holdLifeline(std::function<void()> leave) {
  sigset_t stops;
  sigemptyset(&stops);
  for (int sig : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&stops, sig);
  pthread_sigmask(SIG_BLOCK, &stops, nullptr);  // every thread started from here on inherits it
  std::thread([stops, leave] {
    int sig;
    sigwait(&stops, &sig);
    leave();
  }).detach();
  std::thread([leave] {
    std::string line;
    char c;
    while (::read(0, &c, 1) > 0) {
      if (c != '\n') {
        line += c;
        continue;
      }
      if (line == "heap") {
        heap::Live h = heap::live(heap::Owner::Hub), r = heap::live(heap::Owner::Rig);
        std::printf("heap: hub %lld B in %lld blocks, rig %lld B in %lld blocks\n", static_cast<long long>(h.bytes), static_cast<long long>(h.blocks),
                    static_cast<long long>(r.bytes), static_cast<long long>(r.blocks));
        std::fflush(stdout);
      }
      line.clear();
    }
    leave();
  }).detach();
}

}  // namespace hub
