// Test support: the whole simulated Mega of the Mega's host tests (mega_rig.h) on its ESP port,
// behind a serial line that can damage and drop bytes each way.
#pragma once
#include <stdint.h>

#include <random>
#include <string>

#include "live_channel.h"
#include "mega_rig.h"
#include "mega_sender.h"

namespace esptest {

struct NoisyMega : uv::esp::MegaWire {
  mega::MegaRig mega;
  std::mt19937 rng{1};
  double corrupt = 0, drop = 0;  // per byte, each way
  size_t fed = 0;                // the Mega's lines already handed to the ESP
  uint64_t written = 0;          // bytes the ESP wrote to the Mega, before any noise

  bool write(const char* data, uint16_t n) override {
    written += n;
    for (uint16_t i = 0; i < n; i++) mega.esp.toMega += noisy(data[i]);
    return true;
  }
  std::string noisy(char c) {
    std::uniform_real_distribution<double> u(0, 1);
    if (u(rng) < drop) return "";
    if (u(rng) < corrupt) return std::string(1, static_cast<char>(c ^ (1 << (rng() % 8))));
    return std::string(1, c);
  }
  uint32_t nowMs() const { return static_cast<uint32_t>(mega.nowUs / 1000); }
  // Runs the Mega for `us`, a millisecond at a time, handing each byte it sent to `received`
  // and calling `loop` as the ESP's loop would.
  template <class Received, class Loop>
  void run(uint64_t us, Received received, Loop loop) {
    for (uint64_t t = 0; t < us; t += 1000) {
      mega.run(1000);
      for (; fed < mega.espLines.size(); fed++)
        for (char c : mega.espLines[fed] + "\n")
          for (char d : noisy(c)) received(d, nowMs());
      loop(nowMs());
    }
  }
  // The Mega restarts; the ESP will read its "start" next.
  void restart(uint64_t bootUs = 200000) {
    mega.reset(bootUs);
    fed = mega.espLines.size() - 1;
  }
};

// Web clients that take every message at once, for tests about the Mega's side.
struct NoClients : uv::esp::LiveClients {
  bool trySend(uint8_t, const char*, uint16_t) override { return true; }
  void close(uint8_t, uint16_t, const char*) override {}
};

}  // namespace esptest
