// Replies leave whole or wait: a full transmit ring never cuts a line, and a FAULT is never lost.
#include "host_link.h"

#include <gtest/gtest.h>

#include <string>

#include "dialect_reply.h"
#include "mega_rig.h"

using namespace mega;

namespace {

struct NoKick : TxPort {
  void kick() override {}
};

std::string drain(HostLink& link) {
  std::string out;
  for (int16_t b; (b = link.nextTx()) >= 0;) out.push_back(static_cast<char>(b));
  return out;
}

// Every line a host reads is one the dialect knows, and every ok's checksum holds: a line cut
// short and run into the next fails one or the other.
void expectWholeLines(const std::vector<std::string>& lines) {
  for (const std::string& l : lines) {
    uv::Reply r{};
    ASSERT_TRUE(uv::parseReply(l.data(), static_cast<uint8_t>(l.size()), r)) << l;
    if (l.rfind("ok", 0) == 0) {
      EXPECT_TRUE(r.hasFlow) << l;
    }
    EXPECT_EQ(l.find("FAULT:"), l.rfind("FAULT:", 0) == 0 ? 0u : std::string::npos) << l;
  }
}

}  // namespace

TEST(HostLink, ALineThatDoesNotFitIsNotSentAtAllAndIsCounted) {
  NoKick tx;
  uint8_t moves = 8;
  LineSlot slots[kUsbWindow];
  HostLink link(tx, moves, lineWindow(slots));
  std::string forty(39, 'x');
  int sent = 0;
  while (link.report(forty.c_str())) sent++;
  EXPECT_EQ(sent, (kTxRing - 1) / 40);
  EXPECT_EQ(link.txDropped(), 0u);  // report() says no without counting: its caller tries again
  link.line(forty.c_str());         // a reply with no room: refused whole, and counted
  EXPECT_EQ(link.txDropped(), 1u);
  std::string out = drain(link);
  EXPECT_EQ(out.size(), static_cast<size_t>(sent) * 40);
  for (size_t i = 0; i < out.size(); i += 40) EXPECT_EQ(out.substr(i, 40), forty + "\n");
}

TEST(HostLink, AnM112FromTheOtherPortWaitsForRoomAndAFaultWaitsToo) {
  // Seen by the fuzzer: M112 on the ESP port while the USB ring held an E6/Resend block; the
  // halted reply was cut and ran into the FAULT line: `ok N1 P7 B1*b935FAULT:E31 ...`.
  MegaRig m;
  m.begin();
  uint32_t dwell = m.send("G4 S10");
  m.run(20000);  // the dwell is under way
  m.nano.setTemps(650);  // over the Nano's own limit: a FAULT comes
  // A report and a burst of damaged numbered lines fill the USB ring (an error block, and the
  // rest wait), then M112 on the ESP, all taken in main-loop passes with no byte carried out.
  ASSERT_TRUE(m.usbLink.report(("echo:" + std::string(104, 'r')).c_str()));  // 33 bytes left
  for (int k = 0; k < 4; k++)
    for (char c : std::string("N") + std::to_string(dwell + 1 + k) + " M105*0\n") m.usbLink.received(c);
  for (char c : std::string("M112\n")) m.espLink.received(c);
  // A second of main-loop passes with the Nano heard but no byte carried to the USB host: the
  // halted reply and the FAULT both find the ring too full.
  for (int pass = 0; pass < 10000; pass++) {
    m.nowUs += 100;
    m.nano.advance(m.nowUs);
    m.machine.poll(static_cast<uint32_t>(m.nowUs));
    ASSERT_LT(m.usbLink.room(), 35);  // less than the halted reply or the FAULT needs: the test means something
  }
  m.run(500000);
  expectWholeLines(m.usbLines);
  expectWholeLines(m.espLines);
  std::string okDwell = "ok N" + std::to_string(dwell) + " ";
  bool halted = false, answered = false, fault = false;
  for (const std::string& l : m.usbLines) {
    halted |= l.rfind("Error:E13", 0) == 0;
    answered |= l.rfind(okDwell, 0) == 0;
    fault |= l.rfind("FAULT:E3", 0) == 0;
  }
  EXPECT_TRUE(halted);
  EXPECT_TRUE(answered);
  EXPECT_TRUE(fault);
  EXPECT_EQ(m.usbLink.txDropped(), 0u);
  EXPECT_EQ(m.espLink.txDropped(), 0u);
}
