// Z offset from a probed mesh by bilinear interpolation (protocol/planner.md "Mesh interpolation").
#include "mesh.h"

namespace uv {

int32_t meshZ(const Mesh& m, int32_t x, int32_t y) {
  return meshZ(static_cast<const MeshGrid&>(m), x, y, [&m](uint8_t i, uint8_t j) { return static_cast<int64_t>(m.z[j][i]); });
}

}  // namespace uv
