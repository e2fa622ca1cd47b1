// Wi-Fi access point, optional station, captive-portal DNS, mDNS and /wifi.
#include "network.h"

#include <ArduinoJson.h>
#include <DNSServer.h>
#include <LittleFS.h>

#if defined(ESP8266)
#include <ESP8266WiFi.h>
#include <ESP8266mDNS.h>
static uint32_t chipId() { return ESP.getChipId(); }
// The hardware generator, read with the radio on (beginNetwork): with Wi-Fi off, as core 3.x
// starts, it gives pseudo-random numbers (the core's note in EspClass::random).
static uint32_t hardwareRandom() { return ESP.random(); }
#else
#include <ESPmDNS.h>
#include <WiFi.h>
static uint32_t chipId() { return static_cast<uint32_t>(ESP.getEfuseMac() >> 24); }
static uint32_t hardwareRandom() { return esp_random(); }  // true random only with the radio on
#endif

#include "flash_guard.h"
#include "http_rules.h"
#include "json_view.h"

namespace uv {
namespace esp {

namespace {

const char kSettingsFile[] = "/wifi.json";
constexpr uint32_t kJoinMs = 20000;

DNSServer dns;
WifiSettings* settings = nullptr;
char apIp[16] = "192.168.4.1";
bool joining = false;
uint32_t joinStartMs = 0;

const char kDamagedFile[] = "/wifi.bad";
Print* logOut = nullptr;

// The file is written whole or not at all: a text that did not fit is never stored.
// Called in setup() and then only from POST /wifi on the network task: never at once.
bool save(const WifiSettings& s) {
  static char file[kWifiFileBytes];  // off the small stack of the ESP8266's network callbacks
  JsonWriter w(file, sizeof file);
  writeWifi(w, s, true);
  if (!w.ok()) return false;
  fs::File f = LittleFS.open(kSettingsFile, "w");
  if (!f) return false;
  bool ok = f.write(reinterpret_cast<const uint8_t*>(w.text()), w.length()) == w.length();
  f.close();
  return ok;
}

// What the user expects of a file that is not wholly valid: to still get in with the password
// they set. Every field that is still good is kept (loadWifi); the file itself is kept aside as
// /wifi.bad, never silently replaced, and the log says which field was dropped. Only an AP
// password that cannot be read is drawn afresh, and it is shown on the log and the Mega's OLED.
void load(WifiSettings& s) {
  defaultWifi(chipId(), hardwareRandom, s);
  if (!LittleFS.exists(kSettingsFile)) {
    save(s);  // first start: the fresh random password is kept from now on
    return;
  }
  fs::File f = LittleFS.open(kSettingsFile, "r");
  JsonDocument doc;
  RequestError e{0, "bad_json", "", "not JSON, or cut short"};
  DeserializationError parsed = f ? deserializeJson(doc, f) : DeserializationError::InvalidInput;
  if (f) f.close();
  if (!parsed && loadWifi(JsonView{doc.as<JsonVariantConst>()}, s, e)) return;
  LittleFS.remove(kDamagedFile);
  LittleFS.rename(kSettingsFile, kDamagedFile);
  if (logOut) logOut->printf("echo:%s is damaged (%s %s: %s); kept as %s, its good fields loaded\n", kSettingsFile, e.code, e.path, e.message, kDamagedFile);
  save(s);
}

void startRadio(const WifiSettings& s) {
  WiFi.mode(s.staSsid[0] ? WIFI_AP_STA : WIFI_AP);
  WiFi.softAP(s.apSsid, s.apPassword);  // WPA2-PSK: the password is never empty (applyWifi)
  snprintf(apIp, sizeof apIp, "%s", WiFi.softAPIP().toString().c_str());
  dns.setErrorReplyCode(DNSReplyCode::NoError);
  dns.start(53, "*", WiFi.softAPIP());  // every name leads to the app: the captive portal
  if (s.staSsid[0]) {
    WiFi.begin(s.staSsid, s.staPassword[0] ? s.staPassword : nullptr);
    joining = true;
    joinStartMs = millis();
  }
}

// Answers are written into one buffer owned by the network task (handlers never run at once);
// kept off its stack, which is small on the ESP8266. It holds the whole settings file, so what
// GET /wifi shows (a subset) always fits, and any RequestError (kErrorJsonBytes).
char answer[kErrorJsonBytes > kWifiFileBytes ? kErrorJsonBytes : kWifiFileBytes];

void onGetWifi(AsyncWebServerRequest* r) {
  JsonWriter w(answer, sizeof answer);
  writeWifi(w, *settings, false);
  r->send(200, "application/json", w.text());
}

// The body is gathered (it is under 1 KB) and judged once whole, in onPostWifi.
struct Gathered {
  HttpError refused;  // a foreign origin or a body that is not JSON: nothing of it is kept
  size_t len;
  bool tooLarge;
  char data[1024];
};

// A POST /wifi from a foreign page, or with a body that is not JSON, is refused on its headers.
HttpError wifiHeaderError(AsyncWebServerRequest* r) {
  HttpError e = foreignRequest(r);
  return e.status ? e : jsonBodyError(r->contentType().c_str());
}

void onWifiBody(AsyncWebServerRequest* r, uint8_t* data, size_t len, size_t index, size_t total) {
  if (index == 0) {
    r->_tempObject = calloc(1, sizeof(Gathered));  // freed with the request by the library
    Gathered* g = static_cast<Gathered*>(r->_tempObject);
    if (g) {
      g->tooLarge = total > sizeof(Gathered::data);
      g->refused = wifiHeaderError(r);
    }
  }
  Gathered* g = static_cast<Gathered*>(r->_tempObject);
  if (g && g->refused.status) return;
  if (!g || g->tooLarge || g->len + len > sizeof g->data) {
    if (g) g->tooLarge = true;
    return;
  }
  memcpy(g->data + g->len, data, len);
  g->len += len;
}

void onPostWifi(AsyncWebServerRequest* r) {
  JsonWriter w(answer, sizeof answer);
  const Gathered* g = static_cast<const Gathered*>(r->_tempObject);
  HttpError refused = g ? g->refused : wifiHeaderError(r);  // no body: judged on its headers here
  if (refused.status) {
    writeError(w, refused.code, refused.message);
    return r->send(refused.status, "application/json", w.text());
  }
  JsonDocument doc;
  if (!g || g->tooLarge || deserializeJson(doc, g->data, g->len)) {
    writeError(w, "bad_json", "send {apPassword?, staSsid?, staPassword?} as JSON, under 1 KB");
    return r->send(400, "application/json", w.text());
  }
  RequestError e{};
  WifiSettings next = *settings;
  if (!applyWifi(JsonView{doc.as<JsonVariantConst>()}, next, e)) {
    writeError(w, e.code, e.message, e.path);
    return r->send(400, "application/json", w.text());
  }
  if (flashBusy()) return sendFlashBusy(r);  // loop() is inside a file operation: nothing is stored
  if (!save(next)) {
    writeError(w, "spool_failed", "the ESP could not store the settings");
    return r->send(503, "application/json", w.text());
  }
  *settings = next;
  writeWifi(w, next, false);
  r->send(200, "application/json", w.text());  // they take effect at the next start
}

}  // namespace

const char* apAddress() { return apIp; }

HttpError foreignRequest(AsyncWebServerRequest* r) {
  const char* origin = r->hasHeader("Origin") ? r->header("Origin").c_str() : nullptr;
  return originError(origin, r->host().c_str(), apIp, kMdnsName);
}

void beginNetwork(AsyncWebServer& server, Print& log, WifiSettings& s) {
  settings = &s;
  logOut = &log;
  WiFi.persistent(false);  // the settings live in /wifi.json, not in the SDK's flash area
  WiFi.mode(WIFI_AP);      // the radio on before the password is drawn (hardwareRandom)
  load(s);
  startRadio(s);
  log.printf("echo:Wi-Fi %s password %s at http://%s/ (http://%s.local/)\n", s.apSsid, s.apPassword, apIp, kMdnsName);
  if (MDNS.begin(kMdnsName)) MDNS.addService("http", "tcp", 80);
  server.on("/wifi", HTTP_GET, onGetWifi);
  server.on("/wifi", HTTP_POST, onPostWifi, nullptr, onWifiBody);
}

void pollNetwork() {
  dns.processNextRequest();
#if defined(ESP8266)
  MDNS.update();
#endif
  // Joining a network is optional: if it fails, the printer stays on its own access point.
  if (joining && WiFi.status() == WL_CONNECTED) joining = false;
  if (joining && millis() - joinStartMs > kJoinMs) {
    joining = false;
    WiFi.disconnect();
    WiFi.mode(WIFI_AP);
  }
}

}  // namespace esp
}  // namespace uv
