// The machine as a WebAssembly module: the Mega's command core and the Nano's printhead logic with
// the collaborators the host tests give them (mega_rig.h: host ports, motion and the step
// interrupt's code in virtual time, the card, the EEPROM, the switches), behind a C ABI of bytes and
// time. The simulated printer (app/src/sim/sim-printer.ts) drives it; the physics it does not hold
// (the head's thermal model, the bed's surface) come from there, the bed through an import.
// Built by scripts/build-wasm.sh.
#include <stdint.h>
#include <string.h>

#include <string>

#include "mega_rig.h"
#include "panel_font.h"

#define UV_EXPORT(name) __attribute__((export_name(name)))

// The bed's height under the probe at (x, y), µm: the simulated printer's one bed (app/src/sim/bed.ts).
extern "C" __attribute__((import_module("env"), import_name("bed_um"))) int32_t bedUm(int32_t xUm, int32_t yUm);

namespace {

mega::MegaRig* machine = nullptr;
std::string inbox, outbox;

std::vector<std::string>& linesOf(uint32_t port) { return port ? machine->espLines : machine->usbLines; }

// The rig logs every step, line and exposure for the host tests; a printer that runs for hours
// keeps none of them.
void quiet() {
  machine->rig.record = false;
  machine->nano.logging = false;
  machine->bed = bedUm;
}

const char* give(const std::string& text, uint32_t* n) {
  outbox = text;
  *n = static_cast<uint32_t>(outbox.size());
  return outbox.data();
}

}  // namespace

extern "C" {

// Power-up: a new machine, its card and EEPROM blank. The Mega says `start` on both ports.
UV_EXPORT("printer_start") void printerStart() {
  delete machine;
  machine = new mega::MegaRig();
  // The head rests 10 mm above Z's switch (400 steps/mm); its probe's pin touches the bed 1 mm
  // below the switch (app/src/sim/bed.ts).
  machine->rig.switchAt[2] = -4000;
  quiet();
  machine->begin();
}

// The Mega restarts, as when a host opens its USB port (DTR): its RAM is gone, the card and the
// EEPROM are kept, and the Nano runs on through the 0.1 s a Mega takes to start. With `power_lost`
// the Nano restarts too, its start count one more.
UV_EXPORT("printer_reset") void printerReset(uint32_t powerLost) {
  if (!machine) return printerStart();
  machine->reset(100000, powerLost != 0);
  quiet();
}

// A buffer for `n` bytes from the host, filled by the caller before printer_receive or printer_card_put.
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
  for (const std::string& l : lines) outbox += l + "\n";
  lines.clear();
  return static_cast<uint32_t>(outbox.size());
}
UV_EXPORT("printer_outbox") const char* printerOutbox() { return outbox.data(); }

// Where the head is, in steps, as the motors' pulses put it: axis 0-2.
UV_EXPORT("printer_position") int32_t printerPosition(uint32_t axis) {
  if (!machine || axis > 2) return 0;
  return machine->rig.head[axis];
}

// --- The printhead's physics, from the host's models ---

// How long LED `led` has shone since power-up, µs (a double: it outlives 32 bits in a long job).
UV_EXPORT("printer_on_us") double printerOnUs(uint32_t led) {
  return machine && led < 4 ? static_cast<double>(machine->nano.onUs(static_cast<uint8_t>(led))) : 0;
}

// The six TMP36s read these temperatures, 0.1 °C each, from now on (an int16 array of 6 in the inbox).
UV_EXPORT("printer_temps") void printerTemps() {
  if (!machine || inbox.size() < 2 * uv::kSensorCount) return;
  int16_t deciC[uv::kSensorCount];
  memcpy(deciC, inbox.data(), sizeof deciC);
  machine->nano.setTemps(deciC);
}

// The faults the simulator's panel injects: no printhead answers; the probe's next deploy jams.
UV_EXPORT("printer_nano_missing") void printerNanoMissing(uint32_t missing) {
  if (machine) machine->nano.silent = missing != 0;
}
UV_EXPORT("printer_probe_alarm") void printerProbeAlarm(uint32_t armed) {
  if (machine) machine->probeAlarm = armed != 0;
}
// The card is in its slot, or not.
UV_EXPORT("printer_card_inserted") void printerCardInserted(uint32_t in) {
  if (machine) machine->sd.inserted = in != 0;
}

// --- What outlives the page: the card, the EEPROM, the Nano's start count ---

