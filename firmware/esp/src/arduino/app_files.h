// The app from LittleFS (/www, every file gzipped by `npm run build:esp`): the right content
// type, Content-Encoding gzip, an ETag from each file's gzip trailer with 304 for a match, and
// the captive portal's redirect for any other host. Everything else gets a JSON 404 or 405.
#pragma once
#include <ESPAsyncWebServer.h>

namespace uv {
namespace esp {

void beginAppFiles(AsyncWebServer& server);

}  // namespace esp
}  // namespace uv
