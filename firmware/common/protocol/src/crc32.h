// CRC-32 (IEEE 802.3, reflected, as zlib): the whole-job hash of protocol/job.md.
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace uv {

// Running CRC: start from 0 and feed the previous result back in.
uint32_t crc32Update(uint32_t crc, const char* data, size_t len);
// 8 lower-case hex digits and a NUL into out[9].
void crc32Hex(uint32_t crc, char* out);

}  // namespace uv
