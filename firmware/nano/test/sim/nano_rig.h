// Test rig: runs the real printhead image (build/avr/nano.elf) in simavr and records, with CPU-cycle
// timestamps, its UART traffic, pin edges and how long interrupts stay off.
#pragma once
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

struct avr_t;
struct avr_irq_t;

class NanoRig {
 public:
  static constexpr double kCyclesPerUs = 16.0;

  struct Edge {
    uint64_t cycle;
    bool high;
  };
  struct OutByte {
    uint64_t cycle;
    char c;
  };

  explicit NanoRig(const std::string& elf);
  ~NanoRig();

  // Runs the CPU for a span of simulated time, one instruction at a time.
  void runUs(double us);
  template <class Pred>
  bool runUntil(Pred done, double maxUs) {
    uint64_t end = cycle() + static_cast<uint64_t>(maxUs * kCyclesPerUs);
    while (cycle() < end) {
      if (done()) return true;
      step();
    }
    return done();
  }

  uint64_t cycle() const;
  // Queues bytes for the Nano's UART; they arrive back to back at the UART's byte rate.
  void send(const std::string& bytes) { pending_.insert(pending_.end(), bytes.begin(), bytes.end()); }
  bool sendIdle() const { return pending_.empty() && inFifo_ == 0; }
  // Lines the Nano wrote since the last call.
  std::vector<std::string> takeLines();
  void setMv(int channel, int mv);
  // Sends the CPU into an endless loop at `byteAddress` with interrupts still on: a hung main loop.
  void hangAt(uint32_t byteAddress);
  void setProbe(bool high);

  // Edges per pin: 'B' bits 0-5 (pixel, LEDs) and 'D' bit 3 (servo).
  const std::vector<Edge>& edges(char port, int bit) const { return edges_[port == 'B' ? bit : 8 + bit]; }
  void clearEdges();
  bool level(char port, int bit) const;

  // Cycle at which each received '\n' raised the UART receive interrupt, oldest first.
  std::deque<uint64_t> lineEnds;
  std::vector<OutByte> output;
  // The longest stretch, in cycles, with the global interrupt flag clear (ISRs included).
  uint64_t maxInterruptsOff = 0;
  void resetInterruptStats() { maxInterruptsOff = 0; }

 private:
  void step();
  void feed();
  static void onPin(avr_irq_t* irq, uint32_t value, void* param);
  static void onOutput(avr_irq_t* irq, uint32_t value, void* param);
  static void onRxPending(avr_irq_t* irq, uint32_t value, void* param);

  avr_t* avr_ = nullptr;
  avr_irq_t* uartIn_ = nullptr;
  std::deque<char> pending_;
  std::deque<char> delivered_;  // pushed to simavr, not yet raised as a receive interrupt
  int inFifo_ = 0;
  std::vector<Edge> edges_[16];
  struct PinRef {
    NanoRig* rig;
    int index;
  } pinRefs_[16];
  std::string partial_;
  size_t linesTaken_ = 0;
  uint64_t offSince_ = 0;
  bool wasOff_ = false;
};
