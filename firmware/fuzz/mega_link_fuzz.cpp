// Fuzzes one of the Mega's host ports as its receive interrupt feeds it: bytes into the line
// ring, lines accepted (numbering, checksums, resend, duplicates) and answered as the command
// core would. Holds: every line a host reads is whole, printable, known, and its ok's CRC holds.
#include <fuzzer/FuzzedDataProvider.h>

#include <string>

#include "fuzz_checks.h"
#include "host_link.h"

namespace {

struct Wire : mega::TxPort {
  void kick() override {}
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  Wire wire;
  uint8_t movesFree = 8;
  mega::LineSlot slots[mega::kUsbWindow];
  mega::HostLink link(wire, movesFree, mega::lineWindow(slots));
  std::string carried;
  while (in.remaining_bytes()) {
    switch (in.ConsumeIntegralInRange<uint8_t>(0, 3)) {
      case 0:
        for (char c : in.ConsumeRandomLengthString(120)) link.received(c);
        break;
      case 1:
        link.poll();
        break;
      case 2:  // the command core answers the oldest line, with an error or a report first
        if (link.front() && link.room() >= 140) {
          if (in.ConsumeBool()) link.error(in.ConsumeIntegralInRange<uint8_t>(1, 60), in.ConsumeBool() ? "X" : nullptr);
          else link.ok();
        }
        break;
      case 3: {  // the wire carries some bytes out
        uint8_t n = in.ConsumeIntegral<uint8_t>();
        for (int16_t b; n-- && (b = link.nextTx()) >= 0;) carried.push_back(static_cast<char>(b));
        break;
      }
    }
    movesFree = in.ConsumeIntegralInRange<uint8_t>(0, 8);
  }
  for (int16_t b; (b = link.nextTx()) >= 0;) carried.push_back(static_cast<char>(b));
  for (const std::string& l : fuzz::takeLines(carried)) fuzz::requireHostLine(l);
  FUZZ_REQUIRE(carried.empty(), "a line without its end");
  FUZZ_REQUIRE(link.txDropped() == 0, "a reply dropped though room was made for it");
  return 0;
}
