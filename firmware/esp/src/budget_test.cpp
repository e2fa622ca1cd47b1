// The hub's RAM: its fixed buffers against what an ESP8266 has left once Wi-Fi and the web server
// run (about 50 KB of heap). Measured here with the host's 8-byte pointers: an upper bound.
#include <gtest/gtest.h>

#include <cstdio>

#include "bridge.h"
#include "host_body.h"
#include "live_channel.h"
#include "print_intake.h"
#include "wifi_settings.h"

using namespace uv::esp;

TEST(HubBudget, TheFixedBuffersFitAnEsp8266) {
  constexpr size_t kInbox = 8 * (4 + 257);      // arduino/live_socket.cpp: 8 queued client frames
  constexpr size_t kReplies = 2048;             // arduino/print_endpoint.cpp: one HTTP answer
  constexpr size_t kLiveMessage = LiveChannel::kMaxMessage + 1;  // bridge.cpp: one live message
  size_t intake = sizeof(PrintIntake<uvtest::HostBody, uvtest::HostHeaderParse>);
  size_t total = sizeof(LiveChannel) + sizeof(Bridge) + intake + kInbox + kReplies + kLiveMessage + sizeof(WifiSettings);
  std::printf("[esp budget] hub RAM: %zu B of fixed buffers (live ring %zu, bridge %zu, print intake %zu, the rest %zu); budget 32768 B\n", total,
              sizeof(LiveChannel), sizeof(Bridge), intake, total - sizeof(LiveChannel) - sizeof(Bridge) - intake);
  EXPECT_LE(total, 32768u);
}