// The card's files, by index in the order the card lists them: how many; a name; its bytes.
UV_EXPORT("printer_card_count") uint32_t printerCardCount() {
  if (!machine) return 0;
  uint32_t n = 0;
  char name[mega::kFileNameMax + 1];
  uint32_t size;
  while (machine->sd.entry(static_cast<uint16_t>(n), name, size)) n++;
  return n;
}
UV_EXPORT("printer_card_name") const char* printerCardName(uint32_t i, uint32_t* n) {
  char name[mega::kFileNameMax + 1] = "";
  uint32_t size;
  if (!machine || !machine->sd.entry(static_cast<uint16_t>(i), name, size)) name[0] = 0;
  return give(name, n);
}
UV_EXPORT("printer_card_file") const char* printerCardFile(uint32_t i, uint32_t* n) {
  char name[mega::kFileNameMax + 1] = "";
  uint32_t size;
  if (!machine || !machine->sd.entry(static_cast<uint16_t>(i), name, size)) return give("", n);
  return give(machine->sd.contents(name), n);
}
// Puts a file on the card as it was kept: the inbox holds its name (`name_len` bytes) then its bytes.
UV_EXPORT("printer_card_put") void printerCardPut(uint32_t nameLen) {
  if (!machine || nameLen > inbox.size()) return;
  machine->sd.put(inbox.substr(0, nameLen), inbox.substr(nameLen));
}
// Counts every change of what the card durably holds (a sync, a removal, a rename).
UV_EXPORT("printer_card_revision") uint32_t printerCardRevision() {
  return machine ? static_cast<uint32_t>(machine->sd.revision) : 0;
}

// The Mega's EEPROM: its 4096 bytes, readable and writable; and its count of writes.
UV_EXPORT("printer_eeprom") uint8_t* printerEeprom() { return machine ? machine->eeprom.bytes : nullptr; }
UV_EXPORT("printer_eeprom_writes") uint32_t printerEepromWrites() { return machine ? machine->eeprom.writes : 0; }

// The Nano's start count (its own EEPROM): read, or set before a power cycle takes it one further.
UV_EXPORT("printer_starts") uint32_t printerStarts() { return machine ? machine->nano.startCount() : 0; }
UV_EXPORT("printer_set_starts") void printerSetStarts(uint32_t n) {
  if (machine && n < 65535) machine->nano.startCount(static_cast<uint16_t>(n));
}

// A job from the card exposing now: 0 none, 1 running, 2 running paced. And the exposures the
// Nano has fired by F since power-up.
UV_EXPORT("printer_card_job") uint32_t printerCardJob() {
  if (!machine || !machine->machine.cardJobRunning()) return 0;
  return machine->machine.jobPaced() ? 2 : 1;
}
UV_EXPORT("printer_fires") uint32_t printerFires() { return machine ? machine->nano.fired : 0; }
// The LEDs lit now, a bit mask.
UV_EXPORT("printer_lit") uint32_t printerLit() { return machine ? machine->nano.lit() : 0; }

// A command on a port as a host would send it, numbered and framed (a machine that runs on with
// no host listening takes its resume this way).
UV_EXPORT("printer_command") void printerCommand(uint32_t port) {
  if (machine) machine->send(inbox, port != 0);
}

// --- The panel ---

// Row `r` of the Mega's OLED as the firmware last wrote it; printer_display_draws counts the writes.
UV_EXPORT("printer_display_row") const char* printerDisplayRow(uint32_t r, uint32_t* n) {
  return give(machine && r < mega::kScreenRows ? machine->display.rows[r] : std::string(), n);
}
// The OLED's memory as the firmware's rows put it there: 8 pages of 128 columns, bit 0 the top
// pixel of each (the SSD1306's own layout), each character its 8 columns of the panel's font.
UV_EXPORT("printer_display_frame") const uint8_t* printerDisplayFrame() {
  static uint8_t frame[mega::kScreenRows * mega::kScreenCols * mega::kGlyphWidth];
  for (uint8_t r = 0; r < mega::kScreenRows; r++) {
    const std::string text = machine ? machine->display.rows[r] : std::string();
    for (uint8_t i = 0; i < mega::kScreenCols; i++) {
      char c = i < text.size() ? text[i] : ' ';
      for (uint8_t col = 0; col < mega::kGlyphWidth; col++)
        frame[(r * mega::kScreenCols + i) * mega::kGlyphWidth + col] = mega::glyphColumn(c, col);
    }
  }
  return frame;
}
UV_EXPORT("printer_display_draws") uint32_t printerDisplayDraws() {
  return machine ? static_cast<uint32_t>(machine->display.draws) : 0;
}
// The panel's buttons held down, as a bit mask (machine_io.h).
UV_EXPORT("printer_buttons") void printerButtons(uint32_t held) {
  if (machine) machine->io.pressed = static_cast<uint8_t>(held);
}

}  // extern "C"
