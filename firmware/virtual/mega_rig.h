// Host tests' whole Mega: the command core with its real collaborators (host links, motion and the
// step interrupt's code, printhead link, config store) and fakes of what is outside the chip: two
// hosts, the Nano (running the real Nano logic), an SD card, the EEPROM, endstops and pins.
#pragma once
#include <stdint.h>

#include <array>
#include <functional>
#include <new>
#include <string>
#include <vector>

#include "config_store.h"
#include "dialect_frame.h"
#include "eeprom_fake.h"
#include "fake_nano.h"
#include "host_link.h"
#include "machine.h"
#include "motion_rig.h"
#include "storage_fake.h"

namespace mega {

// One host's end of a serial port, at 115200 baud: about 11.5 bytes a millisecond each way.
class HostPipe : public TxPort {
 public:
  void kick() override {}
  // Moves what the wire carries in `us` between the host and the Mega's interrupts.
  void carry(HostLink& link, uint64_t us) {
    credit_ += us * 11520;
    while (credit_ >= 1000000) {
      credit_ -= 1000000;
      if (!toMega.empty()) {
        link.received(toMega.front());
        toMega.erase(0, 1);
      }
      int16_t b = link.nextTx();
      if (b >= 0) fromMega.push_back(static_cast<char>(b));
    }
  }
  // Complete lines the Mega sent since the last call.
  std::vector<std::string> take() {
    std::vector<std::string> out;
    size_t nl;
    while ((nl = fromMega.find('\n')) != std::string::npos) {
      out.push_back(fromMega.substr(0, nl));
      fromMega.erase(0, nl + 1);
    }
    return out;
  }
  std::string toMega, fromMega;

 private:
  uint64_t credit_ = 0;
};

class FakeIo final : public MachineIo {
 public:
  explicit FakeIo(MotionRig& rig) : rig_(rig) {}
  uint8_t endstops() override { return rig_.endstops(); }
  void motorsEnabled(bool on) override { enabled = on; }
  bool light(uint8_t pin, bool on) override {
    if (pin < 2 || pin == 8) return false;
    lightPin = pin;
    lightOn = on;
    return true;
  }
  uint8_t buttons() override { return pressed; }
  void invertDirections(uint8_t bits) override { inverted = bits; }
  uint8_t inverted = 0;
  bool enabled = false, lightOn = false;
  uint8_t lightPin = 0;
  uint8_t pressed = 0;  // the panel's buttons held down

 private:
  MotionRig& rig_;
};

// A display that takes each row at once (the TWI timing is the simavr rig's and ssd1306_test's).
class FakeDisplay : public TextDisplay {
 public:
  void poll(uint32_t) override {}
  bool ready() override { return true; }
  bool takeLost() override { return false; }
  void row(uint8_t r, const char* text) override {
    rows[r] = text;
    draws++;
  }
  std::string rows[kScreenRows];
  int draws = 0;
};

// What the real Mega image's CPU adds to a stop that this rig's instant 100 µs passes leave out:
// from the E answer to the next stop's first step 2130 µs (StopCycle's timeline, stop_sim_test.cpp),
// and some 500 µs more in the board's ~250 µs passes elsewhere in the cycle (settled, fired, polled).
// Taken at the move's start, it brings the rig's whole stop to the real images' (StopCycle).
constexpr uint32_t kStopLoadUs = 2600;

class MegaRig {
 public:
  MegaRig() {
    nano.wired = true;  // the printhead link takes its time on the wire, both ways
    head.raiseSpeed(kRaiseNanoLink);  // as the board does (each side keeps its own speed in the fake)
    // The switches: each axis's endstop closes a little way below where the head starts.
    rig.switchAt[0] = -1234;
    rig.switchAt[1] = -2345;
    rig.switchAt[2] = -456;
  }

