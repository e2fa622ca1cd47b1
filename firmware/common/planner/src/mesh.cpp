// Z offset from a probed mesh by bilinear interpolation (protocol/planner.md "Mesh interpolation").
#include "mesh.h"

namespace uv {

int32_t meshZ(const Mesh& m, int32_t x, int32_t y) {
  int32_t xMax = m.x0 + (m.nx - 1) * m.dx, yMax = m.y0 + (m.ny - 1) * m.dy;
  int32_t cx = x < m.x0 ? m.x0 : (x > xMax ? xMax : x);
  int32_t cy = y < m.y0 ? m.y0 : (y > yMax ? yMax : y);
  int32_t i = (cx - m.x0) / m.dx, j = (cy - m.y0) / m.dy;
  if (i > m.nx - 2) i = m.nx - 2;
  if (j > m.ny - 2) j = m.ny - 2;
  int64_t u = cx - (m.x0 + i * m.dx), w = cy - (m.y0 + j * m.dy);
  int64_t dx = m.dx, dy = m.dy;
  int64_t n = m.z[j][i] * (dx - u) * (dy - w) + m.z[j][i + 1] * u * (dy - w) + m.z[j + 1][i] * (dx - u) * w +
              m.z[j + 1][i + 1] * u * w;
  int64_t d = dx * dy;
  int64_t a = n < 0 ? -n : n;
  int64_t q = a / d;
  if ((a - q * d) * 2 >= d) q++;  // half away from zero
  return static_cast<int32_t>(n < 0 ? -q : q);
}

}  // namespace uv
