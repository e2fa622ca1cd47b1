// Host tests of the ESP's HTTP decisions: status codes before the body, error bodies, app files.
#include "http_rules.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <set>
#include <string>

#include "noisy_mega.h"

using namespace uv::esp;
using nlohmann::json;

TEST(HttpRules, APrintRequestIsJudgedByItsHeadersBeforeItsBody) {
  esptest::NoisyMega m;
  esptest::NoClients c;
  LiveChannel live(c);
  Bridge bridge(m, live);
  m.mega.begin();
  bridge.begin(m.nowMs());
  auto run = [&](uint64_t us) {
    m.run(
        us, [&](char ch, uint32_t ms) { bridge.received(ch, ms); }, [&](uint32_t ms) { bridge.poll(ms); });
  };
  EXPECT_EQ(admitPrintRequest("application/json", true, 100, bridge, m.nowMs()).status, 503);  // not heard yet
  run(1500000);
  EXPECT_EQ(admitPrintRequest("text/plain", true, 100, bridge, m.nowMs()).status, 415);
  EXPECT_EQ(admitPrintRequest(nullptr, true, 100, bridge, m.nowMs()).status, 415);
  EXPECT_EQ(admitPrintRequest("application/jsonx", true, 100, bridge, m.nowMs()).status, 415);
  EXPECT_EQ(admitPrintRequest("application/json", false, 0, bridge, m.nowMs()).status, 411);
  EXPECT_EQ(admitPrintRequest("application/json", true, 1200001, bridge, m.nowMs()).status, 413);
  HttpError ok = admitPrintRequest("application/json; charset=utf-8", true, 1200000, bridge, m.nowMs());
  EXPECT_EQ(ok.status, 0);
  EXPECT_EQ(admitPrintRequest("application/json", true, 100, bridge, m.nowMs()).status, 409);  // held for the first
  bridge.release();
  EXPECT_EQ(admitPrintRequest("application/json", true, 100, bridge, m.nowMs()).status, 0);
}

TEST(HttpRules, MethodsAndErrorBodies) {
  EXPECT_EQ(methodNotAllowed("/print", Method::Get).status, 405);
  EXPECT_EQ(methodNotAllowed("/print", Method::Delete).status, 0);
  EXPECT_EQ(methodNotAllowed("/status", Method::Post).status, 405);
  EXPECT_EQ(methodNotAllowed("/wifi", Method::Post).status, 0);
  EXPECT_EQ(methodNotAllowed("/index.html", Method::Delete).status, 405);
  char buf[256];
  JsonWriter w(buf, sizeof buf);
  writeError(w, "bad_job", "must be an \"integer\"", "/gridData/3/7");
  EXPECT_EQ(json::parse(w.text()), json({{"error", {{"code", "bad_job"}, {"message", "must be an \"integer\""}, {"path", "/gridData/3/7"}}}}));
  JsonWriter v(buf, sizeof buf);
  writeError(v, "busy", "a job is uploading or running");
  EXPECT_FALSE(json::parse(v.text())["error"].contains("path"));
}

TEST(HttpRules, AppFilesGetTheirTypeAndAnEtagFromTheGzipTrailer) {
  EXPECT_STREQ(contentType("/index.html"), "text/html; charset=utf-8");
  EXPECT_STREQ(contentType("/assets/index-3f2a.js"), "text/javascript");
  EXPECT_STREQ(contentType("/manifest.webmanifest"), "application/manifest+json");
  EXPECT_STREQ(contentType("/x.bin"), "application/octet-stream");
  const uint8_t trailer[8] = {0x78, 0x56, 0x34, 0x12, 0x00, 0x10, 0x00, 0x00};
  char etag[24];
  gzipEtag(trailer, etag);
  EXPECT_STREQ(etag, "\"12345678-1000\"");
}

TEST(HttpRules, EachAppPathFindsItsGzippedFileOrTheApp) {
  std::set<std::string> flash = {"/index.html", "/assets/index-3f2a.js", "/manifest.webmanifest"};
  auto exists = [&](const char* p) { return flash.count(p) > 0; };
  char out[64];
  EXPECT_EQ(appFile("/", out, sizeof out, exists), AppFile::Found);
  EXPECT_STREQ(out, "/index.html");
  EXPECT_EQ(appFile("/assets/index-3f2a.js?v=2", out, sizeof out, exists), AppFile::Found);
  EXPECT_STREQ(out, "/assets/index-3f2a.js");
  EXPECT_EQ(appFile("/studio", out, sizeof out, exists), AppFile::Found);  // a path of the app itself
  EXPECT_STREQ(out, "/index.html");
  EXPECT_EQ(appFile("/missing.js", out, sizeof out, exists), AppFile::NotFound);
  EXPECT_EQ(appFile("/../wifi.json", out, sizeof out, exists), AppFile::NotFound);
  EXPECT_EQ(appFile("/studio", out, sizeof out, [](const char*) { return false; }), AppFile::NoApp);
  EXPECT_STREQ(cacheControl("/index.html"), "no-cache");
  EXPECT_STREQ(cacheControl("/manifest.webmanifest"), "no-cache");
  EXPECT_STREQ(cacheControl("/assets/index-3f2a.js"), "public, max-age=31536000, immutable");
}

TEST(HttpRules, CaptivePortalProbesAreSentToTheApp) {
  EXPECT_TRUE(isForeignHost("connectivitycheck.gstatic.com", "192.168.4.1", "uvprinter"));
  EXPECT_TRUE(isForeignHost("captive.apple.com", "192.168.4.1", "uvprinter"));
  EXPECT_FALSE(isForeignHost("192.168.4.1", "192.168.4.1", "uvprinter"));
  EXPECT_FALSE(isForeignHost("uvprinter.local", "192.168.4.1", "uvprinter"));
  EXPECT_FALSE(isForeignHost("UVPRINTER.local:80", "192.168.4.1", "uvprinter"));
  EXPECT_FALSE(isForeignHost("10.0.0.23", "192.168.4.1", "uvprinter"));  // its address on a joined network
}