  Config config;
  FakeStorage sd;
  FakeEeprom eeprom;
  ConfigStore store{config, sd, eeprom};
  FakeNano nano;
  PrintheadLink head{nano};
  MotionRig rig{config};
  FakeIo io{rig};
  FakeDisplay display;
  HostPipe usb, esp;
  uint8_t movesFree = StepEngine::kBlocks;
  LoopStats stats = {};
  LineSlot usbSlots[kUsbWindow], espSlots[kEspWindow];
  HostLink usbLink{usb, movesFree, lineWindow(usbSlots)}, espLink{esp, movesFree, lineWindow(espSlots)};
  Machine machine{MachineParts{{&usbLink, &espLink}, rig.motion, head, config, store, sd, io, eeprom, display, "UVExposure 0.1.0 (Mega)", movesFree, stats}};
  uint64_t nowUs = 0;
  std::vector<std::string> usbLines, espLines;  // everything each host has read
  // Where the head stood (steps) when each exposure began, in the order of nano.exposures.
  std::vector<std::array<int32_t, 3>> firedAt;
  // The bed's surface under the probe, in µm of the head's Z (no bed: the probe never touches).
  std::function<int32_t(int32_t xUm, int32_t yUm)> bed;
  bool probeAlarm = false;  // the probe's next deploy ends in its alarm

  void begin() {
    // A scan pass's G leaves on its step (the board's step interrupt writes it to the Nano's UART)
    // and its newline reaches the Nano two byte-times later.
    rig.onMark = [this](uint64_t ticks) {
      gAt_ = ticks + 2 * (markLeadUs(head.baud()) - uv::kProgramStartLeadUs);  // 2 byte-times at the link's speed
      return true;
    };
    machine.begin(static_cast<uint32_t>(nowUs));
    run(1000);
  }

  // The Mega restarts (its watchdog, a brown-out, a host opening the USB port): everything on the
  // chip is lost, what was not synced to the card too. The Nano keeps running through the
  // `bootUs` the Mega takes to start again, unless `powerLost` takes it down as well. The head
  // stays where it physically is, and the switches where they are; the Mega's count starts at 0.
  void reset(uint64_t bootUs, bool powerLost = false) {
    sd.powerCut();
    nano.dropFromMega();
    nano.megaUartStarts();
    if (powerLost) nano.powerCycle();
    int32_t where[3], switches[3];
    for (int a = 0; a < 3; a++) {
      where[a] = rig.head[a];
      switches[a] = rig.switchAt[a];
    }
    machine.~Machine();
    usbLink.~HostLink();
    espLink.~HostLink();
    io.~FakeIo();
    rig.~MotionRig();
    head.~PrintheadLink();
    store.~ConfigStore();
    config.~Config();
    for (uint64_t end = nowUs + bootUs; nowUs < end; nowUs += 100) nano.advance(nowUs);
    new (&config) Config();
    new (&store) ConfigStore(config, sd, eeprom);
    new (&head) PrintheadLink(nano);
    head.raiseSpeed(kRaiseNanoLink);
    new (&rig) MotionRig(config);
    for (int a = 0; a < 3; a++) {
      rig.switchAt[a] = switches[a];
      rig.head[a] = where[a];
    }
    new (&io) FakeIo(rig);
    movesFree = StepEngine::kBlocks;
    stats = {};
    new (&usbLink) HostLink(usb, movesFree, lineWindow(usbSlots));
    new (&espLink) HostLink(esp, movesFree, lineWindow(espSlots));
    new (&machine) Machine(MachineParts{{&usbLink, &espLink}, rig.motion, head, config, store, sd, io, eeprom, display, "UVExposure 0.1.0 (Mega)", movesFree, stats});
    usb = HostPipe();
    esp = HostPipe();
    usbN_ = espN_ = 0;  // the host starts numbering again, as after `start`
    firedAt.resize(nano.exposures.size());
    begin();
  }

