// Probe and mesh commands of the command core: G30 (probe here), G29 (probe the grid, keep it,
// apply it) and M420 (leveling on/off, report the mesh).
#include <string.h>

#include "dialect_reply.h"
#include "error_codes.h"
#include "machine.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

namespace {
size_t putMm(int32_t um, char* out) {
  size_t n = 0;
  uint32_t a = um < 0 ? static_cast<uint32_t>(-um) : static_cast<uint32_t>(um);
  if (um < 0) out[n++] = '-';
  n += uv::putUnsigned(a / 1000, out + n);
  out[n++] = '.';
  uint32_t f = a % 1000;
  out[n++] = static_cast<char>('0' + f / 100);
  out[n++] = static_cast<char>('0' + f / 10 % 10);
  out[n++] = static_cast<char>('0' + f % 10);
  return n;
}
}  // namespace

uint8_t Machine::formatPoint(char* out, int32_t x, int32_t y, int32_t z) const {
  uv::Reply r{};
  r.kind = uv::ReplyKind::ProbePoint;
  r.um[0] = x;
  r.um[1] = y;
  r.um[2] = z;
  return static_cast<uint8_t>(uv::formatReply(r, out, 112));
}

bool Machine::refuseProbing(HostLink& port) {
  if (!axisHomed(0) || !axisHomed(1) || !axisHomed(2)) {
    port.errorLineP(uv::kNotHomed, UV_P("home first (G28)"));
    return true;
  }
  if (!deployed_) {
    port.errorLineP(uv::kProbeNoTrigger, UV_P("deploy the probe (M401)"));
    return true;
  }
  return false;
}

Machine::Result Machine::probeOnce(HostLink& port, const uv::Command&) {
  if (refuseProbing(port)) return Result::Done;
  if (!motion_.idle()) return Result::Wait;
  probe_.start(now_);
  long_.op = Op::Probe;
  return Result::Long;
}

void Machine::runProbe() {
  RoutineStatus s = probe_.poll(now_);
  if (s == RoutineStatus::Running) return;
  if (s == RoutineStatus::Failed) {
    if (probe_.error() == uv::kProbeAlarm) long_.port->lineP(UV_P("PROBE:alarm"));
    return finishLong(probe_.error());
  }
  int32_t at[3];
  motion_.positionUm(at);
  char buf[64];
  formatPoint(buf, at[0], at[1], probe_.zUm());
  long_.port->line(buf);
  finishLong();
}

Machine::Result Machine::level(HostLink& port, const uv::Command& c) {
  int32_t nx = c.hasValue('X') ? c.value('X') : config_.milli(Key::MeshNx);
  int32_t ny = c.hasValue('Y') ? c.value('Y') : config_.milli(Key::MeshNy);
  if (nx % 1000 || ny % 1000 || nx < 3000 || nx > 9000 || ny < 3000 || ny > 9000) {
    port.errorLine(uv::kBadParameter);
    return Result::Done;
  }
  if (refuseProbing(port)) return Result::Done;
  if (jobActive()) {
    port.errorLine(uv::kBusy);
    return Result::Done;
  }
  if (!motion_.idle() || mesh_.busy()) return Result::Wait;
  uv::MeshGrid g;
  g.nx = static_cast<uint8_t>(nx / 1000);
  g.ny = static_cast<uint8_t>(ny / 1000);
  int32_t margin = config_.milli(Key::MeshMargin);
  g.x0 = g.y0 = margin;
  g.dx = (config_.milli(Key::BedX) - 2 * margin) / (g.nx - 1);
  g.dy = (config_.milli(Key::BedY) - 2 * margin) / (g.ny - 1);
  if (!uv::meshGridValid(g)) {
    port.errorLineP(uv::kBadParameter, UV_P("mesh.margin leaves no bed"));
    return Result::Done;
  }
  leveling_ = false;
  mesh_.begin(g);
  long_.op = Op::Level;
  long_.meshK = 0;
  long_.moving = false;
  long_.servoOp = 0;
  return Result::Long;
}