TEST(HttpRules, OnlyTheHubsOwnPagesMayDriveIt) {
  auto code = [](const char* origin, const char* host) { return originError(origin, host, "192.168.4.1", "uvprinter").status; };
  // Its own pages, however it was reached.
  EXPECT_EQ(code("http://192.168.4.1", "192.168.4.1"), 0);
  EXPECT_EQ(code("http://uvprinter.local", "uvprinter.local"), 0);
  EXPECT_EQ(code("http://UVPrinter.local:80", "uvprinter.local"), 0);
  EXPECT_EQ(code("http://10.0.0.23", "10.0.0.23:80"), 0);  // its address on a joined network
  EXPECT_EQ(code("http://127.0.0.1:5000", "127.0.0.1:5000"), 0);
  // Not a browser's cross-site request: curl, OctoPrint-like tools.
  EXPECT_EQ(code(nullptr, "192.168.4.1"), 0);
  EXPECT_EQ(code("", "192.168.4.1"), 0);
  // Any other page.
  EXPECT_EQ(code("http://evil.example", "192.168.4.1"), 403);
  EXPECT_EQ(code("https://192.168.4.1", "192.168.4.1"), 403);
  EXPECT_EQ(code("null", "192.168.4.1"), 403);                     // a sandboxed frame, a file:// page
  EXPECT_EQ(code("http://127.0.0.1:5001", "127.0.0.1:5000"), 403);  // another port is another site
  EXPECT_EQ(code("http://192.168.4.1.evil.example", "192.168.4.1"), 403);
  EXPECT_EQ(code("http://evil.example", "evil.example"), 403);  // a DNS name rebound to the hub
  EXPECT_EQ(code("http://192.168.4.1", nullptr), 403);
  EXPECT_EQ(code("http://192.168.4.1", ""), 403);
  std::string longOrigin = "http://" + std::string(100, '1');
  EXPECT_EQ(code(longOrigin.c_str(), longOrigin.c_str() + 7), 403);  // too long to be ours
  HttpError e = originError("http://evil.example", "192.168.4.1", "192.168.4.1", "uvprinter");
  EXPECT_STREQ(e.code, "foreign_origin");
}

TEST(HttpRules, ABodyThatIsNotJsonIsRefusedBeforeItIsRead) {
  EXPECT_EQ(jsonBodyError("application/json").status, 0);
  EXPECT_EQ(jsonBodyError("Application/JSON; charset=utf-8").status, 0);
  for (const char* t : {"text/plain", "text/plain;charset=UTF-8", "application/x-www-form-urlencoded", "multipart/form-data", "application/jsonp", ""})
    EXPECT_EQ(jsonBodyError(t).status, 415) << t;
  EXPECT_EQ(jsonBodyError(nullptr).status, 415);
}

TEST(HttpRules, ARequestHasADeadlineFromItsFirstByte) {
  EXPECT_FALSE(pastDeadline(1000, 1000 + kRequestDeadlineMs));
  EXPECT_TRUE(pastDeadline(1000, 1001 + kRequestDeadlineMs));
  EXPECT_TRUE(pastDeadline(0xfffff000u, 0xfffff000u + kRequestDeadlineMs + 1));  // across millis()'s wrap
}

namespace {
bool feed(HeaderBudget& b, const std::string& text, uint32_t nowMs = 0) {
  return b.take(reinterpret_cast<const uint8_t*>(text.data()), text.size(), nowMs);
}
}  // namespace

TEST(HttpRules, HeadersEndAtTheBlankLineAndTheBodyPassesUncounted) {
  HeaderBudget b(0);
  EXPECT_TRUE(feed(b, "POST /print HTTP/1.1\r\nHost: 192.168.4.1\r\nContent-Length: 9000\r\n"));
  EXPECT_FALSE(b.done());
  EXPECT_TRUE(feed(b, "\r\n" + std::string(8000, '{')));  // the body, in the same packet
  EXPECT_TRUE(b.done());
  EXPECT_TRUE(feed(b, std::string(kHeaderBytesMax, 'x'), kRequestDeadlineMs + 5000));  // the body's deadline is the glue's
}

TEST(HttpRules, AHeaderLineThatNeverEndsIsCutAtTheLimitWhateverThePackets) {
  HeaderBudget b(0);
  EXPECT_TRUE(feed(b, "GET / HTTP/1.1\r\nX-Slow: "));
  bool open = true;
  for (int i = 0; i < kHeaderBytesMax && open; i++) open = feed(b, "a", i);
  EXPECT_FALSE(open);
  HeaderBudget whole(0);
  EXPECT_TRUE(feed(whole, "GET / HTTP/1.1\r\n" + std::string(kHeaderBytesMax - 20, 'h') + "\r\n\r\n"));  // 4096 B exactly, with the blank line
  HeaderBudget over(0);
  EXPECT_FALSE(feed(over, "GET / HTTP/1.1\r\n" + std::string(kHeaderBytesMax - 19, 'h') + "\r\n\r\n"));
}

TEST(HttpRules, HeadersStillArrivingAtTheDeadlineAreCut) {
  HeaderBudget b(1000);
  EXPECT_TRUE(feed(b, "GET / HTTP/1.1\r\n", 1000));
  EXPECT_TRUE(feed(b, "Host: a\r\n", 1000 + kRequestDeadlineMs));
  EXPECT_FALSE(feed(b, "X", 1001 + kRequestDeadlineMs));
}
