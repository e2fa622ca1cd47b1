// The command core's reports: multi-line replies (M115, M119, M20, M503, the mesh), the auto-reports,
// M821's diagnostics, and the printhead's FAULT lines, each sent whole when its port has room.
#include <string.h>

#include "dialect_reply.h"
#include "error_codes.h"
#include "job_files.h"
#include "machine.h"
#include "machine_budget.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

namespace {
// The room a DOSE: line waits for: one with a 7-digit stop and exposure, 8-digit times (up to 99 s),
// a plan and a flag.
constexpr uint8_t kDoseLineRoom = 10 + 7 + 6 + 5 + 5 + 7 + 4 + 35 + 6 + 35 + 8 + 1;
}  // namespace

bool Machine::emitNext() {
  HostLink& port = *long_.port;
  char buf[112];
  uv::Reply r{};
  switch (long_.gen) {
    case Gen::Firmware: {
      static const char kWin[] UV_FLASH = "RX_WINDOW", kTemp[] UV_FLASH = "AUTOREPORT_TEMP", kPos[] UV_FLASH = "AUTOREPORT_POS",
                        kSd[] UV_FLASH = "SDCARD", kResume[] UV_FLASH = "RESUME", kJob[] UV_FLASH = "JOB_FORMAT",
                        kLink[] UV_FLASH = "LINK_BAUD";
      static const char* const kCaps[] UV_FLASH = {kWin, kTemp, kPos, kSd, kResume, kJob, kLink};
      char cap[32];
      if (long_.index == 0) {
        r.kind = uv::ReplyKind::Firmware;
        strcpy_flash(cap, firmwareName_);  // the name is in flash
        r.text = cap;
        r.textLen = static_cast<uint8_t>(strlen(cap));
        r.value = 1;
      } else if (long_.index <= 7) {
        uint8_t i = static_cast<uint8_t>(long_.index - 1);
        // JOB_FORMAT: the newest job format it reads (job.md), 2 with run-length rows. LINK_BAUD: the
        // printhead link's speed a job planned now is costed at and runs at (nano.md "Link speed").
        const uint32_t values[] = {long_.port->window(), 1u, 1u, sd_.present() ? 1u : 0u, sd_.present() ? 1u : 0u, 2u, head_.jobBaud()};
        r.kind = uv::ReplyKind::Cap;
        strcpy_flash(cap, uvFlashPtr(kCaps[i]));
        r.text = cap;
        r.textLen = static_cast<uint8_t>(strlen(cap));
        r.value = values[i];
      } else {
        return false;
      }
      uv::formatReply(r, buf, sizeof buf);
      break;
    }
    case Gen::Endstops: {
      static const char kX[] UV_FLASH = "x_min: ", kY[] UV_FLASH = "y_min: ", kZ[] UV_FLASH = "z_min: ", kProbe[] UV_FLASH = "z_probe: ";
      static const char* const kNames[] UV_FLASH = {kX, kY, kZ, kProbe};
      if (long_.index >= 4) return false;
      bool closed = long_.index < 3 ? (io_.endstops() & (1 << long_.index)) : head_.probeTriggered();
      strcpy_flash(buf, uvFlashPtr(kNames[long_.index]));
      strcpy_flash(buf + strlen(buf), closed ? UV_P("TRIGGERED") : UV_P("open"));
      break;
    }
    case Gen::Files: {
      if (long_.index == 0) {
        strcpy_flash(buf, UV_P("Begin file list"));
      } else if (long_.index == 1) {
        uint32_t size;
        char name[kFileNameMax + 1];
        do {
          if (!sd_.entry(long_.fileIndex++, name, size)) {
            long_.index = 2;
            return true;
          }
        } while (isWorkFile(name));
        size_t n = strlen(name);
        memcpy(buf, name, n);
        buf[n] = ' ';
        buf[n + 1 + uv::putUnsigned(size, buf + n + 1)] = 0;
        if (!port.report(buf)) long_.fileIndex--;  // the same file next pass
        return true;
      } else if (long_.index == 2) {
        strcpy_flash(buf, UV_P("End file list"));
      } else {
        return false;
      }
      break;
    }
    case Gen::Mesh:
      if (!emitMesh(buf)) return false;
      break;
    case Gen::Config: {
      if (long_.index >= kKeyCount) return false;
      uvMemcpyP(buf, UV_P("M850 "), 5);
      uint8_t n = static_cast<uint8_t>(5 + keyName(static_cast<Key>(long_.index), buf + 5));
      buf[n++] = ' ';
      config_.format(static_cast<Key>(long_.index), buf + n);
      break;
    }
  }
  if (!port.report(buf)) return true;  // no room yet: the same line next pass
  long_.index++;
  return true;
}


