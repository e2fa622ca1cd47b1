// The probed bed mesh (G29): kept in the EEPROM, where it outlives a restart and needs no RAM (the
// exposure reads the four points around each stop), and written to MESH.TXT on the card for people.
#pragma once
#include <stdint.h>

#include "eeprom.h"
#include "mesh.h"
#include "storage.h"

namespace mega {

constexpr uint16_t kMeshEepromAt = 256;  // after the config copy (config_store.h)
constexpr const char* kMeshFile = "MESH.TXT";

class MeshStore {
 public:
  explicit MeshStore(Eeprom& ee) : ee_(ee) {}

  // Reads the stored mesh at start-up; false if there is none or it is damaged.
  bool load();
  bool valid() const { return valid_; }
  const uv::MeshGrid& grid() const { return grid_; }
  int16_t z(uint8_t i, uint8_t j);
  // The mesh's Z offset at a bed position, µm (planner.md "Mesh interpolation").
  int32_t offsetAt(int32_t x, int32_t y);

  // A new mesh: the old one is void until commit().
  void begin(const uv::MeshGrid& grid);
  // Queues one probed point; the EEPROM takes it in the background (poll()).
  bool setPoint(uint8_t i, uint8_t j, int16_t zUm);
  // Seals the mesh once every point is written: its CRC, then its magic. valid() turns true when
  // the last byte is in.
  bool commit();
  void poll();
  bool busy() const { return pendingLen_ != 0 || magicDue_ || sealing_; }

 private:
  uint16_t zAddr(uint8_t i, uint8_t j) const { return static_cast<uint16_t>(kMeshEepromAt + 20 + 2 * (j * grid_.nx + i)); }
  uint32_t crcOfStored(uint16_t bytes);
  void queue(uint16_t addr, const uint8_t* bytes, uint8_t n);

  Eeprom& ee_;
  uv::MeshGrid grid_ = {};
  bool valid_ = false;
  uint16_t pendingAt_ = 0;
  uint8_t pending_[20];  // the header is the most queued at once
  uint8_t pendingLen_ = 0, pendingPos_ = 0;
  bool magicDue_ = false, sealing_ = false;
};

}  // namespace mega
