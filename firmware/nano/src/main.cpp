// Printhead Nano entry point: wires the UART, the command brain and the board drivers together.
#include <Arduino.h>
#include <avr/eeprom.h>
#include <avr/wdt.h>

#include "adc_sampler.h"
#include "config.h"
#include "led_timer.h"
#include "line_splitter.h"
#include "neopixel.h"
#include "pins.h"
#include "printhead.h"
#include "printhead_config.h"
#include "probe_input.h"
#include "servo_pulse.h"
#include "uart.h"

namespace {

// Survives the C runtime's clearing of .bss, so setup() can tell a watchdog reset.
uint8_t resetCause __attribute__((section(".noinit")));

// Runs before the C runtime: LEDs off first, then the watchdog is stopped so a watchdog reset
// cannot loop while the runtime starts (the Optiboot bootloader passes MCUSR through).
void earliest() __attribute__((naked, used, section(".init3")));
void earliest() {
  LED_PORT &= static_cast<uint8_t>(~LED_PORT_MASK);
  LED_DDR |= LED_PORT_MASK;
  resetCause = MCUSR;
  MCUSR = 0;
  wdt_disable();
}

// Switch-offs and servo edges are kept clear of the pixel's interrupts-off write by this much: the
// write (61 µs with interrupts off, measured in simavr) and the compare interrupt's 16 µs early
// wake, with room to spare.
constexpr uint16_t kPixelQuietTicks = 1500;  // 93.75 µs

// A scan program's time 0, in Timer1 ticks after the receive interrupt read TCNT1 for the `\n` of
// its `G`: the protocol's lead, less the interrupt's own entry before that read (measured on the
// pins in simavr, firmware/nano/test/sim/nano_sim_test.cpp).
constexpr uint16_t kStampLatencyTicks = 46;
constexpr uint16_t kStartLeadTicks = static_cast<uint16_t>(uv::kProgramStartLeadUs * nano::kTicksPerUs - kStampLatencyTicks);

class Board : public nano::PrintheadIo {
 public:
  void fire(const nano::FirePlan& plan) override { nano::led_timer::fire(plan); }
  void allOff() override { nano::led_timer::allOff(); }
  bool cutByReset() override { return nano::uart::takeResetCut(); }
  bool takeCut(int32_t& ticks) override { return nano::led_timer::takeCut(ticks); }
  bool startProgram(nano::ScanStore& store) override {
    uint16_t tick;
    uint32_t us;
    uint8_t sreg = SREG;
    cli();  // no interrupt between the check and the timer's start
    bool inTime = nano::uart::takeStart(tick, us) && micros() - us <= uv::kProgramLateUs;
    if (inTime) nano::led_timer::run(store, static_cast<uint16_t>(tick + kStartLeadTicks));
    SREG = sreg;
    return inTime;
  }
  uint32_t clockLineUs() override { return nano::uart::clockLineUs(); }
  uint8_t litMask() const override { return nano::led_timer::lit(); }
  void servoPulse(uint16_t us) override { nano::servo_pulse::set(us); }
  bool probeTriggered() override { return nano::probe_input::takeTriggered(); }
  void reply(const char* text, uint8_t len) override {
    // Never block: a reply that finds no room is dropped, and the Mega's time-out asks again.
    nano::uart::write(text, len);
  }
  void linkSpeed(uint32_t baud, bool afterReply) override { nano::uart::setBaud(baud, afterReply); }
};

Board board;
nano::Printhead head(board, nano::kPrintheadConfig);
char lineBuf[uv::kNanoMaxLine + 1];
uv::LineSplitter splitter(lineBuf, uv::kNanoMaxLine);
uv::Colour shown = uv::Colour::Red;  // differs from the first wanted colour, so it is written once
bool pixelWritten = false;
uint16_t readingsMs = 0;  // when the sweep was last looked for (low bits of millis())

void updatePixel(uint32_t nowMs) {
  uv::Colour want = head.colour(nowMs);
  if (pixelWritten && want == shown) return;
  // Not while a line is arriving: the write holds interrupts off for tens of µs, and a poll's reply
  // must not wait behind it. Between lines it ends before the next line's last byte can arrive.
  if (splitter.pending() || nano::uart::available()) return;
  if (!nano::led_timer::quietFor(kPixelQuietTicks) || !nano::servo_pulse::quietFor(kPixelQuietTicks)) return;
  uv::Rgb c = uv::colourRgb(want);
  nano::neopixel::show(c.r, c.g, c.b);
  shown = want;
  pixelWritten = true;
}

}  // namespace

void setup() {
  nano::led_timer::allOff();
  nano::led_timer::begin();
  nano::neopixel::begin();
  nano::probe_input::begin();
  nano::adc_sampler::begin();
  if (resetCause & _BV(WDRF)) head.watchdogReset();
  // Every start gets the next number (EEPROM word 0, wrapping): the Mega's C poll tells by it that
  // the printhead restarted, so an exposure cut by a power loss is never taken for a whole one.
  uint16_t* bootCount = reinterpret_cast<uint16_t*>(0);
  uint16_t boot = static_cast<uint16_t>(eeprom_read_word(bootCount) + 1);
  eeprom_update_word(bootCount, boot);  // about 7 ms, before the watchdog and the UART start
  head.setBoot(boot);
  nano::uart::begin(uv::kNanoBaud);
  wdt_enable(WDTO_250MS);
}

void loop() {
  wdt_reset();
  uint32_t now = millis();
  int budget = 64;  // bytes per pass, so the pixel and the watchdog are served under a flood
  int16_t c;
  while (budget-- > 0 && (c = nano::uart::read()) >= 0) {
    // A byte no line holds (the receive interrupt marks one with a framing or overrun error as 0x01):
    // above 115200 the Mega may be at another speed, and the link falls back (the interrupt already
    // took 115200 and switched the LEDs off; the brain drops the programs).
    if ((c < 0x20 && c != '\n' && c != '\r') || c > 0x7E) head.noise();
    if (splitter.push(static_cast<char>(c))) {
      head.line(splitter.text(), splitter.length(), splitter.overflow(), now);
    }
  }
  // A fresh sweep is taken between lines, when none has begun to arrive: its conversion (about
  // 120 µs) would otherwise hold up the reply to a poll whose newline came while it ran (the 200 µs
  // budget, nano_sim_test), where now the next newline is at least two byte-times away. Lines that
  // leave no such gap (long ones, back to back) put it off 8 ms at most: over-temperature still cuts
  // within two sweeps of 10.6 ms and that.
  if ((!splitter.pending() && !nano::uart::available()) || static_cast<uint16_t>(static_cast<uint16_t>(now) - readingsMs) >= 8) {
    uint16_t mv[uv::kSensorCount];
    if (nano::adc_sampler::take(mv)) head.readings(mv);
    readingsMs = static_cast<uint16_t>(now);
  }
  head.poll(now);
  updatePixel(now);
}
