// Test rig: the real Mega image (build/avr/mega.elf) and the real Nano image (build/avr/nano.elf)
// in one simavr process, their UARTs cross-connected as on the machine. The rig plays the host on
// the Mega's USB UART, counts step pulses on the CNC shield's pins, and closes the endstops when an
// axis reaches its switch. An SSD1306 model answers on the Mega's TWI, and the rig measures the
// panel's CPU time per main-loop pass.
#pragma once
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "ssd1306_model.h"

struct avr_t;
struct avr_irq_t;

class BoardSim {
 public:
  static constexpr double kCyclesPerUs = 16.0;

  BoardSim(const std::string& megaElf, const std::string& nanoElf);

  void runUs(double us);
  template <class Pred>
  bool runUntil(Pred done, double maxUs) {
    uint64_t end = megaCycle() + static_cast<uint64_t>(maxUs * kCyclesPerUs);
    while (megaCycle() < end) {
      if (done()) return true;
      for (int i = 0; i < 64; i++) step();
    }
    return done();
  }
  uint64_t megaCycle() const;

  // Host side of the Mega's USB UART.
  void send(const std::string& bytes);
  // Lines the Mega sent the host since the last call.
  std::vector<std::string> takeLines();
  // Host side of the Mega's ESP UART (Serial2, esp.port's default).
  void sendEsp(const std::string& bytes);
  std::vector<std::string> takeEspLines();
  // The stack's high-water mark: the lowest RAM address it has written since power-up, and its
  // depth in bytes from the top of RAM. The free RAM above static RAM starts at staticEnd().
  uint16_t stackDeepest() const;
  uint16_t stackBytes() const;
  uint16_t staticEnd() const { return staticEnd_; }
  // Every line the Mega sent the Nano, and every line the Nano answered.
  std::vector<std::string> nanoLines, nanoReplies;
  // Each line the Mega sent the Nano: the Mega's cycle as its first byte and its '\n' went out.
  std::vector<uint64_t> nanoLineFirst, nanoLineLast;

  // The Mega's longest stretch with the global interrupt flag clear (ISRs included), in cycles,
  // and where it began: an interrupt's vector (bytes: 4 × its number), or the code that cleared it.
  uint64_t megaMaxInterruptsOff = 0;
  uint32_t megaMaxOffPc = 0;
  // While set: the Mega's cycles and instructions run by the word address of each instruction (a
  // profile of the real image, ISRs included; scripts/mega-profile.py names the functions).
  struct PcCount {
    uint64_t cycles = 0, runs = 0;
  };
  std::vector<PcCount>* megaProfile = nullptr;
  bool profileTimedOnly = false;  // megaProfile counts only timeCalls()'s calls, their callees included

  // The panel on the Mega's TWI.
  Ssd1306Model panel;
  // The panel's CPU per main-loop pass, in cycles: Machine::panel() (the screen and the frame it
  // starts, other interrupts taken meanwhile left out) plus the TWI interrupts since the pass before.
  uint64_t panelPassMax = 0;
  uint64_t panelPasses = 0;
  uint64_t panelCallMax = 0;     // the longest Machine::panel() alone
  uint64_t twiIsrCycles = 0;     // all of the TWI interrupt's time
  uint64_t twiIsrMax = 0;        // its longest single run
  void resetPanelFigures() { panelPassMax = panelPasses = panelCallMax = twiIsrCycles = twiIsrMax = 0; }
  // Times every call of a function of the Mega's image from now on: `symbol` is its mangled name (or
  // the start of it: LTO may add a suffix). Each call's cycles, its callees' included and the
  // interrupts taken meanwhile left out, and the Mega's cycle count as it began and returned, go to
  // timedCalls(symbol). False when the image has no such function.
  bool timeCalls(const std::string& symbol);
  struct TimedCall {
    uint64_t cycles, from, to;
  };
  const std::vector<TimedCall>& timedCalls(const std::string& symbol) const;
  // Sets the Nano's sensor input `ch` (TMP36: 500 mV + 10 mV/°C).
  void setNanoMv(int ch, uint32_t mv);

