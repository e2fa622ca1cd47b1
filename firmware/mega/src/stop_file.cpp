// The planned stops of a job on the SD card: header and 20-byte stops, little-endian.
#include "stop_file.h"

#include "le_bytes.h"
#include "nano_codec.h"
#include "progmem.h"

namespace mega {

namespace {
const char kMagic[4] UV_FLASH = {'U', 'V', 'S', '1'};
const char kScanMagic[4] UV_FLASH = {'U', 'V', 'P', '2'};  // passes (2: kept as kept_pass.h has them)
}  // namespace

bool writeStopHeader(Storage& sd, FileHandle f, const StopFileHeader& h) {
  char b[kStopHeaderBytes] = {};
  uvMemcpyP(b, h.scan ? kScanMagic : kMagic, 4);
  putLe32(h.count, b + 4);
  putLe32(h.estimateS, b + 8);
  putLe32(h.originUm[0], b + 12);
  putLe32(h.originUm[1], b + 16);
  putLe32(h.pitchUm[0], b + 20);
  putLe32(h.pitchUm[1], b + 24);
  putLe32(static_cast<uint32_t>(static_cast<uint16_t>(h.thermalCoeff)) | static_cast<uint32_t>(static_cast<uint16_t>(h.thermalRefDeciC)) << 16, b + 28);
  return sd.seek(f, 0) && sd.write(f, b, sizeof b);
}

bool readStopHeader(Storage& sd, FileHandle f, StopFileHeader& h) {
  char b[kStopHeaderBytes];
  if (!sd.seek(f, 0) || sd.read(f, b, sizeof b) != sizeof b) return false;
  bool stops = true, scan = true;
  for (uint8_t i = 0; i < 4; i++) {
    stops = stops && b[i] == static_cast<char>(uvFlashByte(&kMagic[i]));
    scan = scan && b[i] == static_cast<char>(uvFlashByte(&kScanMagic[i]));
  }
  if (!stops && !scan) return false;
  h.scan = scan;
  h.count = getLe32(b + 4);
  h.estimateS = getLe32(b + 8);
  h.originUm[0] = getLe32(b + 12);
  h.originUm[1] = getLe32(b + 16);
  h.pitchUm[0] = getLe32(b + 20);
  h.pitchUm[1] = getLe32(b + 24);
  uint32_t t = getLe32(b + 28);
  h.thermalCoeff = static_cast<int16_t>(t & 0xffff);
  h.thermalRefDeciC = static_cast<int16_t>(t >> 16);
  if (scan) return sd.size(f) == kStopHeaderBytes + sizeof(uv::JobHeader) + 8;
  return sd.size(f) == kStopHeaderBytes + static_cast<uint32_t>(kStopBytes) * h.count;
}

bool writeScanHeader(Storage& sd, FileHandle f, const uv::JobHeader& h, uint32_t linkBaud, uint32_t kept) {
  char b[8];
  putLe32(linkBaud, b);
  putLe32(kept, b + 4);
  return sd.seek(f, kStopHeaderBytes) && sd.write(f, reinterpret_cast<const char*>(&h), sizeof h) && sd.write(f, b, sizeof b);
}

bool readScanHeader(Storage& sd, FileHandle f, uv::JobHeader& h, uint32_t& linkBaud, uint32_t& kept) {
  char b[8];
  if (!sd.seek(f, kStopHeaderBytes) || sd.read(f, reinterpret_cast<char*>(&h), sizeof h) != static_cast<int16_t>(sizeof h) || sd.read(f, b, sizeof b) != 8)
    return false;
  linkBaud = getLe32(b);
  kept = getLe32(b + 4);
  return uv::nanoLinkBaud(linkBaud);
}

bool writeStop(Storage& sd, FileHandle f, const uv::Stop& s) {
  char b[kStopBytes];
  // The head position in cells, hx and hy as the two 16-bit halves of one word.
  putLe32((static_cast<uint32_t>(static_cast<uint16_t>(s.hx))) | (static_cast<uint32_t>(static_cast<uint16_t>(s.hy)) << 16), b);
  for (uint8_t i = 0; i < 4; i++) putLe32(s.us[i], b + 4 + 4 * i);
  return sd.write(f, b, sizeof b);
}

bool readStop(Storage& sd, FileHandle f, uint32_t i, uv::Stop& s) {
  char b[kStopBytes];
  if (!sd.seek(f, kStopHeaderBytes + static_cast<uint32_t>(kStopBytes) * i) || sd.read(f, b, sizeof b) != sizeof b) return false;
  uint32_t xy = getLe32(b);
  s.hx = static_cast<int16_t>(xy & 0xffff);
  s.hy = static_cast<int16_t>(xy >> 16);
  for (uint8_t k = 0; k < 4; k++) s.us[k] = getLe32(b + 4 + 4 * k);
  return true;
}

}  // namespace mega
