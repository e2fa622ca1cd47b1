// Host tests' printhead: the real Nano command brain (firmware/nano/src/printhead) behind the
// Mega's ByteStream, with LEDs that switch off in simulated time and a log of every exposure, so
// tests can count each cell's light. It can go silent, stick an LED on, or be reset. With `wired`, each
// byte takes its ten bit-times at the sender's speed (86.8 µs at 115200), as on the machine. Each side
// has its own speed (protocol/nano.md "Link speed"): a byte sent at a speed its receiver is not at
// arrives as noise, a 0x00 (what a receiver at 250000 or more reads of a 115200 byte's start bit).
// Its own time is 64-bit: a simulated printer runs for hours, past the 71.6 minutes in which a
// 32-bit µs count wraps. The Nano's logic sees millis() and micros() as the board's, which wrap.
#pragma once
#include <stdint.h>

#include <deque>
#include <new>
#include <string>
#include <vector>

#include "byte_stream.h"
#include "line_splitter.h"
#include "nano_codec.h"
#include "printhead.h"
#include "printhead_config.h"

namespace mega {

struct ScanLight {
  uint8_t led;
  uint64_t onUs, offUs;
};

struct Exposure {
  uint64_t startUs;
  uint8_t mask;
  uint32_t askedUs[4];
  uint32_t litUs[4];  // how long each LED actually shone (less if cut off by R or a fault)
};

class FakeNano : public ByteStream, private nano::PrintheadIo {
 public:
  FakeNano() : head_(*this, config_), splitter_(line_, uv::kNanoMaxLine) {
    head_.setBoot(boot_);
    setTemps(250);
  }

  // --- the Mega's side ---
  int16_t read() override {
    if (toMega_.empty() || toMega_.front().atNs > nowUs * 1000) return -1;
    char c = toMega_.front().baud == megaBaud_ ? toMega_.front().c : '\0';
    toMega_.pop_front();
    return static_cast<uint8_t>(c);
  }
  bool setBaud(uint32_t baud) override {
    if (wired && toNanoFreeNs_ > nowUs * 1000) return false;  // a byte still going out
    megaBaud_ = baud;
    return true;
  }
  uint32_t megaBaud() const { return megaBaud_; }
  uint32_t nanoBaud() { return nanoBaudAt(nowUs * 1000); }
  bool write(const char* data, uint8_t n) override {
    if (uartFull) return false;
    if (!wired) {
      if (megaBaud_ != nanoBaudAt(nowUs * 1000)) return noise(n), true;
      take(data, n);
      return true;
    }
    // The Mega's transmit ring holds kTxRing bytes not yet on the wire: a line that does not fit
    // waits, as on the board, so what is sent after it (a K awaiting its answer) is not held back.
    if (toNano_.size() + n > kTxRing) return false;
    onWire(toNano_, toNanoFreeNs_, data, n, megaBaud_);
    return true;
  }
  // The Mega's W goes out only on an idle transmitter: its time is when its first bit leaves.
  bool writeNow(char op, uint32_t& atUs) override {
    if (uartFull || (wired && toNanoFreeNs_ > nowUs * 1000)) return false;
    const char line[2] = {op, '\n'};
    atUs = static_cast<uint32_t>(nowUs);  // the Mega's micros(), which wraps
    if (wired) onWire(toNano_, toNanoFreeNs_, line, 2, megaBaud_);
    else if (megaBaud_ != nanoBaudAt(nowUs * 1000)) noise(2);
    else take(line, 2);
    return true;
  }

