// POST /print, DELETE /print and GET /status on ESPAsyncWebServer (protocol/esp.md). The body is
// spooled to LittleFS as it arrives, checked and converted a row at a time in loop(), and only
// then answered (202, or 400/413 with the field at fault) and uploaded through the bridge. The
// network task and loop() share nothing but the hand-over's rings (hand_over.h).
#pragma once
#include <ESPAsyncWebServer.h>

#include "bridge.h"

namespace uv {
namespace esp {

// service: drains the Mega's UART and the clients while a long body is read.
void beginPrintEndpoint(AsyncWebServer& server, Bridge& bridge, void (*service)());
// loop()'s side: the requests handed over, one step of a POST's check; call every loop pass.
void pollPrintEndpoint();
// The network task: loop()'s answers to their requests (network_wake.h).
void pumpPrintEndpoint();

}  // namespace esp
}  // namespace uv
