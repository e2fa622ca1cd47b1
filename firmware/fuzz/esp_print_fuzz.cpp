// Fuzzes POST /print's body as the hub spools it and checks it a share at a time (print_intake.h):
// any bytes, and JSON shaped like a job, in job format 1 or 2. Holds: the answer is 202, 400 or 413 (503 only if the
// spool fails), always whole JSON; a refusal names a code and, where it has one, the field.
#include <fuzzer/FuzzedDataProvider.h>

#include <unistd.h>

#include <fstream>
#include <string>

#include "bridge.h"
#include "fuzz_checks.h"
#include "host_body.h"
#include "print_intake.h"

using namespace uv::esp;

namespace {

struct Quiet : LiveClients {
  bool trySend(uint8_t, const char*, uint16_t) override { return true; }
  void close(uint8_t, uint16_t, const char*) override {}
};
struct Wire : MegaWire {
  bool write(const char*, uint16_t) override { return true; }
};

const std::string kSpool = "/tmp/uv-print-fuzz-" + std::to_string(getpid()) + ".json";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  Quiet clients;
  LiveChannel live(clients);
  Wire wire;
  Bridge bridge(wire, live);
  bridge.begin(1000);
  std::string body = in.ConsumeRemainingBytesAsString();
  // Half the bodies (by their length, so the seeds stay bodies) go to a Mega that reads job format
  // 2 (its M115 answer), so the conversion writes run-length rows where they are shorter.
  if (body.size() % 2 == 0) {
    for (char c : std::string("FIRMWARE_NAME:UVExposure 0.1.0 (Mega)\nCap:JOB_FORMAT:2\n")) bridge.received(c, 1000);
    FUZZ_REQUIRE(bridge.jobFormat() == 2, "the Mega's Cap:JOB_FORMAT:2 was not heard");
  }
  std::ofstream(kSpool, std::ios::binary | std::ios::trunc) << body;
  uvtest::HostBody spool(kSpool);
  PrintIntake<uvtest::HostBody, uvtest::HostHeaderParse> intake(spool, bridge, uvtest::HostHeaderParse{});
  intake.begin();
  Intake r;
  uint32_t ids = 0;
  int steps = 0;
  while ((r = intake.step([&] { return ++ids; })) == Intake::Working) FUZZ_REQUIRE(++steps < 100000, "the check never ends");
  uint16_t status = intake.status();
  std::string answer = intake.response();
  nlohmann::json j = nlohmann::json::parse(answer, nullptr, false);
  FUZZ_REQUIRE(!j.is_discarded(), ("an answer that is not whole JSON: " + answer).c_str());
  if (r == Intake::Accepted) {
    FUZZ_REQUIRE(status == 202 && j["job"]["state"] == "uploading", "an accepted job answered otherwise");
  } else {
    FUZZ_REQUIRE(status == 400 || status == 413 || status == 503, ("a refusal with status " + std::to_string(status)).c_str());
    FUZZ_REQUIRE(j.contains("error") && j["error"].contains("code"), ("a refusal without its code: " + answer).c_str());
  }
  intake.cancel();
  return 0;
}
