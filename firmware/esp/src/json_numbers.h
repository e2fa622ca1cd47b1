// Which JSON numbers are integers the hub takes: those an int64 holds exactly. Shared by the JSON
// views (nlohmann on the host, ArduinoJson on the ESP) so a number out of range is refused the
// same way everywhere, never wrapped (a uint64 over INT64_MAX) nor cast (1e300: undefined).
#pragma once
#include <stdint.h>

namespace uv {
namespace esp {

// A float that is a whole number within int64: 128.0 is 128, as in the schema validator.
inline bool exactInt64(double d, int64_t& out) {
  // -2^63 and 2^63 are exact doubles; the cast is defined only strictly inside (-2^63-1, 2^63).
  if (!(d >= -9223372036854775808.0 && d < 9223372036854775808.0)) return false;  // NaN too
  int64_t i = static_cast<int64_t>(d);
  if (static_cast<double>(i) != d) return false;
  out = i;
  return true;
}

// An unsigned integer that int64 holds.
inline bool exactInt64(uint64_t u, int64_t& out) {
  if (u > static_cast<uint64_t>(INT64_MAX)) return false;
  out = static_cast<int64_t>(u);
  return true;
}

}  // namespace esp
}  // namespace uv