void Machine::runLevel() {
  const uv::MeshGrid& g = mesh_.grid();
  uint8_t count = static_cast<uint8_t>(g.nx * g.ny);
  if (long_.meshK == count) {  // every point in: seal it, keep it, apply it, show it
    if (!long_.moving) {
      long_.moving = mesh_.commit();  // once the last point's bytes are in
      return;
    }
    if (mesh_.busy()) return;
    if (!mesh_.valid()) return finishLong(uv::kFileError);
    leveling_ = true;
    writeMeshFile();
    long_.op = Op::Emit;
    long_.gen = Gen::Mesh;
    long_.index = 0;
    return;
  }
  uint8_t j = static_cast<uint8_t>(long_.meshK / g.nx);
  uint8_t i = static_cast<uint8_t>(long_.meshK % g.nx);
  if (j & 1) i = static_cast<uint8_t>(g.nx - 1 - i);  // serpentine over the grid
  if (!long_.moving) {
    int32_t to[3];
    motion_.targetUm(to);
    to[0] = g.x0 + i * g.dx;
    to[1] = g.y0 + j * g.dy;
    if (!motion_.moveTo(to, 0)) return;
    long_.moving = true;
    return;
  }
  if (long_.servoOp == 0) {  // on the way
    if (!motion_.idle()) return;
    probe_.start(now_);
    long_.servoOp = 1;  // probing
    return;
  }
  RoutineStatus s = probe_.poll(now_);
  if (s == RoutineStatus::Running) return;
  if (s == RoutineStatus::Failed) {
    long_.servoOp = 0;
    if (probe_.error() == uv::kProbeAlarm) long_.port->lineP(UV_P("PROBE:alarm"));
    return finishLong(probe_.error());
  }
  if (!mesh_.setPoint(i, j, static_cast<int16_t>(probe_.zUm()))) return;  // the last point is still being written
  char buf[64];
  formatPoint(buf, g.x0 + i * g.dx, g.y0 + j * g.dy, probe_.zUm());
  long_.port->line(buf);
  long_.servoOp = 0;
  long_.moving = false;
  long_.meshK++;
  if (long_.meshK == count) long_.moving = false;  // now: whether the seal has begun
}

bool Machine::emitMesh(char* buf) {
  const uv::MeshGrid& g = mesh_.grid();
  char* p = buf;
  if (long_.index == 0) {
    p += uv::putFlash(UV_P("MESH:grid "), p);
    p += uv::putUnsigned(g.nx, p);
    *p++ = ' ';
    p += uv::putUnsigned(g.ny, p);
    p += uv::putFlash(UV_P(" x0="), p);
    p += putMm(g.x0, p);
    p += uv::putFlash(UV_P(" y0="), p);
    p += putMm(g.y0, p);
    p += uv::putFlash(UV_P(" dx="), p);
    p += putMm(g.dx, p);
    p += uv::putFlash(UV_P(" dy="), p);
    p += putMm(g.dy, p);
  } else if (long_.index <= g.ny) {
    uint8_t j = static_cast<uint8_t>(long_.index - 1);
    p += uv::putFlash(UV_P("MESH:row "), p);
    p += uv::putUnsigned(j, p);
    for (uint8_t i = 0; i < g.nx; i++) {
      *p++ = ' ';
      p += putMm(mesh_.z(i, j), p);
    }
  } else {
    return false;
  }
  *p = 0;
  return true;
}

void Machine::writeMeshFile() {
  if (!sd_.present()) return;
  FileHandle f = sd_.open(kMeshFile, Storage::Mode::Create);
  if (f < 0) return;
  char buf[112];
  uint8_t index = long_.index;
  for (long_.index = 0; emitMesh(buf); long_.index++) {
    size_t n = strlen(buf);
    buf[n++] = '\n';
    sd_.write(f, buf, static_cast<uint16_t>(n));
  }
  long_.index = index;
  sd_.sync(f);
  sd_.close(f);
}

Machine::Result Machine::meshCommand(HostLink& port, const uv::Command& c) {
  if (c.has('V')) {
    if (!mesh_.valid()) {
      port.errorLineP(uv::kBadParameter, UV_P("no mesh"));
      return Result::Done;
    }
    long_.op = Op::Emit;
    long_.gen = Gen::Mesh;
    long_.index = 0;
    return Result::Long;
  }
  if (c.hasValue('S')) {
    if (c.value('S') && !mesh_.valid()) {
      port.errorLineP(uv::kBadParameter, UV_P("no mesh"));
      return Result::Done;
    }
    leveling_ = c.value('S') != 0;
  } else {
    // Bare M420: whether exposures follow the mesh, for a host's check before a job.
    port.lineP(leveling_ ? UV_P("echo:leveling on") : UV_P("echo:leveling off"));
  }
  return Result::Done;
}

}  // namespace mega
