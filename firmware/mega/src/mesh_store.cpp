// The probed bed mesh in the EEPROM: header, points, CRC-32; written a byte at a time in the background.
#include "mesh_store.h"

#include <string.h>

#include "crc32.h"
#include "le_bytes.h"

namespace mega {

namespace {
// magic 2, nx, ny, x0 4, y0 4, dx 4, dy 4 = 20 bytes, then the points (int16 LE), then the CRC-32.
constexpr uint8_t kMagic0 = 'M', kMagic1 = '1';

void put32(int32_t v, uint8_t* out) { putLe32(static_cast<uint32_t>(v), reinterpret_cast<char*>(out)); }
}  // namespace

uint32_t MeshStore::crcOfStored(uint16_t bytes) {
  uint32_t crc = 0;
  for (uint16_t a = 0; a < bytes; a++) {
    char b = static_cast<char>(ee_.read(kMeshEepromAt + a));
    crc = uv::crc32Update(crc, &b, 1);
  }
  return crc;
}

bool MeshStore::load() {
  valid_ = false;
  while (!ee_.ready()) {
  }
  auto byte = [this](uint16_t a) { return ee_.read(kMeshEepromAt + a); };
  auto word = [&byte](uint16_t a) {
    uint32_t v = 0;
    for (uint8_t i = 0; i < 4; i++) v |= static_cast<uint32_t>(byte(a + i)) << (8 * i);
    return v;
  };
  if (byte(0) != kMagic0 || byte(1) != kMagic1) return false;
  uv::MeshGrid g;
  g.nx = byte(2);
  g.ny = byte(3);
  g.x0 = static_cast<int32_t>(word(4));
  g.y0 = static_cast<int32_t>(word(8));
  g.dx = static_cast<int32_t>(word(12));
  g.dy = static_cast<int32_t>(word(16));
  if (!uv::meshGridValid(g)) return false;  // as strict as a probed one: a CRC is no proof of sense
  uint16_t bytes = static_cast<uint16_t>(20 + 2 * g.nx * g.ny);
  if (word(bytes) != crcOfStored(bytes)) return false;
  grid_ = g;
  valid_ = true;
  return true;
}

int16_t MeshStore::z(uint8_t i, uint8_t j) {
  uint16_t a = zAddr(i, j);
  return static_cast<int16_t>(ee_.read(a) | ee_.read(static_cast<uint16_t>(a + 1)) << 8);
}

int32_t MeshStore::offsetAt(int32_t x, int32_t y) {
  if (!valid_) return 0;
  return uv::meshZ(grid_, x, y, [this](uint8_t i, uint8_t j) { return static_cast<int64_t>(z(i, j)); });
}

void MeshStore::queue(uint16_t addr, const uint8_t* bytes, uint8_t n) {
  pendingAt_ = addr;
  memcpy(pending_, bytes, n);
  pendingLen_ = n;
  pendingPos_ = 0;
}

void MeshStore::begin(const uv::MeshGrid& grid) {
  valid_ = false;
  grid_ = grid;
  uint8_t head[20] = {0, 0, grid.nx, grid.ny};  // the magic is cleared now and written last, by commit()
  magicDue_ = sealing_ = false;
  put32(grid.x0, head + 4);
  put32(grid.y0, head + 8);
  put32(grid.dx, head + 12);
  put32(grid.dy, head + 16);
  queue(kMeshEepromAt, head, sizeof head);
}

bool MeshStore::setPoint(uint8_t i, uint8_t j, int16_t zUm) {
  if (pendingLen_) return false;  // the previous point is still being written
  uint8_t b[2] = {static_cast<uint8_t>(zUm), static_cast<uint8_t>(static_cast<uint16_t>(zUm) >> 8)};
  queue(zAddr(i, j), b, 2);
  return true;
}

bool MeshStore::commit() {
  if (pendingLen_) return false;
  while (!ee_.ready()) {
  }
  uint16_t bytes = static_cast<uint16_t>(20 + 2 * grid_.nx * grid_.ny);
  // The CRC covers the magic too: compute it as the header will read.
  uint32_t crc = 0;
  for (uint16_t a = 0; a < bytes; a++) {
    char b = static_cast<char>(a == 0 ? kMagic0 : a == 1 ? kMagic1 : ee_.read(kMeshEepromAt + a));
    crc = uv::crc32Update(crc, &b, 1);
  }
  uint8_t tail[6];
  put32(static_cast<int32_t>(crc), tail);
  queue(static_cast<uint16_t>(kMeshEepromAt + bytes), tail, 4);
  magicDue_ = true;
  valid_ = false;
  return true;
}

void MeshStore::poll() {
  while (pendingLen_ && ee_.ready()) {
    uint16_t at = static_cast<uint16_t>(pendingAt_ + pendingPos_);
    uint8_t b = pending_[pendingPos_++];
    if (pendingPos_ == pendingLen_) pendingLen_ = 0;
    if (ee_.read(at) != b) {
      ee_.write(at, b);
      return;
    }
  }
  if (!pendingLen_ && magicDue_ && ee_.ready()) {
    magicDue_ = false;
    uint8_t magic[2] = {kMagic0, kMagic1};
    queue(kMeshEepromAt, magic, 2);  // last: a mesh cut short by a restart never reads as valid
    sealing_ = true;
  } else if (!pendingLen_ && sealing_ && ee_.ready()) {
    sealing_ = false;
    valid_ = true;
  }
}

}  // namespace mega
