// Z offset from a probed mesh by bilinear interpolation (protocol/planner.md "Mesh interpolation").
#pragma once
#include <stdint.h>

namespace uv {

constexpr uint8_t kMeshMax = 9;

struct Mesh {
  uint8_t nx, ny;  // 2-9 points per axis
  int32_t x0, y0;  // µm
  int32_t dx, dy;  // µm between points, > 0
  int16_t z[kMeshMax][kMeshMax];  // [j][i], µm
};

int32_t meshZ(const Mesh& m, int32_t x, int32_t y);

}  // namespace uv
