// The one FlashGate of the ESP (flash_gate.h): loop() holds it across each of its LittleFS calls;
// the network callbacks ask flashBusy() before any of theirs.
#pragma once
#include <ESPAsyncWebServer.h>

#include "flash_gate.h"

namespace uv {
namespace esp {

extern FlashGate fileSystemGate;

// Network callbacks: true while loop() is inside a file operation, which on the ESP8266 is where
// they run when the flash yields. Never on the ESP32, whose LittleFS locks itself.
inline bool flashBusy() {
#if defined(ESP8266)
  return fileSystemGate.held();
#else
  return false;
#endif
}

// 503 flash_busy with Retry-After (protocol/esp.md "The flash").
void sendFlashBusy(AsyncWebServerRequest* r);

}  // namespace esp
}  // namespace uv
