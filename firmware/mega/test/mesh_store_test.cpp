// The mesh in EEPROM: a stored grid is taken only if G29 could have made it, whatever its CRC says.
#include "mesh_store.h"

#include <gtest/gtest.h>

#include "crc32.h"
#include "eeprom_fake.h"
#include "le_bytes.h"

using namespace mega;

namespace {

// Writes a mesh record as MeshStore lays it out, with a good CRC, straight into the EEPROM.
void store(FakeEeprom& ee, uint8_t nx, uint8_t ny, int32_t x0, int32_t y0, int32_t dx, int32_t dy) {
  uint8_t rec[20 + 2 * 81 + 4] = {'M', '1', nx, ny};
  putLe32(static_cast<uint32_t>(x0), reinterpret_cast<char*>(rec + 4));
  putLe32(static_cast<uint32_t>(y0), reinterpret_cast<char*>(rec + 8));
  putLe32(static_cast<uint32_t>(dx), reinterpret_cast<char*>(rec + 12));
  putLe32(static_cast<uint32_t>(dy), reinterpret_cast<char*>(rec + 16));
  uint16_t bytes = static_cast<uint16_t>(20 + 2 * (nx > 9 ? 0 : nx) * (ny > 9 ? 0 : ny));
  for (uint16_t i = 20; i < bytes; i += 2) rec[i] = 40;  // 40 µm everywhere
  putLe32(uv::crc32Update(0, reinterpret_cast<const char*>(rec), bytes), reinterpret_cast<char*>(rec + bytes));
  for (uint16_t i = 0; i < bytes + 4; i++) ee.bytes[kMeshEepromAt + i] = rec[i];
}

}  // namespace

TEST(MeshStore, AGoodStoredMeshLoadsAndInterpolates) {
  FakeEeprom ee;
  store(ee, 3, 3, 10000, 10000, 90000, 90000);
  MeshStore mesh(ee);
  ASSERT_TRUE(mesh.load());
  EXPECT_EQ(mesh.offsetAt(50000, 70000), 40);
}

TEST(MeshStore, AStoredGridG29CouldNotHaveMadeIsRefused) {
  // Seen by the fuzzer: a huge spacing with a good CRC overflowed x0 + (nx - 1) * dx in offsetAt.
  struct Bad {
    uint8_t nx, ny;
    int32_t x0, y0, dx, dy;
  };
  for (Bad b : {Bad{9, 9, 0, 0, 0x7fffffff, 1000}, Bad{3, 3, 2000000, 0, 1000, 1000}, Bad{3, 3, -5, 0, 1000, 1000},
                Bad{3, 3, 0, 0, 1000000, 1000001}, Bad{2, 3, 0, 0, 1000, 1000}, Bad{3, 10, 0, 0, 1000, 1000},
                Bad{3, 3, 0, 0, 0, 1000}, Bad{9, 9, 1, 1, 250000, 250000}}) {
    FakeEeprom ee;
    store(ee, b.nx, b.ny, b.x0, b.y0, b.dx, b.dy);
    MeshStore mesh(ee);
    EXPECT_FALSE(mesh.load()) << int(b.nx) << "x" << int(b.ny) << " from " << b.x0 << "," << b.y0 << " by " << b.dx << "," << b.dy;
    EXPECT_EQ(mesh.offsetAt(1000000, 1000000), 0);
  }
  FakeEeprom ee;  // the largest G29 can make: 9 x 9 over a 2000 mm bed
  store(ee, 9, 9, 0, 0, 250000, 250000);
  MeshStore mesh(ee);
  EXPECT_TRUE(mesh.load());
  EXPECT_EQ(mesh.offsetAt(2000000, 2000000), 40);
}
