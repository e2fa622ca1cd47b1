// Printhead Nano entry point: reads Mega commands from the UART and answers them (protocol/nano.md).
#include <Arduino.h>
#include <avr/io.h>

#include "line_splitter.h"
#include "nano_codec.h"
#include "pins.h"

namespace {

char lineBuf[uv::kNanoMaxLine + 1];
uv::LineSplitter splitter(lineBuf, uv::kNanoMaxLine);
uint32_t offAt[uv::kLedCount];  // micros() deadline per lit LED
uint8_t litMask = 0;
uint8_t latched = 0;            // latched E bits

// LEDs off before anything else runs, even before the C runtime initialises memory.
void ledsOffEarly() __attribute__((naked, used, section(".init3")));
void ledsOffEarly() {
  LED_PORT &= static_cast<uint8_t>(~LED_PORT_MASK);
  LED_DDR |= LED_PORT_MASK;
}

void writeLeds(uint8_t mask) {
  uint8_t sreg = SREG;
  cli();
  LED_PORT = static_cast<uint8_t>((LED_PORT & ~LED_PORT_MASK) | ((mask << LED_SHIFT) & LED_PORT_MASK));
  SREG = sreg;
  litMask = mask;
}

int16_t readDeciC(uint8_t sensor) {
  int32_t mv = static_cast<int32_t>(analogRead(PIN_TEMP_FIRST + sensor)) * 5000 / 1024;
  return static_cast<int16_t>(mv - 500);  // TMP36: 10 mV/°C, 500 mV at 0 °C; tenths = mV - 500
}

void reply(const uv::NanoReply& r) {
  char out[64];
  size_t n = uv::formatNanoReply(r, out, sizeof out);
  Serial.write(out, n);
}

void fire(const uv::NanoCommand& c) {
  if (litMask) {
    latched |= uv::fault::kBusy;
    return;
  }
  uint32_t now = micros();
  uint8_t mask = 0;
  for (uint8_t i = 0; i < uv::kLedCount; i++) {
    if ((c.mask >> i & 1) && c.durations[i] > 0) {
      mask |= static_cast<uint8_t>(1 << i);
      offAt[i] = now + c.durations[i];
    }
  }
  writeLeds(mask);
}

void handle(const uv::NanoCommand& c) {
  uv::NanoReply r{};
  r.op = c.op;
  switch (c.op) {
    case 'S': r.mask = litMask; reply(r); break;
    case 'F': fire(c); break;
    case 'R': writeLeds(0); break;
    case 'P': r.triggered = digitalRead(PIN_PROBE_SIGNAL) == HIGH; reply(r); break;
    case 'T':
      for (uint8_t i = 0; i < uv::kSensorCount; i++) r.deciC[i] = readDeciC(i);
      reply(r);
      break;
    case 'E': r.flags = latched; latched = 0; reply(r); break;
    case 'V': r.protocol = 1; strcpy(r.firmware, "0.1.0"); reply(r); break;
    default: break;  // D, U, X: the servo driver comes with the printhead issue
  }
}

}  // namespace

void setup() {
  writeLeds(0);
  pinMode(PIN_PROBE_SIGNAL, INPUT_PULLUP);
  Serial.begin(115200);
}

void loop() {
  uint32_t now = micros();
  for (uint8_t i = 0; i < uv::kLedCount; i++) {
    if ((litMask >> i & 1) && static_cast<int32_t>(now - offAt[i]) >= 0) writeLeds(litMask & ~(1 << i));
  }
  while (Serial.available()) {
    if (!splitter.push(static_cast<char>(Serial.read()))) continue;
    if (splitter.length() == 0 && !splitter.overflow()) continue;
    uv::NanoCommand c{};
    if (uv::nanoLineUsable(splitter.text(), splitter.length(), splitter.overflow()) &&
        uv::parseNanoCommand(splitter.text(), splitter.length(), c)) {
      handle(c);
    } else {
      latched |= uv::fault::kMalformed;
    }
  }
}
