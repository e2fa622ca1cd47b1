// ESPAsyncWebServer 3.12 reads a request's line and headers in AsyncWebServerRequest::_onData,
// which adds the bytes of a line to `_temp` until its '\n' comes, with no limit but the heap
// (`_temp.reserve` failing aborts the connection, once the heap is short for everyone), and it
// offers no hook before the handler is chosen, at the headers' end. The library's server makes
// each request in its AsyncServer's onClient (WebServer.cpp, AsyncWebServer::AsyncWebServer), and
// the request sets itself as its AsyncClient's data handler. So this server sets its own onClient
// (`_server` is protected): it makes the request the same way, then puts a counter in front of the
// request's data handler (AsyncClient's protected `_recv_cb`, named through a class derived from
// AsyncClient, as both ESPAsyncTCP 2.0 and AsyncTCP 3.5 declare it). Past 4096 bytes without the
// headers' end, or past the request's deadline, the connection is aborted, as the library aborts a
// request it cannot parse. At the headers' end the request's own handler is put back.
#include "hub_server.h"

#include "http_rules.h"

namespace uv {
namespace esp {

namespace {

// Never made: it names the data handler that AsyncClient keeps protected.
struct ClientData : AsyncClient {
  static AcDataHandler AsyncClient::*handler() { return &ClientData::_recv_cb; }
  static void* AsyncClient::*arg() { return &ClientData::_recv_cb_arg; }
};

void limitHeaders(AsyncClient* c) {
  AcDataHandler parse = c->*ClientData::handler();  // the request's _onData
  void* request = c->*ClientData::arg();
  HeaderBudget budget(millis());
  c->onData([parse, request, budget](void*, AsyncClient* client, void* data, size_t len) mutable {
    if (!budget.take(static_cast<const uint8_t*>(data), len, millis())) {
      client->abort();  // the request goes with its connection (its onDisconnect)
      return;
    }
    // Copies: putting the request's handler back, or the request taking the connection over (a
    // WebSocket), ends this lambda while the request parses.
    AcDataHandler p = parse;
    void* a = request;
    if (budget.done()) client->onData(p, a);
    p(a, client, data, len);
  }, nullptr);
}

}  // namespace

HubServer::HubServer(uint16_t port) : AsyncWebServer(port) {
  _server.onClient(
      [](void* s, AsyncClient* c) {
        if (!c) return;
        c->setRxTimeout(3);  // as the library's own onClient
        std::shared_ptr<AsyncWebServerRequest> r = AsyncWebServerRequest::create(static_cast<AsyncWebServer*>(s), c);
        if (!r) {
          c->abort();
          delete c;
          return;
        }
        limitHeaders(c);
      },
      this);
}

}  // namespace esp
}  // namespace uv
