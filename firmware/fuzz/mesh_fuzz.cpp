// Fuzzes the mesh the Mega reads from its EEPROM at start-up, CRC and all (a CRC is no proof of
// sense). Holds: a mesh that loads is one G29 could have made, and interpolating it anywhere on
// or off the bed stays within the stored points' range (UBSan sees any overflow on the way).
#include <fuzzer/FuzzedDataProvider.h>

#include <string.h>

#include <algorithm>
#include <string>

#include "crc32.h"
#include "eeprom_fake.h"
#include "fuzz_checks.h"
#include "mesh_store.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  mega::FakeEeprom ee;
  std::string record = in.ConsumeBytesAsString(20 + 2 * 81);
  bool sealed = in.ConsumeBool();
  memcpy(ee.bytes + mega::kMeshEepromAt, record.data(), record.size());
  if (record.size() >= 4 && sealed) {  // most random records die at the CRC: give half a good one
    ee.bytes[mega::kMeshEepromAt] = 'M';
    ee.bytes[mega::kMeshEepromAt + 1] = '1';
    uint8_t nx = ee.bytes[mega::kMeshEepromAt + 2], ny = ee.bytes[mega::kMeshEepromAt + 3];
    uint16_t bytes = static_cast<uint16_t>(20 + 2 * std::min<int>(nx, 9) * std::min<int>(ny, 9));
    uint32_t crc = uv::crc32Update(0, reinterpret_cast<const char*>(ee.bytes + mega::kMeshEepromAt), bytes);
    for (int i = 0; i < 4; i++) ee.bytes[mega::kMeshEepromAt + bytes + i] = static_cast<uint8_t>(crc >> (8 * i));
  }
  mega::MeshStore mesh(ee);
  if (!mesh.load()) {
    FUZZ_REQUIRE(mesh.offsetAt(in.ConsumeIntegral<int32_t>(), in.ConsumeIntegral<int32_t>()) == 0, "an unloaded mesh moves Z");
    return 0;
  }
  const uv::MeshGrid& g = mesh.grid();
  FUZZ_REQUIRE(uv::meshGridValid(g), "a loaded mesh G29 could not have made");
  int32_t lo = INT32_MAX, hi = INT32_MIN;
  for (uint8_t j = 0; j < g.ny; j++)
    for (uint8_t i = 0; i < g.nx; i++) {
      lo = std::min<int32_t>(lo, mesh.z(i, j));
      hi = std::max<int32_t>(hi, mesh.z(i, j));
    }
  for (int k = 0; k < 16 && in.remaining_bytes(); k++) {
    int32_t z = mesh.offsetAt(in.ConsumeIntegral<int32_t>(), in.ConsumeIntegral<int32_t>());
    FUZZ_REQUIRE(z >= lo && z <= hi, "an interpolated Z outside the probed points");
  }
  return 0;
}