Machine::Result Machine::diagnostics(HostLink& port, const uv::Command& c) {
  char buf[112];
  char* p = buf;
  auto field = [&p](const char* flashName, uint32_t v) {
    size_t n = uvStrlenP(flashName);
    uvMemcpyP(p, flashName, n);
    p += n;
    p += uv::putUnsigned(v, p);
  };
  uint16_t dropped = 0, unsent = 0;
  for (HostLink* h : ports_) {
    dropped = static_cast<uint16_t>(dropped + h->dropped());
    unsent = static_cast<uint16_t>(unsent + h->txDropped());
  }
  field(UV_P("echo:DIAG loop_max_us="), stats_.loopMaxUs);
  field(UV_P(" step_isr_max_us="), stats_.stepIsrMaxUs);
  field(UV_P(" underruns="), motion_.engine().underruns());
  field(UV_P(" rx_dropped="), dropped);
  field(UV_P(" tx_dropped="), unsent);
  *p = 0;
  port.line(buf);
  if (c.has('R')) stats_.loopMaxUs = 0;
  return Result::Done;
}

bool Machine::doseRecord(void* self, const uv::NanoReply* record) {
  Machine& m = *static_cast<Machine*>(self);
  if (!record) {
    for (HostLink* p : m.ports_)
      if (p->room() < kDoseLineRoom) return false;
    return true;
  }
  uv::DoseReport d;
  if (!m.running() || !m.run()->attribute(*record, d)) return true;  // no stop of a job: not reported
  char line[uv::kDoseReportMax + 1];
  if (uv::formatDoseReport(d, line, sizeof line)) {
    for (HostLink* p : m.ports_) p->line(line);  // one wider than the room asked for is counted (M821)
    m.run()->keepDose(line);  // and beside a card job, on the card
  }
  return true;
}

void Machine::printheadEvents() {
  uint8_t e = head_.takeEvents();
  if (e & PrintheadLink::kWentOffline) {
    headFaults_.owed |= HeadFaults::kOffline * kAllPorts;
    lastFault_ = uv::kNanoTimeout;
  }
  if (e & PrintheadLink::kCameBack) broadcastP(UV_P("echo:printhead answering again"));
  if (e & PrintheadLink::kNanoReset) broadcastP(UV_P("echo:printhead restarted by its watchdog"));
  if (e & PrintheadLink::kFault) {
    head_.allOff();
    uint8_t active = head_.activeFaults();
    lastFault_ = (active & uv::fault::kSensor) ? uv::kSensorFault : uv::kOverTemperature;
    const int16_t* t = head_.deciC();
    uint8_t hot = 0;
    for (uint8_t i = 1; i < uv::kSensorCount; i++)
      if (t[i] > t[hot]) hot = i;
    headFaults_.sensor = (active & uv::fault::kSensor) != 0;
    headFaults_.hot = hot;
    headFaults_.deciC = t[hot];  // as it was when the fault came: the line may wait for room
    headFaults_.owed |= HeadFaults::kThermal * kAllPorts;
  }
  sayHeadFaults();
}

void Machine::sayHeadFaults() {
  // A FAULT line is never lost: it waits, per port, until that port has room for it whole.
  for (uint8_t k = 0; headFaults_.owed && k < kPorts; k++) {
    for (uint8_t kind = HeadFaults::kOffline; kind <= HeadFaults::kThermal; kind = static_cast<uint8_t>(kind << kPorts)) {
      uint8_t bit = static_cast<uint8_t>(kind << k);
      if (!(headFaults_.owed & bit)) continue;
      char buf[48];
      if (kind == HeadFaults::kOffline) {
        strcpy_flash(buf, UV_P("FAULT:E30 printhead not responding"));
      } else if (headFaults_.sensor) {
        strcpy_flash(buf, UV_P("FAULT:E32 temperature sensor fault"));
      } else {
        strcpy_flash(buf, UV_P("FAULT:E31 over-temperature T"));
        size_t n = strlen(buf);
        buf[n++] = static_cast<char>('0' + headFaults_.hot);
        buf[n++] = ' ';
        buf[n + uv::formatDeciC(headFaults_.deciC, buf + n)] = 0;
      }
      if (ports_[k]->report(buf)) headFaults_.owed = static_cast<uint8_t>(headFaults_.owed & ~bit);
    }
  }
}

uint8_t Machine::formatTemps(char* out) const {
  uv::Reply r{};
  r.kind = uv::ReplyKind::Temps;
  for (uint8_t i = 0; i < uv::kSensorCount; i++) r.deciC[i] = head_.deciC()[i];
  return static_cast<uint8_t>(uv::formatReply(r, out, 112));
}

uint8_t Machine::formatPosition(char* out) const {
  uv::Reply r{};
  r.kind = uv::ReplyKind::Position;
  int32_t steps[3];
  motion_.positionSteps(steps);
  for (uint8_t a = 0; a < 3; a++) {
    r.steps[a] = steps[a];
    r.um[a] = motion_.toUm(a, steps[a]);
  }
  return static_cast<uint8_t>(uv::formatReply(r, out, 112));
}

void Machine::reports() {
  char buf[112];
  if (tempPeriodUs_ && static_cast<int32_t>(now_ - tempNext_) >= 0 && head_.tempsKnown()) {
    tempNext_ = now_ + tempPeriodUs_;
    formatTemps(buf);
    broadcast(buf);
  }
  if (posPeriodUs_ && static_cast<int32_t>(now_ - posNext_) >= 0) {
    posNext_ = now_ + posPeriodUs_;
    formatPosition(buf);
    broadcast(buf);
  }
}


}  // namespace mega
