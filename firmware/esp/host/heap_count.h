// The host hub's own heap, counted apart from the simulated Mega's (issue 36, the soak): every
// operator new of the process is tagged with its owner, the hub (its core, the hand-over, the
// HTTP and WebSocket sessions) or the rig (the simulated Mega and its SD card, whose files grow
// with every job as a real card does), and its bytes are counted live until they are freed.
#pragma once
#include <stdint.h>

namespace hub {
namespace heap {

enum class Owner : uint8_t { Hub = 0, Rig = 1 };

// Allocations made on this thread while one lives are the rig's.
class RigScope {
 public:
  RigScope();
  ~RigScope();
  RigScope(const RigScope&) = delete;
  RigScope& operator=(const RigScope&) = delete;

 private:
  Owner before_;
};

struct Live {
  int64_t bytes;   // asked for, without the count's own tag
  int64_t blocks;
};
Live live(Owner o);

}  // namespace heap
}  // namespace hub