  // The Nano's clock against the Mega's: 1 + its error. Each board's 16 MHz comes from its own
  // crystal or resonator (±50 ppm and ±0.5 %), and a scan's light runs on the Nano's.
  double nanoClock = 1.0;
  // While `logging`: every X or Y step with the head's place after it, and every edge of the Nano's
  // four LED pins (D10-D13), each with its time in the Mega's cycles.
  bool logging = false;
  struct HeadStep {
    uint64_t cycle;
    int32_t x, y;
  };
  std::vector<HeadStep> headSteps;
  struct LedEdge {
    uint64_t cycle;
    int led;
    bool on;
  };
  std::vector<LedEdge> ledEdges;
  // While `logging`: each line on the printhead link as its newline leaves the sender's UART,
  // `toNano` for the Mega's, else the Nano's reply (the stop cycle's timeline, stop_sim_test).
  struct LinkLine {
    uint64_t cycle;
    bool toNano;
    std::string text;
  };
  std::vector<LinkLine> linkLines;

  int32_t pos[3] = {0, 0, 0};                       // steps counted on the pins
  int32_t switchAt[3] = {INT32_MIN, INT32_MIN, INT32_MIN};  // a switch closes at or below this
  bool dirHigh[3] = {false, false, false};

  // A byte-fed UART: keeps simavr's receive FIFO topped up so bytes arrive back to back.
  struct Feed {
    avr_t* avr;
    avr_irq_t* in;
    std::deque<char> pending;
    int inFifo = 0;
    void push();
  };

 private:
  void step();
  void setSwitch(int axis);
  static void onStep(avr_irq_t* irq, uint32_t value, void* param);
  static void onDir(avr_irq_t* irq, uint32_t value, void* param);
  static void onLed(avr_irq_t* irq, uint32_t value, void* param);
  static void onHostOut(avr_irq_t* irq, uint32_t value, void* param);
  static void onEspOut(avr_irq_t* irq, uint32_t value, void* param);
  static void onMegaToNano(avr_irq_t* irq, uint32_t value, void* param);
  static void onNanoToMega(avr_irq_t* irq, uint32_t value, void* param);
  static void onRxTaken(avr_irq_t* irq, uint32_t value, void* param);
  static void onTwi(avr_irq_t* irq, uint32_t value, void* param);
  void profilePanel(uint64_t cycles, bool wasInPanel, int wasVector);

  avr_t* mega_ = nullptr;
  avr_t* nano_ = nullptr;
  Feed host_{}, esp_{}, toNano_{}, toMega_{};
  struct AxisRef {
    BoardSim* sim;
    int axis;
  } axisRefs_[3], ledRefs_[4];
  std::string hostPartial_, nanoPartial_, replyPartial_;
  std::deque<std::string> hostLines_, espLines_;
  std::string espPartial_;
  uint16_t staticEnd_ = 0;
  avr_irq_t* switchIrq_[3] = {};
  bool switchClosed_[3] = {false, false, false};
  bool ledOn_[4] = {false, false, false, false};
  bool megaOff_ = false;
  uint64_t megaOffSince_ = 0;
  uint32_t megaOffPc_ = 0;
  avr_irq_t* twiIn_ = nullptr;
  uint32_t panelEntry_ = 0;  // Machine::panel()'s address (noinline), 0 if the image has none
  bool inPanel_ = false;
  uint16_t panelSp_ = 0;
  uint64_t passCycles_ = 0, isrRun_ = 0, callCycles_ = 0;
  std::string megaElf_;
  struct TimedFunction {
    std::string symbol;
    uint32_t entry;
    bool in = false;
    uint16_t sp = 0;  // the stack pointer in the call (its return address pushed)
    std::vector<TimedCall> calls;
  };
  std::vector<TimedFunction> timed_;
  bool inTimed() const;
  void timeCall(uint64_t cycles, int wasVector);
  int lastVector_ = 0;
};
