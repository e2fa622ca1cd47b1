// The hub's web server: ESPAsyncWebServer, with a limit on each connection's request line and
// headers (http_rules.h HeaderBudget) that the library does not have (protocol/esp.md "A slow
// client holds nothing for long").
#pragma once
#include <ESPAsyncWebServer.h>

namespace uv {
namespace esp {

class HubServer : public AsyncWebServer {
 public:
  explicit HubServer(uint16_t port);
};

}  // namespace esp
}  // namespace uv
