// Invariants the fuzz harnesses hold every input to, beyond "no crash": a failed one aborts, so
// libFuzzer keeps the input that broke it.
#pragma once
#include <stdio.h>
#include <stdlib.h>

#include <string>
#include <vector>

#include "dialect_reply.h"

#define FUZZ_REQUIRE(cond, what)                                                        \
  do {                                                                                  \
    if (!(cond)) {                                                                      \
      fprintf(stderr, "invariant broken at %s:%d: %s\n", __FILE__, __LINE__, (what)); \
      abort();                                                                          \
    }                                                                                   \
  } while (0)

namespace fuzz {

inline bool printable(const std::string& s) {
  for (unsigned char c : s)
    if (c < 0x20 || c > 0x7e) return false;
  return true;
}

// Splits what a port carried into its complete lines; the rest stays in `carried`.
inline std::vector<std::string> takeLines(std::string& carried) {
  std::vector<std::string> lines;
  size_t nl;
  while ((nl = carried.find('\n')) != std::string::npos) {
    lines.push_back(carried.substr(0, nl));
    carried.erase(0, nl + 1);
  }
  return lines;
}

// A line the Mega sent a host: printable, within the dialect's longest reply, one the dialect
// knows, and an ok whose checksum holds (a line cut short and run into the next fails that).
inline void requireHostLine(const std::string& l) {
  FUZZ_REQUIRE(printable(l), ("unprintable line to a host: " + l).c_str());
  FUZZ_REQUIRE(l.size() <= 200, ("overlong line to a host: " + l).c_str());
  uv::Reply r{};
  FUZZ_REQUIRE(uv::parseReply(l.data(), static_cast<uint8_t>(l.size()), r), ("a line the dialect does not know: " + l).c_str());
  if (l.rfind("ok", 0) == 0) FUZZ_REQUIRE(r.hasFlow, ("an ok whose checksum fails: " + l).c_str());
  // A FAULT appended to another line (`ok N1 P7 B1*b935FAULT:E31 ...`, seen once) is lost to the
  // host; an error or echo may quote the host's own text, which can hold anything printable.
  bool quotes = l.rfind("Error:", 0) == 0 || l.rfind("echo:", 0) == 0;
  FUZZ_REQUIRE(quotes || l.find("FAULT:") == std::string::npos || l.rfind("FAULT:", 0) == 0, ("a FAULT run into another line: " + l).c_str());
}

}  // namespace fuzz
