// The printhead's command brain: the protocol/nano.md table, refusals, latched faults and the pixel colour.
// Plain C++: the board drivers sit behind PrintheadIo, so all of it is tested on the host.
#pragma once
#include <stdint.h>

#include "dose_tally.h"
#include "fire_plan.h"
#include "nano_codec.h"
#include "scan_store.h"
#include "thermal_guard.h"

namespace nano {

// Servo pulse widths a BLTouch / CR Touch expects (protocol/nano.md).
constexpr uint16_t kServoDeployUs = 647;
constexpr uint16_t kServoStowUs = 1473;
constexpr uint16_t kServoAlarmReleaseUs = 2194;
constexpr uint16_t kFlashMs = 60;

class PrintheadIo {
 public:
  virtual void fire(const FirePlan& plan) = 0;  // LEDs on in one port write, offs on the timer
  virtual void allOff() = 0;                    // every LED off in one write, pending offs cleared
  // Whether the board already switched everything off for this R the moment it arrived (the
  // UART's interrupt does, so R acts within microseconds however busy the main loop is), and
  // something was lit or still to switch then.
  virtual bool cutByReset() { return false; }
  // Whether the LEDs were cut (R, a fault, silence, a fall-back) since the last call, and when: ticks
  // (16 a µs) after an F's on-edge, or after the last event a chain made (negative before time 0).
  virtual bool takeCut(int32_t& ticks) = 0;
  // Runs the store's armed chain from the `G` just received; false when the G's time 0 has gone
  // by (the Nano took it too late) and nothing runs.
  virtual bool startProgram(ScanStore& store) = 0;
  // The Nano's micros() when the `\n` of the latest `W` arrived (its receive interrupt notes it),
  // by which the Mega measures this clock against its own.
  virtual uint32_t clockLineUs() = 0;
  virtual uint8_t litMask() const = 0;
  virtual void servoPulse(uint16_t us) = 0;     // 50 Hz train of this width from now on
  virtual bool probeTriggered() = 0;            // level now, or a latched pulse since the last call
  virtual void reply(const char* text, uint8_t len) = 0;
  // The link's speed (protocol/nano.md "Link speed"): from the moment the reply just queued has
  // gone out when `afterReply`, else at once.
  virtual void linkSpeed(uint32_t baud, bool afterReply) = 0;
};

// A switch to a raised speed holds only if a correct line arrives at it within this long.
constexpr uint32_t kLinkConfirmMs = 100;

struct PrintheadConfig {
  uint32_t capUs;
  ThermalLimits thermal;
  const char* firmwareVersion;
};

class Printhead {
 public:
  Printhead(PrintheadIo& io, const PrintheadConfig& cfg) : io_(io), cfg_(cfg), guard_(cfg.thermal), store_(cfg.capUs) {}

  // One line from the UART splitter (without terminator).
  void line(const char* text, uint8_t len, bool overflow, uint32_t nowMs);
  // Every pass of the main loop: a running chain whose Mega has fallen silent is cut.
  void poll(uint32_t nowMs);
  // A received byte that cannot be in a line (a framing or overrun error, or outside 0x20-0x7E, \r
  // and \n): above 115200 it is a doubt about the speed, and the link falls back.
  void noise();
  // Above 115200 (an L raised it, and no doubt has lowered it since).
  bool linkRaised() const { return raised_; }
  // A fresh set of oversampled readings, in mV. Cuts the LEDs on a fault.
  void readings(const uint16_t mv[uv::kSensorCount]);
  void watchdogReset() { latched_ |= uv::fault::kWatchdog; }
  // This start's number (from the EEPROM), for the C reply: a Mega tells a restart by it.
  void setBoot(uint16_t boot) { boot_ = boot; }

  // What the pixel should show now: a command's flash, then green, or red while a fault is active.
  uv::Colour colour(uint32_t nowMs);
  uint8_t faults() const { return static_cast<uint8_t>(guard_.active() | latched_); }
  const int16_t* deciC() const { return deciC_; }
  const ScanStore& store() const { return store_; }

 private:
  void handle(const uv::NanoCommand& c, uint32_t nowMs);
  void fire(const uv::NanoCommand& c);
  bool program(const char* text, uint8_t len);  // an A or K line; false when malformed
  void start();
  bool exposing() const { return io_.litMask() || store_.running(); }
  void send(const uv::NanoReply& r);
  // The dose records of what has ended since the last call: an F gone dark, the programs the chain
  // ran to their last event, and a cut's running program up to the cut. Before every line, every
  // poll and every discard, so a spent buffer is read before it is loaded again.
  void settle();
  void speed(uint32_t baud, uint32_t nowMs);
  // Back to 115200 at once, and, as an R would, every LED off and every program dropped.
  void fallBack();

  PrintheadIo& io_;
  const PrintheadConfig& cfg_;
  ThermalGuard guard_;
  ScanStore store_;
  DoseTally dose_;
  int16_t deciC_[uv::kSensorCount] = {};
  uint8_t latched_ = 0;
  uv::Colour flash_ = uv::Colour::Green;
  uint32_t flashUntilMs_ = 0;
  bool flashing_ = false;
  bool measured_ = false;  // no F before the first full set of readings
  uint16_t boot_ = 0;
  uint32_t fires_ = 0;     // F commands that lit since start
  bool whole_ = true;      // the last one was not cut short by R or a fault
  bool programLast_ = false;  // the last one was a scan chain: an underrun also cuts it short
  uint32_t lastLineMs_ = 0;   // when the last complete line arrived
  // RAM is short (the 50 % budget): the speed as whether it is raised, and its time in 16 bits.
  bool raised_ = false;
  bool confirming_ = false;   // raised, and no correct line heard at the new speed yet
  uint16_t switchedMs_ = 0;   // when it was raised (low bits of millis(): the window is 100 ms)
};

}  // namespace nano
