// The machine as a WebAssembly module: the Mega's command core and the Nano's printhead logic with
// the collaborators the host tests give them (mega_rig.h: host ports, motion and the step
// interrupt's code in virtual time, the card, the EEPROM, the switches), behind a C ABI of bytes and
// time. The first brick of the simulated printer that runs the firmware's own C++ (issue 27); built
// by scripts/build-wasm.sh, driven by app/src/sim/wasm/printer-module.ts.
#include <stdint.h>

#include <string>

#include "mega_rig.h"

#define UV_EXPORT(name) __attribute__((export_name(name)))

namespace {

mega::MegaRig* machine = nullptr;
std::string inbox, outbox;
size_t taken[2] = {0, 0};  // lines of each port already handed out

std::vector<std::string>& linesOf(uint32_t port) { return port ? machine->espLines : machine->usbLines; }

// The rig logs every step for the host tests; a printer that runs for hours must not. (It still
// logs each exposure and each scan pass's light, some 40 bytes apiece: issue 27's printer proper
// will hold none of the tests' logs.)
void quiet() { machine->rig.record = false; }

}  // namespace

extern "C" {

// Power-up: a new machine, its card and EEPROM blank. The Mega says `start` on both ports.
UV_EXPORT("printer_start") void printerStart() {
  delete machine;
  machine = new mega::MegaRig();
  quiet();
  machine->begin();
  taken[0] = taken[1] = 0;
}

// The Mega restarts, as when a host opens its USB port: its RAM is gone, the card and the EEPROM are
// kept, and the Nano runs on through the 0.1 s a Mega takes to start.
UV_EXPORT("printer_reset") void printerReset() {
  if (!machine) return printerStart();
  machine->reset(100000);  // what each port read before stays read: taken[] goes on
  quiet();
}

// A buffer for `n` bytes from a host, filled by the caller before printer_receive.
UV_EXPORT("printer_inbox") char* printerInbox(uint32_t n) {
  inbox.assign(n, '\0');
  return &inbox[0];
}

// The inbox's `n` bytes go on the wire to port 0 (USB) or 1 (the ESP's UART), at 115200 baud.
UV_EXPORT("printer_receive") void printerReceive(uint32_t port, uint32_t n) {
  if (!machine) return;  // no power: the bytes are lost
  (port ? machine->esp : machine->usb).toMega.append(inbox.data(), n < inbox.size() ? n : inbox.size());
}

// `us` of the machine's time: the main loop every 100 µs, the step interrupt between.
UV_EXPORT("printer_run") void printerRun(uint32_t us) {
  if (machine) machine->run(us);
}

// The lines the Mega sent on a port since the last call, each ending in '\n'; their length, and
// printer_outbox() their bytes.
UV_EXPORT("printer_sent") uint32_t printerSent(uint32_t port) {
  outbox.clear();
  if (!machine) return 0;
  std::vector<std::string>& lines = linesOf(port);
  for (size_t& i = taken[port ? 1 : 0]; i < lines.size(); i++) outbox += lines[i] + "\n";
  return static_cast<uint32_t>(outbox.size());
}
UV_EXPORT("printer_outbox") const char* printerOutbox() { return outbox.data(); }

// Where the head is, in steps, as the motors' pulses put it: axis 0-2.
UV_EXPORT("printer_position") int32_t printerPosition(uint32_t axis) {
  if (!machine) return 0;
  int32_t steps[3];
  machine->rig.motion.positionSteps(steps);
  return axis < 3 ? steps[axis] : 0;
}

}  // extern "C"
