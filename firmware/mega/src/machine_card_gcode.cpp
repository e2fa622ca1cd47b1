// G-code files on the card, as Marlin hosts use them (protocol/mega.md "G-code files on the card"): M28/M29
// store the lines and show the file whole, M23/M24/M25/M26/M27/M32/M524/M30 run it between the hosts' lines.
#include <new>
#include <string.h>

#include "error_codes.h"
#include "job_files.h"
#include "machine.h"
#include "machine_budget.h"
#include "progmem.h"
#include "text_scan.h"

namespace mega {

namespace {
// Lines a G-code file may not run: they would start another file or job from inside it.
bool refusedFromCard(const uv::Command& c) {
  if (c.letter != 'M') return false;
  switch (c.code) {
    case 23: case 24: case 28: case 29: case 32: case 828: case 1000: return true;
    default: return false;
  }
}
}  // namespace

bool Machine::gcodeCommand(HostLink& port, const uv::Command& c, Result& r) {
  char name[kFileNameMax + 1] = {};
  if (c.text) {
    memcpy(name, c.text, c.textLen);
    name[c.textLen] = 0;
  }
  bool card = arena_ == Arena::Gcode && !gcode()->uploading();  // a G-code file is selected
  r = Result::Done;
  switch (c.code) {
    case 28:
      if (!isGcodeName(name)) {
        if (!strchr(name, '~')) return false;
        port.errorLineP(uv::kBadParameter, UV_P("a job's name has no ~"));  // `~` marks the Mega's own files
        return true;
      }
      if (refuseCardJob(port)) return true;
      clearArena();
      selected_[0] = 0;
      arena_ = Arena::Gcode;
      jobPort_ = &port;
      if (new (arenaMem_) GcodeFile(sd_), gcode()->beginUpload(name)) {
        clearArena();
        port.errorLine(uv::kFileError, name);
        return true;
      }
      {
        char buf[56];
        uvMemcpyP(buf, UV_P("echo:Writing to file: "), 22);
        strcpy(buf + 22, name);
        port.line(buf);
      }
      return true;
    case 29:
      if (arena_ != Arena::Gcode || !gcode()->uploading()) return false;
      if (&port != jobPort_) {
        port.errorLine(uv::kBusy);  // the other port's upload is not this one's to end
        return true;
      }
      if (gcode()->commit()) port.errorLine(uv::kFileError);
      else port.lineP(UV_P("echo:Done saving file."));
      clearArena();
      return true;
    case 23:
    case 32: {
      if (!isGcodeName(name)) {
        if (c.code == 23) return false;
        port.errorLineP(uv::kBadParameter, UV_P("M32 runs G-code files"));
        return true;
      }
      if (refuseCardJob(port)) return true;
      clearArena();
      selected_[0] = 0;
      new (arenaMem_) GcodeFile(sd_);
      arena_ = Arena::Gcode;
      if (gcode()->open(name)) {
        clearArena();
        port.errorLine(uv::kFileNotFound, name);
        return true;
      }
      saySelected(port, name, c.textLen, gcode()->size());
      strcpy(selected_, name);
      jobPort_ = &port;
      jobState_ = uv::JobState::Idle;
      if (c.code == 32) gcode()->running = true;
      return true;
    }
    case 24:
      if (!card) return false;
      gcode()->running = true;  // its lines run once no host line waits (runCardLine)
      jobPort_ = &port;
      return true;
    case 25:
      if (!card) return false;
      gcode()->running = false;  // after the line that runs now
      return true;
    case 26:
      if (!card || !c.hasValue('S') || c.value('S') < 0 || c.value('S') % 1000 ||
          !gcode()->seek(static_cast<uint32_t>(c.value('S') / 1000)))
        port.errorLineP(uv::kBadParameter, UV_P("S"));
      return true;
    case 27: {
      if (!card || c.has('S')) return false;
      char buf[48];
      formatCardProgress(buf);
      port.line(buf);
      return true;
    }
    case 524:
      if (arena_ != Arena::Gcode) return false;
      clearArena();  // an upload cut short leaves nothing; a running file stops
      selected_[0] = 0;
      motion_.stop();
      return true;
    case 30:
      if (!card || strcmp(name, selected_) != 0) return false;
      if (gcode()->running) {
        port.errorLine(uv::kBusy);
        return true;
      }
      clearArena();  // deselected, then deleted as any file
      selected_[0] = 0;
      return false;
    default:
      return false;
  }
}

Machine::Result Machine::storeGcodeLine(HostLink& port, const LineSlot& line) {
  if (line.n < 0) {  // a plain line has no check: it cannot be stored as verified
    port.errorLineP(uv::kNoLineNumber, UV_P("a stored line needs a line number"));
    return Result::Done;
  }
  if (gcode()->store(line.text, line.len)) {
    clearArena();  // the working file goes; the upload is over
    port.errorLine(uv::kFileError);
  }
  return Result::Done;
}

void Machine::runCardLine() {
  if (arena_ != Arena::Gcode || !gcode()->running || long_.op != Op::None || halted_) return;
  HostLink& port = *const_cast<HostLink*>(jobPort_);
  if (port.room() < kReplyRoom) return;
  GcodeFile& g = *gcode();
  if (!g.pending) {
    if (!g.next(g.line)) {
      if (g.failed()) port.errorLine(uv::kFileError, selected_);
      else port.lineP(UV_P("Done printing file"));
      clearArena();  // Marlin deselects the file once it has run
      selected_[0] = 0;
      return;
    }
    g.pending = true;
  }
  uv::Command c;
  if (g.line.overflow) {
    port.errorLineP(uv::kBadParameter, UV_P("line too long"));
  } else if (!uv::parseCommand(g.line.text, g.line.len, c) && refusedFromCard(c)) {
    port.errorLine(uv::kBusy, g.line.text);
  } else {
    port.lastError = 0;
    Result r = execute(port, g.line);
    if (r == Result::Wait) return;  // the same line next pass
    if (r == Result::Long) long_.fromCard = true;
    if (uv::isFault(port.lastError)) return stopCardFile();
  }
  if (arena_ == Arena::Gcode) g.pending = false;
}

bool Machine::formatCardProgress(char* out) {
  if (arena_ != Arena::Gcode || gcode()->uploading()) return false;
  uvMemcpyP(out, UV_P("SD printing byte "), 17);
  size_t n = 17 + uv::putUnsigned(gcode()->pos(), out + 17);
  out[n++] = '/';
  out[n + uv::putUnsigned(gcode()->size(), out + n)] = 0;
  return true;
}

void Machine::stopCardFile() {
  // A fault (the machine stopped or in danger) ends the file, as a killed Marlin ends its SD print.
  if (arena_ == Arena::Gcode && !gcode()->uploading()) {
    clearArena();
    selected_[0] = 0;
  }
}

}  // namespace mega
