// The hub's RAM: its fixed buffers against what an ESP8266 has left once Wi-Fi and the web server
// run (about 50 KB of heap). Measured here with the host's 8-byte pointers: an upper bound.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "bridge.h"
#include "host_body.h"
#include "live_channel.h"
#include "live_inbox.h"
#include "loop_desk.h"
#include "network_desk.h"
#include "print_intake.h"
#include "wifi_settings.h"

using namespace uv::esp;

TEST(HubBudget, TheFixedBuffersFitAnEsp8266) {
  constexpr size_t kInbox = sizeof(LiveInbox);  // arduino/live_socket.cpp: /ws's messages on their way to loop()
  constexpr size_t kNetworkReply = kErrorJsonBytes;  // arduino/print_endpoint.cpp: answers the network task makes itself
  constexpr size_t kLiveMessage = LiveChannel::kMaxMessage + 1;  // bridge.cpp: one live message
  using Intake = PrintIntake<uvtest::HostBody, uvtest::HostHeaderParse>;
  size_t intake = sizeof(Intake);
  // The hand-over between the tasks: its rings (two whole answers) and each side's desk.
  size_t handOver = sizeof(HandOver) + sizeof(NetworkDesk<std::weak_ptr<int>>) + sizeof(LoopDesk<Bridge, Intake>);
  size_t total = sizeof(LiveChannel) + sizeof(Bridge) + intake + handOver + kInbox + kNetworkReply + kLiveMessage + sizeof(WifiSettings);
  std::printf("[esp budget] hub RAM: %zu B of fixed buffers (live ring %zu, bridge %zu, print intake %zu, hand-over %zu, the rest %zu); budget 32768 B\n",
              total, sizeof(LiveChannel), sizeof(Bridge), intake, handOver, total - sizeof(LiveChannel) - sizeof(Bridge) - intake - handOver);
  EXPECT_LE(total, 32768u);
}
