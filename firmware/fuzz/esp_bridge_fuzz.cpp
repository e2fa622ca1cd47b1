// Fuzzes the ESP's hub between the Mega's UART and the browsers' WebSockets: any bytes from the
// Mega, any JSON messages from any of the clients, joins and leaves, time. Holds: every frame a
// client gets is whole JSON within the channel's limit; every line to the Mega is one printable
// dialect line; the status the hub serves is whole JSON.
#include <fuzzer/FuzzedDataProvider.h>

#include <string>

#include "bridge.h"
#include "fuzz_checks.h"
#include "nlohmann_view.h"

using uv::esp::LiveChannel;

namespace {

struct Clients : uv::esp::LiveClients {
  bool trySend(uint8_t, const char* text, uint16_t len) override {
    FUZZ_REQUIRE(len <= LiveChannel::kMaxMessage, "a frame over the channel's limit");
    FUZZ_REQUIRE(!nlohmann::json::parse(std::string(text, len), nullptr, false).is_discarded(),
                 ("a frame that is not JSON: " + std::string(text, len)).c_str());
    return true;
  }
  void close(uint8_t, uint16_t, const char*) override {}
};

struct Wire : uv::esp::MegaWire {
  std::string sent;
  bool write(const char* data, uint16_t n) override {
    sent.append(data, n);
    return true;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  Clients clients;
  LiveChannel live(clients);
  Wire wire;
  uv::esp::Bridge bridge(wire, live);
  uint32_t nowMs = 1000;
  bridge.begin(nowMs);
  while (in.remaining_bytes()) {
    switch (in.ConsumeIntegralInRange<uint8_t>(0, 5)) {
      case 0:
        for (char c : in.ConsumeRandomLengthString(120)) bridge.received(c, nowMs);
        break;
      case 1: {
        nlohmann::json m = nlohmann::json::parse(in.ConsumeRandomLengthString(120), nullptr, false);
        if (!m.is_discarded()) bridge.clientMessage(in.ConsumeIntegralInRange<uint8_t>(0, 5), uvtest::View{&m});
        break;
      }
      case 2:
        bridge.clientJoined(in.ConsumeIntegralInRange<uint8_t>(0, 5), nowMs);
        break;
      case 3:
        bridge.clientLeft(in.ConsumeIntegralInRange<uint8_t>(0, 5));
        break;
      case 4:
        nowMs += in.ConsumeIntegralInRange<uint32_t>(0, 5000);
        break;
      case 5: {
        char status[2048];
        uv::esp::JsonWriter w(status, sizeof status);
        bridge.writeStatus(w, nowMs);
        FUZZ_REQUIRE(w.ok(), "the status did not fit its buffer");
        FUZZ_REQUIRE(!nlohmann::json::parse(w.text(), nullptr, false).is_discarded(), "a status that is not JSON");
        break;
      }
    }
    bridge.poll(nowMs);
    live.pump();  // the network side's turn
    for (const std::string& l : fuzz::takeLines(wire.sent))
      FUZZ_REQUIRE(fuzz::printable(l) && l.size() <= 96, ("a line to the Mega out of form: " + l).c_str());
  }
  return 0;
}