  // Advances simulated time in 100 µs main-loop passes, the step interrupt in between.
  void run(uint64_t us) {
    for (uint64_t end = nowUs + us; nowUs < end; nowUs += 100) {
      nano.advance(nowUs);
      const bool atRest = rig.engine.idle();
      machine.poll(static_cast<uint32_t>(nowUs));
      // The first move after an exposure, a job's next stop: the board's CPU plans the stop and
      // converts, profiles and cuts its move before the first step, which this rig's instant passes do not.
      if (atRest && !rig.engine.idle() && nano.fired != loadedAfter_) {
        loadedAfter_ = nano.fired;
        rig.startDelayTicks = kStopLoadUs * 2;
      }
      while (firedAt.size() < nano.exposures.size()) {
        std::array<int32_t, 3> p;
        rig.motion.positionSteps(p.data());
        firedAt.push_back(p);
      }
      for (const uint64_t until = (nowUs + 100) * 2;;) {
        rig.isrUntil(gAt_ && gAt_ < until ? gAt_ : until);
        if (gAt_ && rig.now >= gAt_) {
          nano.advance(gAt_ / 2);
          nano.arrived("G\n", 2);
          gAt_ = 0;
        }
        if (rig.now >= until) break;
      }
      // The CR Touch: its pin, when out, closes on the bed. Armed with an alarm, its next deploy
      // jams it, and it reads triggered until the alarm release.
      if (nano.servoUs == nano::kServoAlarmReleaseUs) probeAlarm = probeJammed_ = false;
      else if (nano.servoUs == nano::kServoDeployUs && probeAlarm) probeJammed_ = true;
      if (probeJammed_) {
        nano.probe = true;
      } else if (bed) {
        int32_t um[3];
        rig.motion.positionUm(um);
        nano.probe = nano.servoUs == nano::kServoDeployUs && um[2] <= bed(um[0], um[1]);
      }
      usb.carry(usbLink, 100);
      esp.carry(espLink, 100);
      for (std::string& l : usb.take()) usbLines.push_back(l);
      for (std::string& l : esp.take()) espLines.push_back(l);
    }
  }

  // Sends one numbered line on a port and runs until the ok that names it; returns the lines of
  // its reply block (everything that port read meanwhile, the ok included).
  std::vector<std::string> cmd(const std::string& body, bool onEsp = false, uint64_t maxUs = 120000000) {
    std::vector<std::string>& lines = onEsp ? espLines : usbLines;
    size_t from = lines.size();
    uint32_t n = send(body, onEsp);
    std::string okPrefix = "ok N" + std::to_string(n) + " ";
    for (uint64_t t = 0; t < maxUs; t += 100) {
      run(100);
      for (size_t i = from; i < lines.size(); i++)
        if (lines[i].rfind(okPrefix, 0) == 0) return std::vector<std::string>(lines.begin() + static_cast<long>(from), lines.begin() + static_cast<long>(i) + 1);
    }
    return {"(no ok for " + body + ")"};
  }

  // Queues one numbered line for the Mega without running anything; returns its number.
  uint32_t send(const std::string& body, bool onEsp = false) {
    uint32_t& n = onEsp ? espN_ : usbN_;
    n++;
    char frame[128];
    uv::encodeFrame(n, body.c_str(), frame, sizeof frame);
    (onEsp ? esp : usb).toMega += std::string(frame) + "\n";
    return n;
  }

  // The reply block's lines other than reports and the ok.
  static std::vector<std::string> payload(const std::vector<std::string>& block) {
    std::vector<std::string> out;
    for (const std::string& l : block)
      if (l.rfind("ok", 0) != 0 && l.rfind("busy:", 0) != 0 && l.rfind("T:", 0) != 0) out.push_back(l);
    return out;
  }

 private:
  uint32_t usbN_ = 0, espN_ = 0;
  uint64_t gAt_ = 0;  // a scan pass's G on its way to the Nano: when it arrives (ticks)
  uint32_t loadedAfter_ = 0;  // nano.fired when the last stop after an exposure was loaded
  bool probeJammed_ = false;
};

}  // namespace mega
