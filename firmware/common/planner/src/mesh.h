// Z offset from a probed mesh by bilinear interpolation (protocol/planner.md "Mesh interpolation").
#pragma once
#include <stdint.h>

namespace uv {

constexpr uint8_t kMeshMax = 9;

// Where a mesh's points are.
struct MeshGrid {
  uint8_t nx, ny;  // 2-9 points per axis
  int32_t x0, y0;  // µm
  int32_t dx, dy;  // µm between points, > 0
};

struct Mesh : MeshGrid {
  int16_t z[kMeshMax][kMeshMax];  // [j][i], µm
};

// The largest bed the machine takes (CONFIG.md: bed.x, bed.y up to 2000 mm), in µm.
constexpr int32_t kMeshMaxBedUm = 2000000;

// A grid as G29 makes one: 3-9 points per axis, from x0, y0 >= 0 at spacings > 0, the last point
// on a bed of at most kMeshMaxBedUm. A grid read back from storage must pass the same test before
// it is used, so that no product in meshZ can overflow.
inline bool meshGridValid(const MeshGrid& m) {
  auto axisFits = [](uint8_t n, int32_t origin, int32_t step) {
    if (n < 3 || n > kMeshMax || origin < 0 || origin > kMeshMaxBedUm || step <= 0) return false;
    return step <= (kMeshMaxBedUm - origin) / (n - 1);  // origin + (n - 1) * step, never computed past the bed
  };
  return axisFits(m.nx, m.x0, m.dx) && axisFits(m.ny, m.y0, m.dy);
}

// The interpolation over any store of points: `zAt(i, j)` gives point (i, j) in µm. The Mega
// reads its points from EEPROM this way instead of holding the table in RAM.
template <class ZAt>
int32_t meshZ(const MeshGrid& m, int32_t x, int32_t y, ZAt zAt) {
  int32_t xMax = m.x0 + (m.nx - 1) * m.dx, yMax = m.y0 + (m.ny - 1) * m.dy;
  int32_t cx = x < m.x0 ? m.x0 : (x > xMax ? xMax : x);
  int32_t cy = y < m.y0 ? m.y0 : (y > yMax ? yMax : y);
  int32_t i = (cx - m.x0) / m.dx, j = (cy - m.y0) / m.dy;
  if (i > m.nx - 2) i = m.nx - 2;
  if (j > m.ny - 2) j = m.ny - 2;
  int64_t u = cx - (m.x0 + i * m.dx), w = cy - (m.y0 + j * m.dy);
  int64_t dx = m.dx, dy = m.dy;
  uint8_t ii = static_cast<uint8_t>(i), jj = static_cast<uint8_t>(j);
  int64_t n = zAt(ii, jj) * (dx - u) * (dy - w) + zAt(static_cast<uint8_t>(ii + 1), jj) * u * (dy - w) +
              zAt(ii, static_cast<uint8_t>(jj + 1)) * (dx - u) * w +
              zAt(static_cast<uint8_t>(ii + 1), static_cast<uint8_t>(jj + 1)) * u * w;
  int64_t d = dx * dy;
  int64_t a = n < 0 ? -n : n;
  int64_t q = a / d;
  if ((a - q * d) * 2 >= d) q++;  // half away from zero
  return static_cast<int32_t>(n < 0 ? -q : q);
}

int32_t meshZ(const Mesh& m, int32_t x, int32_t y);

}  // namespace uv