  // --- the test's side ---
  // Runs the Nano up to `toUs`: the bytes the wire delivers by then, each when its stop bit ends,
  // and the LEDs' switch-offs and a scan chain's events in between.
  void advance(uint64_t toUs) {
    while (!toNano_.empty() && toNano_.front().atNs <= toUs * 1000) {
      const WireByte b = toNano_.front();
      toNano_.pop_front();
      settle((b.atNs + 999) / 1000);
      if (b.baud != nanoBaudAt(b.atNs)) noise(1);
      else take(&b.c, 1);
      midLine_ = b.c != '\n';
    }
    settle(toUs);
  }
  // A line that has crossed the wire already and ends now (a scan pass's G, which the rig times from
  // its step).
  void arrived(const char* data, uint8_t n) {
    if (megaBaud_ != nanoBaudAt(nowUs * 1000)) return noise(n);
    take(data, n);
  }
  void setTemps(int16_t deciC) {
    int16_t each[uv::kSensorCount];
    for (int16_t& t : each) t = deciC;
    setTemps(each);
  }
  // Each sensor's own reading (the simulated printer's thermal model gives them).
  void setTemps(const int16_t deciC[uv::kSensorCount]) {
    uint16_t mv[uv::kSensorCount];
    for (uint8_t i = 0; i < uv::kSensorCount; i++) {
      temps_[i] = deciC[i];
      mv[i] = static_cast<uint16_t>(500 + deciC[i]);  // TMP36: 10 mV/°C, 500 mV at 0
    }
    head_.readings(mv);  // over a limit, the real logic switches every LED off (CUTOFF)
  }
  // This start's number, as the Nano's EEPROM counter holds it (a machine kept from an earlier run).
  void startCount(uint16_t boot) {
    boot_ = boot;
    head_.setBoot(boot);
  }
  uint16_t startCount() const { return boot_; }
  // How long LED `i` has shone since this fake was made, µs, whatever switched it: the dose the
  // simulated printer's thermal model heats the head by.
  uint64_t onUs(uint8_t i) const { return onTotal_[i] + ((lit_ >> i & 1) ? nowUs - onSince_[i] : 0); }
  uint8_t litMask() const override { return lit_; }
  uint8_t lit() const { return lit_; }
  // Power fails and returns: LEDs dark at once, the Nano's RAM gone, its start count one more.
  void powerCycle() {
    allOff();
    head_.~Printhead();
    new (&head_) nano::Printhead(*this, config_);
    head_.setBoot(++boot_);
    setTemps(temps_);
    nanoBaud_ = uv::kNanoBaud;  // it starts at 115200
    nanoNextAtNs_ = 0;
    toMega_.clear();
    toMegaFreeNs_ = 0;
    dropFromMega();  // what was on its way found the Nano off
  }
  // The Mega restarts: the lines in its transmit ring never leave, but for the end of the one already
  // going out (kept whole here, so the Nano's next line is not run together with a fragment).
  void dropFromMega() {
    auto end = toNano_.begin();
    if (midLine_)
      while (end != toNano_.end() && (end++)->c != '\n') {
      }
    toNano_.erase(end, toNano_.end());
    toNanoFreeNs_ = toNano_.empty() ? 0 : toNano_.back().atNs;
  }

  // The Mega's UART starts again, at 115200 (a Mega restart; the Nano may still be at a raised speed).
  void megaUartStarts() { megaBaud_ = uv::kNanoBaud; }

  // The Nano's clock runs this many parts per million fast: what its W answers say.
  int32_t clockPpm = 0;
  bool noClock = false;  // firmware from before W: it does not answer one
  bool noRaise = false;  // firmware from before L (or a wiring that fails raised): it never answers one
  bool silent = false;   // hears nothing, answers nothing
  bool stuck = false;    // LEDs ignore their off time (a failed timer), only R turns them off
  bool uartFull = false;
  bool wired = false;  // bytes take their time on the wire (else a line arrives as it is written)
  uint64_t nowUs = 0;
  std::vector<Exposure> exposures;
  std::vector<ScanLight> scanLight;
  std::vector<std::string> lines;  // every line the Mega sent
  // The logs above grow with every line and exposure, for the tests; the simulated printer, which
  // runs for hours, keeps none.
  bool logging = true;
  uint32_t fired = 0;  // exposures by F, logged or not
  uint16_t servoUs = 0;
  bool probe = false;

