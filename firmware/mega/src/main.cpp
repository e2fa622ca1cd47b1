// Motion controller Mega: wires the command core to the board. Everything here is static, so the
// whole of RAM use shows in the image's .data and .bss; loop() never waits.
#include <Arduino.h>

#include "config_store.h"
#include "host_link.h"
#include "hw/avr_eeprom.h"
#include "hw/board.h"
#include "hw/host_uart.h"
#include "hw/nano_uart.h"
#include "hw/oled.h"
#include "hw/sd_storage.h"
#include "hw/stepper_timer.h"
#include "machine.h"
#include "pins.h"
#include "printhead_link.h"
#include "progmem.h"

namespace {

using namespace mega;

const char kFirmwareName[] UV_FLASH = "UVExposure 0.1.0 (Mega)";

Config config;
SdStorage sd;
AvrEeprom eeprom;
ConfigStore store(config, sd, eeprom);
Motion motion(stepEngine, config);
NanoUart nanoSerial;
PrintheadLink head(nanoSerial);
HostUart usbUart(0);
HostUart espUart(2);  // or 3: esp.port, read at start-up
uint8_t movesFree = StepEngine::kBlocks;
LoopStats stats = {};
LineSlot usbSlots[kUsbWindow];
LineSlot espSlots[kEspWindow];
HostLink usb(usbUart, movesFree, lineWindow(usbSlots));
HostLink esp(espUart, movesFree, lineWindow(espSlots));
Board board;
Oled oled;
Machine machine(MachineParts{{&usb, &esp}, motion, head, config, store, sd, board, eeprom, oled, kFirmwareName, movesFree, stats});
uint32_t lastPass = 0;

}  // namespace

void setup() {
  board.begin();
  stepperBegin();
  nanoSerial.begin(uv::kNanoBaud);
  head.raiseSpeed(mega::kRaiseNanoLink);  // to kNanoFastBaud once the Nano is known and the link idle (protocol/nano.md "Link speed")
  sd.begin(PIN_SD_CS);
  store.load();  // for esp.port and invert.*, before anything talks
  usbUart.begin(usb, 115200);
  espUart = HostUart(config.whole(Key::EspPort) == 3 ? 3 : 2);
  espUart.begin(esp, 115200);
  oled.begin();
  machine.begin(micros());
}

void loop() {
  uint32_t now = micros();
  uint32_t pass = now - lastPass;  // the whole pass, the time interrupts took included
  if (lastPass && pass > stats.loopMaxUs) stats.loopMaxUs = pass;
  lastPass = now;
  machine.poll(now);
  stepperKick();
  stats.stepIsrMaxUs = static_cast<uint16_t>(stepperWorstTicks() / 2);
}
