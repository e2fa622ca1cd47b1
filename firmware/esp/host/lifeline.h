// How long the host hub lives: as long as whoever started it.
#pragma once
#include <functional>

namespace hub {

// When stdin closes (the test runner ended, however it ended) or a SIGTERM, SIGINT or SIGHUP
// comes, `leave` runs (it takes the hub's flash with it and exits). Run by hand, the hub reads the
// terminal and ends at Ctrl-D. The signals are taken by one thread alone, so nothing else is cut
// short in the middle of a write: call it before any other thread is started. Test-only: a line
// `heap` on stdin prints the hub's live heap apart from the rig's (heap_count.h).
void holdLifeline(std::function<void()> leave);

}  // namespace hub
