// Motion controller Mega entry point: host ports (USB and ESP), the printhead link and the command set.
#include <Arduino.h>

#include "dialect_command.h"
#include "dialect_reply.h"
#include "error_codes.h"
#include "host_port.h"
#include "printhead_link.h"
#include "hw/serial_stream.h"
#include "pins.h"

namespace {

constexpr int16_t kLimitDeciC = 600;

mega::SerialStream nanoSerial(NANO_SERIAL);
mega::PrintheadLink nano(nanoSerial);
HostPort usb(Serial);
HostPort esp(ESP_SERIAL_DEFAULT);
uint32_t tempReportMs = 0;  // 0 = auto-report off
uint32_t lastTempReport = 0;

void temps(HostPort& port) {
  uv::Reply r{};
  r.kind = uv::ReplyKind::Temps;
  for (uint8_t i = 0; i < uv::kSensorCount; i++) {
    r.deciC[i] = nano.deciC()[i];
    r.limitDeciC[i] = kLimitDeciC;
  }
  char buf[160];
  uv::formatReply(r, buf, sizeof buf);
  port.line(buf);
}

class Commands : public Executor {
 public:
  void execute(const uv::Frame& frame, HostPort& port) override {
    uv::Command c;
    uint8_t err = uv::parseCommand(frame.body, frame.bodyLen, c);
    if (err) return port.error(err);
    if (c.is('M', 115)) {
      port.line("FIRMWARE_NAME:UVExposure 0.1.0 (Mega) PROTOCOL_VERSION:1 MACHINE_TYPE:UV-LED exposure printer LEDS:4 SENSORS:6");
      port.line("Cap:RX_WINDOW:8");
      port.line("Cap:AUTOREPORT_TEMP:1");
      return port.ok();
    }
    if (c.is('M', 105)) {
      if (!nano.online()) return port.error(uv::kNanoTimeout);
      temps(port);
      return port.ok();
    }
    if (c.is('M', 155)) {
      if (!c.hasValue('S') || c.value('S') < 0 || c.value('S') > 60000) return port.error(uv::kBadParameter);
      tempReportMs = static_cast<uint32_t>(c.value('S'));
      return port.ok();
    }
    port.error(uv::kUnknownCommand);
  }
} commands;

}  // namespace

void setup() {
  Serial.begin(115200);
  NANO_SERIAL.begin(115200);
  ESP_SERIAL_DEFAULT.begin(115200);
  nano.begin(micros());
  usb.line("start");
  esp.line("start");
}

void loop() {
  uint32_t now = millis();
  nano.poll(micros());
  usb.poll(commands);
  esp.poll(commands);
  if (tempReportMs && now - lastTempReport >= tempReportMs && nano.tempsKnown()) {
    lastTempReport = now;
    temps(usb);
    temps(esp);
  }
}
