// Network hub entry point: a WPA2 access point that serves the app from LittleFS (protocol/esp.md).
#include <Arduino.h>
#include <LittleFS.h>

#if defined(ESP8266)
#include <ESP8266WebServer.h>
#include <ESP8266WiFi.h>
using WebServerType = ESP8266WebServer;
static uint32_t chipId() { return ESP.getChipId(); }
#else
#include <WebServer.h>
#include <WiFi.h>
using WebServerType = WebServer;
static uint32_t chipId() { return static_cast<uint32_t>(ESP.getEfuseMac() >> 24); }
#endif

#include "access_point.h"

namespace {

WebServerType server(80);
char ssid[24];
char password[16];

const char* contentType(const String& path) {
  if (path.endsWith(".html")) return "text/html";
  if (path.endsWith(".js")) return "application/javascript";
  if (path.endsWith(".css")) return "text/css";
  if (path.endsWith(".svg")) return "image/svg+xml";
  if (path.endsWith(".webmanifest")) return "application/manifest+json";
  if (path.endsWith(".png")) return "image/png";
  return "application/octet-stream";
}

// Serves `<path>.gz` from LittleFS; the app build writes only gzipped files (see README).
void serveApp() {
  String path = server.uri();
  if (path.endsWith("/")) path += "index.html";
  File f = LittleFS.open(path + ".gz", "r");
  if (!f) {
    server.send(404, "application/json", "{\"error\":{\"code\":\"not_found\",\"message\":\"no such path\"}}");
    return;
  }
  server.sendHeader("Cache-Control", path.endsWith(".html") ? "no-cache" : "max-age=31536000, immutable");
  server.streamFile(f, contentType(path));  // the core adds Content-Encoding: gzip for a .gz file
  f.close();
}

}  // namespace

void setup() {
  Serial.begin(115200);
  uv::esp::accessPointCredentials(chipId(), ssid, sizeof ssid, password, sizeof password);
  WiFi.mode(WIFI_AP);
  WiFi.softAP(ssid, password);  // WPA2-PSK: the password is 12 characters, never empty
  Serial.printf("echo:Wi-Fi %s password %s at %s\n", ssid, password, WiFi.softAPIP().toString().c_str());
  LittleFS.begin();
  server.onNotFound(serveApp);
  server.begin();
}

void loop() { server.handleClient(); }
