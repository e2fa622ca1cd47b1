// The dialect's stable numeric error codes (protocol/errors.csv); never renumber.
#include "error_codes.h"

#include <string.h>

#include "progmem.h"

namespace uv {
namespace {

struct Entry {
  uint8_t code;
  const char* name;
  const char* message;
};

#define UV_ERR(code, name, msg)                   \
  static const char name##_n[] UV_FLASH = #name; \
  static const char name##_m[] UV_FLASH = msg;
UV_ERR(1, invalid_byte, "invalid byte in line")
UV_ERR(2, checksum_mismatch, "checksum mismatch")
UV_ERR(3, no_checksum, "line number without checksum")
UV_ERR(4, no_line_number, "checksum without line number")
UV_ERR(5, line_too_long, "line too long")
UV_ERR(6, line_sequence, "line number is not last line number+1")
UV_ERR(10, unknown_command, "unknown command")
UV_ERR(11, bad_parameter, "bad or missing parameter")
UV_ERR(12, busy, "not allowed while a job is running")
UV_ERR(13, halted, "machine halted: send M999")
UV_ERR(14, not_homed, "axis not homed")
UV_ERR(15, soft_limit, "target outside soft limits")
UV_ERR(20, no_sd, "no SD card")
UV_ERR(21, file_not_found, "file not found")
UV_ERR(22, file_error, "SD read or write error")
UV_ERR(23, job_malformed, "job record malformed")
UV_ERR(24, job_hash_mismatch, "job hash mismatch")
UV_ERR(25, job_incomplete, "job upload incomplete")
UV_ERR(26, no_job, "no job selected")
UV_ERR(27, no_resume, "no interrupted job to resume")
UV_ERR(28, stream_overflow, "stream buffer too small for this job")
UV_ERR(29, scan_unsupported, "scan job not supported by this machine")
UV_ERR(30, nano_timeout, "printhead not responding")
UV_ERR(31, over_temperature, "over-temperature")
UV_ERR(32, sensor_fault, "temperature sensor fault")
UV_ERR(33, exposure_refused, "printhead refused an exposure")
UV_ERR(34, link_speed, "printhead link not at the job's planned speed")
UV_ERR(40, probe_alarm, "probe alarm")
UV_ERR(41, probe_no_trigger, "probe did not trigger")
UV_ERR(42, endstop_hit, "unexpected endstop hit")
UV_ERR(43, selftest_failed, "self-test failed")
UV_ERR(44, homing_failed, "endstop not found while homing")
UV_ERR(50, config_invalid, "config value invalid")
#undef UV_ERR

#define UV_ROW(code, name) {code, name##_n, name##_m},
const Entry kTable[] UV_FLASH = {
    UV_ROW(1, invalid_byte) UV_ROW(2, checksum_mismatch) UV_ROW(3, no_checksum)
    UV_ROW(4, no_line_number) UV_ROW(5, line_too_long) UV_ROW(6, line_sequence)
    UV_ROW(10, unknown_command) UV_ROW(11, bad_parameter) UV_ROW(12, busy)
    UV_ROW(13, halted) UV_ROW(14, not_homed) UV_ROW(15, soft_limit) UV_ROW(20, no_sd)
    UV_ROW(21, file_not_found) UV_ROW(22, file_error) UV_ROW(23, job_malformed)
    UV_ROW(24, job_hash_mismatch) UV_ROW(25, job_incomplete) UV_ROW(26, no_job)
    UV_ROW(27, no_resume) UV_ROW(28, stream_overflow) UV_ROW(29, scan_unsupported) UV_ROW(30, nano_timeout) UV_ROW(31, over_temperature)
    UV_ROW(32, sensor_fault) UV_ROW(33, exposure_refused) UV_ROW(34, link_speed) UV_ROW(40, probe_alarm)
    UV_ROW(41, probe_no_trigger) UV_ROW(42, endstop_hit) UV_ROW(43, selftest_failed) UV_ROW(44, homing_failed)
    UV_ROW(50, config_invalid)};
#undef UV_ROW

bool copyField(uint8_t code, bool wantName, char* out, uint8_t size) {
  for (const Entry& e : kTable) {
    uint8_t c = uvFlashByte(&e.code);
    if (c != code) continue;
    const char* src = wantName ? uvFlashPtr(e.name) : uvFlashPtr(e.message);
    uvFlashStrncpy(out, src, size);
    out[size - 1] = '\0';
    return true;
  }
  // Not in the table: a text all the same, so a caller that formats a line never sends what was
  // in its buffer before (found by fuzzing the host link).
  uvFlashStrncpy(out, wantName ? UV_P("unknown") : UV_P("unknown error"), size);
  out[size - 1] = '\0';
  return false;
}

}  // namespace

bool errorMessage(uint8_t code, char* out, uint8_t size) { return copyField(code, false, out, size); }
bool errorName(uint8_t code, char* out, uint8_t size) { return copyField(code, true, out, size); }

}  // namespace uv
