// The framing of what the host sends the bootloader rig on its stdin: wire bytes, the port's baud, a DTR pulse.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace uv {

struct RigFrame {
  char kind;  // 'D' bytes on the wire, 'B' the host's baud, 'R' a DTR pulse (reset)
  std::vector<uint8_t> bytes;
  uint32_t baud = 0;
};

// Cuts stdin's stream into frames, wherever read() split it. An unknown kind byte is skipped.
class RigFrames {
 public:
  template <class OnFrame>
  void feed(const uint8_t* data, size_t n, OnFrame onFrame) {
    for (size_t i = 0; i < n; i++) {
      uint8_t b = data[i];
      if (need_ < 0) {
        frame_ = RigFrame{static_cast<char>(b), {}, 0};
        if (b == 'R') {
          onFrame(frame_);
        } else if (b == 'B') {
          need_ = 4;
        } else if (b == 'D') {
          need_ = 0;
          counted_ = false;
        }
        continue;
      }
      if (frame_.kind == 'D' && !counted_) {
        counted_ = true;
        need_ = b;
      } else if (frame_.kind == 'D') {
        frame_.bytes.push_back(b);
        need_--;
      } else {
        frame_.baud |= static_cast<uint32_t>(b) << (8 * (4 - need_));
        need_--;
      }
      if (need_ == 0 && (frame_.kind != 'D' || counted_)) {
        if (frame_.kind != 'D' || !frame_.bytes.empty()) onFrame(frame_);
        need_ = -1;
      }
    }
  }

 private:
  RigFrame frame_{};
  int need_ = -1;  // bytes still to come in this frame; -1 between frames
  bool counted_ = false;
};

}  // namespace uv