 private:
  struct WireByte {
    uint64_t atNs;  // when its stop bit ends at the far side
    char c;
    uint32_t baud;  // the speed it was sent at
  };
  // The Nano's speed at a moment: a change asked for after a reply takes effect as its last byte ends.
  uint32_t nanoBaudAt(uint64_t ns) {
    if (nanoNextAtNs_ && ns >= nanoNextAtNs_) {
      nanoBaud_ = nanoNextBaud_;
      nanoNextAtNs_ = 0;
    }
    return nanoBaud_;
  }
  // Bytes the Nano cannot read: each a 0x00, which its main loop takes as noise, and which spoils its line.
  void noise(uint8_t n) {
    for (uint8_t i = 0; i < n; i++) {
      if (!silent) head_.noise();
      take("\0", 1);
    }
  }
  void linkSpeed(uint32_t baud, bool afterReply) override {
    if (afterReply && wired && toMegaFreeNs_ > nowUs * 1000) {
      nanoNextBaud_ = baud;
      nanoNextAtNs_ = toMegaFreeNs_;
    } else {
      nanoBaud_ = baud;
      nanoNextAtNs_ = 0;
    }
  }
  static constexpr size_t kTxRing = 64;  // NanoUart::kRing (hw/nano_uart.h)
  // The real Nano lights an F about 180 µs after its newline arrives (its main loop parses the line
  // and sets the timer; simavr, stop_sim_test.cpp); the rest it answers or does within about 100.
  static constexpr uint64_t kFireTakenNs = 180000;
  // Queues bytes on one direction of the wire: each starts when the one before it has gone.
  void onWire(std::deque<WireByte>& wire, uint64_t& freeNs, const char* data, uint8_t n, uint32_t baud) {
    const uint64_t byteNs = 10ull * 1000000000 / baud;
    uint64_t t = freeNs > nowUs * 1000 ? freeNs : nowUs * 1000;
    for (uint8_t i = 0; i < n; i++) wire.push_back({t += byteNs, data[i], baud});
    freeNs = t;
    if (&wire == &toNano_ && n && data[0] == 'F' && data[n - 1] == '\n') wire.back().atNs += kFireTakenNs;
  }
  // The LEDs' switch-offs and a chain's events up to `atUs`.
  void settle(uint64_t atUs) {
    nowUs = atUs;
    if (!silent) head_.poll(millis());  // the chain the Mega stopped talking to is cut after 50 ms
    if (program_) return runProgram();  // a scan chain's LEDs follow its events, not an F's offs
    for (uint8_t i = 0; i < 4; i++) {
      if ((lit_ & (1 << i)) && !stuck && nowUs >= offAt_[i]) off(i, offAt_[i]);
    }
  }
  void take(const char* data, uint8_t n) {
    for (uint8_t i = 0; i < n; i++) {
      if (!splitter_.push(data[i])) continue;
      std::string l(splitter_.text(), splitter_.length());
      if (logging) lines.push_back(l);
      if (silent || (noClock && l == "W") || (noRaise && l.rfind("L:", 0) == 0)) continue;
      head_.line(splitter_.text(), splitter_.length(), splitter_.overflow(), millis());
    }
  }
  // The board's millis() and micros(): 32 bits, so they wrap (micros() every 71.6 minutes).
  uint32_t millis() const { return static_cast<uint32_t>(nowUs / 1000); }
  uint32_t clockLineUs() override {
    return static_cast<uint32_t>(nowUs + static_cast<int64_t>(nowUs) * clockPpm / 1000000);
  }
  void fire(const nano::FirePlan& p) override {
    Exposure e{nowUs, p.onMask, {}, {}};
    for (uint8_t k = 0; k < p.count; k++) {
      for (uint8_t i = 0; i < 4; i++) {
        if (!(p.events[k].mask & (1 << i))) continue;
        e.askedUs[i] = p.events[k].tick / nano::kTicksPerUs;
        offAt_[i] = nowUs + e.askedUs[i];
      }
    }
    for (uint8_t i = 0; i < 4; i++)
      if ((p.onMask >> i & 1) && !(lit_ >> i & 1)) onSince_[i] = nowUs;
    lit_ = p.onMask;
    fired++;
    if (logging) exposures.push_back(e);
    startAt_ = nowUs;
  }
  void off(uint8_t i, uint64_t atUs) {
    if (lit_ >> i & 1) onTotal_[i] += atUs - onSince_[i];
    lit_ = static_cast<uint8_t>(lit_ & ~(1 << i));
    if (logging && !exposures.empty()) exposures.back().litUs[i] = static_cast<uint32_t>(atUs - startAt_);
  }
  // A cut, as the board's timer notes it for the dose records: after the chain's last event, or the F's on-edge.
  bool takeCut(int32_t& ticks) override {
    ticks = cutTicks_;
    bool was = cut_;
    cut_ = false;
    return was;
  }
  void allOff() override {
    if (program_ || lit_) {
      cut_ = true;
      cutTicks_ = static_cast<int32_t>((static_cast<int64_t>(nowUs) - static_cast<int64_t>(program_ ? madeAt_ : startAt_)) * nano::kTicksPerUs);
    }
    if (program_) {
      setLit(0, nowUs);  // a chain cut: its light ends now
      program_ = nullptr;
      return;
    }
    for (uint8_t i = 0; i < 4; i++)
      if (lit_ & (1 << i)) off(i, nowUs);
  }
  // A scan chain runs in simulated time, on this Nano's clock (clockPpm): advance() takes its
  // events as they fall due.
  bool startProgram(nano::ScanStore& store) override {
    program_ = &store;
    chainAt_ = nowUs;
    chainUs_ = uv::kProgramStartLeadUs;
    madeAt_ = chainAt_ + uv::kProgramStartLeadUs;  // time 0
    return takeEvent();
  }
  bool takeEvent() {
    uint32_t d;
    uint8_t m;
    if (program_->next(d, m) != nano::ScanStore::Step::Event) {
      program_ = nullptr;
      setLit(0, eventAt_);
      return false;
    }
    chainUs_ += d;  // the Nano's µs since the G, and the same moment on the test's clock:
    eventAt_ = chainAt_ + static_cast<uint64_t>(static_cast<int64_t>(chainUs_) * 1000000 / (1000000 + clockPpm));
    nextMask_ = m;
    return true;
  }
  void runProgram() {
    while (program_ && !stuck && nowUs >= eventAt_) {
      setLit(nextMask_, eventAt_);
      madeAt_ = eventAt_;
      takeEvent();
    }
  }
  // Scan light is logged per LED as [on, off) µs intervals.
  void setLit(uint8_t m, uint64_t atUs) {
    for (uint8_t i = 0; i < 4; i++) {
      bool was = lit_ >> i & 1, is = m >> i & 1;
      if (!was && is) onSince_[i] = atUs;
      if (was && !is) onTotal_[i] += atUs - onSince_[i];
      if (!logging) continue;
      if (!was && is) scanLight.push_back({i, atUs, atUs});
      if (was && !is)
        for (auto it = scanLight.rbegin(); it != scanLight.rend(); ++it)
          if (it->led == i) {
            it->offUs = atUs;
            break;
          }
    }
    lit_ = m;
  }
  void servoPulse(uint16_t us) override { servoUs = us; }
  bool probeTriggered() override { return probe; }
  void reply(const char* text, uint8_t len) override {
    if (silent) return;
    const uint32_t baud = nanoBaudAt(nowUs * 1000);
    if (wired) return onWire(toMega_, toMegaFreeNs_, text, len, baud);
    for (uint8_t i = 0; i < len; i++) toMega_.push_back({0, text[i], baud});
  }

