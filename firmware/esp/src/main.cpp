// The network hub (protocol/esp.md): a WPA2 access point, the app from LittleFS, POST /print,
// GET /status and the /ws live channel, all in front of the Mega on a UART. The logic is the
// plain C++ in this folder (host-tested); arduino/ holds the glue to the ESP's libraries.
#include <Arduino.h>
#include <ESPAsyncWebServer.h>
#include <LittleFS.h>

#include "arduino/app_files.h"
#include "arduino/hub_server.h"
#include "arduino/live_socket.h"
#include "arduino/network.h"
#include "arduino/network_wake.h"
#include "arduino/print_endpoint.h"
#include "bridge.h"

namespace {

#if defined(ESP8266)
// Mega+WiFi boards wire the ESP8266's only full UART to the Mega; the log goes out on UART1's
// TX-only pin (GPIO2).
HardwareSerial& mega = Serial;
HardwareSerial& logPort = Serial1;
void beginMegaUart() {
  mega.setRxBufferSize(2048);
  mega.begin(115200);
}
#else
HardwareSerial& mega = Serial2;  // GPIO16 RX, GPIO17 TX
HardwareSerial& logPort = Serial;
void beginMegaUart() {
  mega.setRxBufferSize(2048);
  mega.setTxBufferSize(512);
  mega.begin(115200, SERIAL_8N1, 16, 17);
}
#endif

// The UART to the Mega: a line goes whole or waits for the next pass, never blocking.
struct MegaUart : uv::esp::MegaWire {
  bool write(const char* data, uint16_t n) override {
    if (mega.availableForWrite() < n) return false;
    mega.write(reinterpret_cast<const uint8_t*>(data), n);
    return true;
  }
} wire;

uv::esp::HubServer server(80);  // ESPAsyncWebServer with a limit on the request's headers
AsyncWebSocket ws("/ws");
uv::esp::LiveSocket socketClients(ws);
uv::esp::LiveChannel live(socketClients);
uv::esp::Bridge bridge(wire, live);
uv::esp::WifiSettings wifi;

// What loop() published goes to the network task: on the ESP8266 it is sent here (the network
// callbacks never run beside loop()); on the ESP32 the network task is woken to send it.
void handToNetwork() {
#if defined(ESP8266)
  uv::esp::pumpNetwork();
#else
  // News, or a client whose queue was full at the last turn: its next message goes once the
  // library has sent the last (nothing tells us when; every 10 ms is soon enough).
  static uint32_t written = 0, backlogMs = 0;
  bool news = live.written() != written;
  bool backlog = live.backlogged() && millis() - backlogMs >= 10;
  if (!news && !backlog) return;
  written = live.written();
  if (backlog) backlogMs = millis();
  uv::esp::wakeNetwork();
#endif
}

// Everything that must not wait: the Mega's bytes, the clients' messages, the live channel. It
// also runs from inside the intake's and the upload's reads of a long body (FileBody's refill);
// reached again from inside bridge.poll() (the upload reading its body), it returns at once, so
// the bridge is never re-entered.
void service() {
  static bool running = false;
  if (running) return;
  running = true;
  while (mega.available()) bridge.received(static_cast<char>(mega.read()), millis());
  socketClients.drain();
  bridge.poll(millis());
  handToNetwork();
  running = false;
  yield();  // the ESP8266 runs its network callbacks here, with the bridge between operations
}

}  // namespace

void setup() {
  logPort.begin(115200);
  beginMegaUart();
  if (!LittleFS.begin()) {
    logPort.println("echo:LittleFS would not mount; formatting it");
    LittleFS.format();
    LittleFS.begin();
  }
  uv::esp::beginNetwork(server, logPort, wifi);
  socketClients.begin(bridge, live);
  uv::esp::onNetworkPump(uv::esp::pumpPrintEndpoint, [] { socketClients.pump(); });
  server.addHandler(&ws);
  uv::esp::beginPrintEndpoint(server, bridge, service);
  uv::esp::beginAppFiles(server);
  server.begin();
  char panel[17];
  uv::esp::panelLine(wifi, panel);
  bridge.begin(millis(), panel);
}

void loop() {
  // The bridge and the print intake are loop()'s alone; the network task's requests reach them
  // only as messages (hand_over.h, arduino/print_endpoint.cpp), so neither task waits for the other.
  service();
  uv::esp::pollPrintEndpoint();
  uv::esp::pollNetwork();
  handToNetwork();
  // No ws.cleanupClients() here: it closes clients, which belongs to the network task; /ws lets in
  // only the board's number of clients (live_socket.cpp).
}