  nano::PrintheadConfig config_ = nano::kPrintheadConfig;  // the real Nano's build-time settings and version
  nano::Printhead head_;
  char line_[uv::kNanoMaxLine + 2];
  bool cut_ = false;           // takeCut(): a cut since the last call, and when
  int32_t cutTicks_ = 0;
  uint64_t madeAt_ = 0;        // when the chain's last event (or its time 0) was made
  uv::LineSplitter splitter_;
  std::deque<WireByte> toNano_, toMega_;
  uint64_t toNanoFreeNs_ = 0, toMegaFreeNs_ = 0;  // when each direction's last queued byte ends
  bool midLine_ = false;  // the Nano has part of a line from the wire
  uint32_t megaBaud_ = uv::kNanoBaud, nanoBaud_ = uv::kNanoBaud, nanoNextBaud_ = uv::kNanoBaud;
  uint64_t nanoNextAtNs_ = 0;  // when nanoNextBaud_ takes over, or 0
  uint8_t lit_ = 0;
  uint64_t offAt_[4] = {};
  uint64_t startAt_ = 0;
  nano::ScanStore* program_ = nullptr;
  uint64_t eventAt_ = 0;
  uint64_t chainAt_ = 0;  // when the chain's G came
  uint32_t chainUs_ = 0;  // the chain's time so far, in the Nano's µs
  uint8_t nextMask_ = 0;
  uint16_t boot_ = 7;
  int16_t temps_[uv::kSensorCount] = {250, 250, 250, 250, 250, 250};
  uint64_t onTotal_[4] = {};   // each LED's on-time up to its last switch-off, µs
  uint64_t onSince_[4] = {};   // when each lit LED came on
};

}  // namespace mega
