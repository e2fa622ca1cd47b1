// A board's chip in simavr with its fuses and lock bits as Arduino ships them (boards-as-shipped.json),
// its UART on stdio: what the browser's flasher and avrdude meet at the end of a USB cable
// (e2e/bootloader-rig.ts, scripts/rig-pty.py, bench/flash.bench.ts).
//
//   bootloader_rig --board nano|mega --boot optiboot_atmega328.hex [--app nano.hex]
//
// The board's unkind parts, from its fuses: a reset starts the boot section (BOOTRST) at its fused size
// (BOOTSZ), not where the bootloader happens to begin; the chip stays in reset for the DTR pulse through
// the 100 nF capacitor and then the start-up time-out (14 CK + 65 ms), and drops what arrives meanwhile;
// the lock bits refuse SPM page erases and writes into the boot section; each page erase and write keeps
// SPMEN busy for its programming time. Internal pull-ups are simavr's own (an input pin whose PORT bit is
// set reads high, once the rig has cleared simavr's memory of the pins at each reset).
//
// stdin carries framed messages from the host, since a cable carries more than bytes:
//   'D' n b1..bn   n bytes (1..255) on the wire to the chip's RX, at the host's baud
//   'B' b0..b3     the host opened the port at this baud (little endian)
//   'R'            DTR pulsed low: the auto-reset capacitor resets the chip (external reset)
// stdout carries the chip's TX bytes, as they are sent. The run is paced to the wall clock (a
// bootloader's time-outs are real time to the host), and ends when stdin closes.
#include <poll.h>
#include <simavr/avr_adc.h>
#include <simavr/avr_flash.h>
#include <simavr/avr_ioport.h>
#include <simavr/avr_uart.h>
#include <simavr/sim_avr.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <string>
#include <vector>

#include "rig_frames.h"
#include "shipped_boards.h"

namespace {

// MCUSR is at I/O 0x34 (data 0x54) on both the ATmega328P and the ATmega2560.
constexpr uint16_t kMcusr = 0x54;
constexpr uint8_t kPorf = 1 << 0, kExtrf = 1 << 1;
// SPMCSR is at I/O 0x37 (data 0x57) on both; SPMEN, PGERS, PGWRT are its bits 0..2.
constexpr uint16_t kSpmcsr = 0x57;
constexpr uint8_t kSpmen = 1 << 0, kPgers = 1 << 1, kPgwrt = 1 << 2;

struct Rig {
  avr_t* avr = nullptr;
  avr_irq_t* rx = nullptr;
  uint32_t bootStart = 0;
  uint32_t hostBaud = 115200;
  bool xon = true;
  std::deque<uint8_t> wire;   // bytes the host sent, not yet at the chip's RX pin
  uint64_t nextRxCycle = 0;   // when the next one has crossed the wire
  // The chip's bytes with the cycle each has crossed the wire by: simavr 1.6 hands a byte written to
  // UDR out at once, so the rig keeps the line's pace (10 bits a byte at the host's baud).
  std::deque<std::pair<uint64_t, uint8_t>> tx;
  uint64_t txFree = 0;
  // avr_reset (ours, and the watchdog's inside simavr) starts avr->cycle again from 0: the rig's
  // clock is this base plus avr->cycle, so it never runs backwards.
  uint64_t cycleBase = 0;
  uint64_t lastCycle = 0;
  uv::ShippedBoard board;
  // In reset until this cycle (the DTR pulse, then the start-up time-out): the chip does not run.
  uint64_t heldUntil = 0;
  bool held = false;
  uint8_t heldCause = 0;  // what MCUSR says once the chip starts
  avr_io_t spmGuard{};
  // What the host did, in order, each at a chip time: as it arrives, except that what the host sent
  // after a reset's time-out is never put inside it. A rig running behind the wall clock (a loaded
  // machine) would otherwise squeeze a byte sent 100 ms after a reset into the 65 ms the chip is deaf;
  // a byte sent within them keeps its distance and is lost, as on a board. No event is delayed more,
  // so the rig's lag is never piled onto its answers.
  struct HostEvent {
    uint64_t at;
    char kind;  // 'D' one byte, 'B' baud, 'R' reset
    uint32_t value;
  };
  std::deque<HostEvent> events;
  uint64_t lastEventAt = 0;
  double resetWall = -1e9;  // when the last reset arrived, by the wall clock
  uint64_t resetAt = 0;     // and the chip time it was given
  avr_io_t* flash = nullptr;  // simavr's own self-programming module
};

Rig rig;

void noSleep(avr_t*, avr_cycle_count_t) {}

uint64_t now() {
  if (rig.avr->cycle < rig.lastCycle) rig.cycleBase += rig.lastCycle - rig.avr->cycle;
  rig.lastCycle = rig.avr->cycle;
  return rig.cycleBase + rig.avr->cycle;
}

// The chip's UART baud from UBRR0 and U2X0 (simavr does not compare it with the host's): a host at
// another baud meets framing garbage on a real board, here silence.
uint32_t chipBaud() {
  // UCSR0A, UBRR0L, UBRR0H: 0xC0, 0xC4, 0xC5 on both chips.
  uint16_t ubrr = rig.avr->data[0xC4] | ((rig.avr->data[0xC5] & 0x0f) << 8);
  bool u2x = rig.avr->data[0xC0] & 0x02;
  return static_cast<uint32_t>(rig.avr->frequency / ((u2x ? 8.0 : 16.0) * (ubrr + 1)));
}

bool baudsMatch() {
  double ratio = static_cast<double>(chipBaud()) / rig.hostBaud;
  return std::fabs(ratio - 1.0) < 0.035;  // what 8N1 tolerates between two ends
}

uint64_t byteCycles() { return static_cast<uint64_t>(rig.avr->frequency * 10.0 / rig.hostBaud); }

void onTx(avr_irq_t*, uint32_t value, void*) {
  if (!baudsMatch()) return;
  rig.txFree = std::max(rig.txFree, now()) + byteCycles();
  rig.tx.push_back({rig.txFree, static_cast<uint8_t>(value)});
}
void onXon(avr_irq_t*, uint32_t, void*) { rig.xon = true; }
void onXoff(avr_irq_t*, uint32_t, void*) { rig.xon = false; }

uint64_t msCycles(double ms) { return static_cast<uint64_t>(rig.avr->frequency * ms / 1000.0); }

// The DTR# edge: RESET low for the pulse, then the start-up time-out; the chip starts after both.
double wallSeconds();

uint64_t resetHoldCycles(bool pulse) {
  const auto delay = uv::resetDelay(rig.board.fuses);
  return msCycles((pulse ? uv::autoResetPulseMs(rig.board.capacitorNf, rig.board.pullUpOhms) : 0) + delay.ms) + delay.clocks;
}

// The chip time for an event arriving now (see HostEvent).
uint64_t arrivalCycle(bool reset) {
  const double wall = wallSeconds();
  uint64_t at = std::max(rig.lastEventAt, now());
  const auto distance = static_cast<uint64_t>((wall - rig.resetWall) * rig.avr->frequency);
  at = std::max(at, rig.resetAt + std::min(distance, resetHoldCycles(true) + msCycles(1)));
  if (reset) {
    rig.resetWall = wall;
    rig.resetAt = at;
  }
  return rig.lastEventAt = at;
}

void holdInReset(uint8_t cause, bool pulse);

void applyDueEvents() {
  while (!rig.events.empty() && rig.events.front().at <= now()) {
    const auto e = rig.events.front();
    rig.events.pop_front();
    if (e.kind == 'D') {
      if (rig.wire.empty() && rig.nextRxCycle < now()) rig.nextRxCycle = now() + byteCycles();
      rig.wire.push_back(static_cast<uint8_t>(e.value));
    } else if (e.kind == 'B') {
      rig.hostBaud = e.value;
    } else {
      holdInReset(kExtrf, true);
    }
  }
}

void holdInReset(uint8_t cause, bool pulse) {
  rig.held = true;
  rig.heldCause = cause;
  rig.heldUntil = now() + resetHoldCycles(pulse);
}

avr_cycle_count_t spmDone(avr_t* avr, avr_cycle_count_t, void*) {
  avr->data[kSpmcsr] &= static_cast<uint8_t>(~(kSpmen | kPgers | kPgwrt));
  return 0;
}

// Ahead of simavr's flash module (avr_ioctl asks the last registered first): page erases and writes
// into the locked boot section do nothing, as the lock bits make them; the others take their time.
int spmGuardIoctl(avr_io_t* port, uint32_t ctl, void* param) {
  avr_t* avr = port->avr;
  const uint8_t spmcsr = avr->data[kSpmcsr];
  if (ctl != AVR_IOCTL_FLASH_SPM || !(spmcsr & kSpmen) || !(spmcsr & (kPgers | kPgwrt))) return -1;
  uint32_t z = avr->data[30] | avr->data[31] << 8;
  if (avr->rampz) z |= static_cast<uint32_t>(avr->data[avr->rampz]) << 16;
  if (z >= uv::bootSectionStart(rig.board.chip, rig.board.fuses) && !uv::bootSectionWritable(rig.board.fuses)) {
    avr->data[kSpmcsr] &= static_cast<uint8_t>(~(kSpmen | kPgers | kPgwrt));
    return 0;
  }
  rig.flash->ioctl(rig.flash, ctl, param);
  avr->data[kSpmcsr] |= kSpmen;  // busy until programmed: boot_spm_busy_wait() polls this bit
  avr_cycle_timer_register(avr, msCycles(rig.board.chip.spmMs), spmDone, nullptr);
  return 0;
}

void resetChip(uint8_t cause) {
  now();
  avr_reset(rig.avr);
  now();
  // A reset makes every pin an input without its pull-up (PORTx and DDRx 0). simavr clears the
  // registers but its pin IRQs keep the values they last had, and it passes on only changes: a
  // firmware setting the same pull-ups as before the reset (INPUT_PULLUP on the Mega's stop button)
  // would leave the pin reading low, the button pressed, the machine halted (E13). Each start sets
  // them afresh, as the chip does.
  for (avr_io_t* io = rig.avr->io_port; io; io = io->next)
    if (io->kind && std::strcmp(io->kind, "port") == 0)
      for (int i = 0; i < IOPORT_IRQ_COUNT; i++) io->irq[i].value = 0;
  rig.avr->pc = rig.bootStart;
  rig.avr->data[kMcusr] = cause;
  avr_cycle_timer_cancel(rig.avr, spmDone, nullptr);
}

// Reads an Intel HEX file into flash. simavr's own reader refuses the start-address records (type 03)
// that Debian's bootloader images carry.
bool loadHex(const char* path, bool boot) {
  FILE* f = std::fopen(path, "r");
  if (!f) return false;
  char line[600];
  uint32_t base = 0, lowest = UINT32_MAX;
  bool ok = true;
  while (ok && std::fgets(line, sizeof line, f)) {
    if (line[0] != ':') continue;
    auto byteAt = [&](int i) { return static_cast<uint32_t>(std::strtoul(std::string(line + 1 + 2 * i, 2).c_str(), nullptr, 16)); };
    uint32_t count = byteAt(0), offset = byteAt(1) << 8 | byteAt(2), type = byteAt(3);
    if (type == 1) break;
    if (type == 2) base = (byteAt(4) << 8 | byteAt(5)) << 4;
    if (type == 4) base = (byteAt(4) << 8 | byteAt(5)) << 16;
    if (type != 0) continue;
    for (uint32_t i = 0; i < count; i++) {
      uint32_t at = base + offset + i;
      if (at > rig.avr->flashend) ok = false;
      else rig.avr->flash[at] = static_cast<uint8_t>(byteAt(4 + i));
    }
    if (base + offset < lowest) lowest = base + offset;
  }
  std::fclose(f);
  if (boot && lowest < rig.bootStart) {
    std::fprintf(stderr, "%s starts at 0x%x, below the boot section the fuses give (0x%x)\n", path, lowest, rig.bootStart);
    return false;
  }
  return ok && lowest != UINT32_MAX;
}

double wallSeconds() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec + t.tv_nsec * 1e-9;
}

void writeAll(const std::vector<uint8_t>& bytes) {
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t w = write(1, bytes.data() + done, bytes.size() - done);
    if (w <= 0) std::exit(0);  // the host went away
    done += static_cast<size_t>(w);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string board, boot, app;
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string flag = argv[i];
    if (flag == "--board") board = argv[i + 1];
    else if (flag == "--boot") boot = argv[i + 1];
    else if (flag == "--app") app = argv[i + 1];
  }
  if (boot.empty() || board.empty()) {
    std::fprintf(stderr, "usage: bootloader_rig --board <nano|mega> --boot <bootloader.hex> [--app <app.hex>]\n");
    return 2;
  }
  try {
    rig.board = uv::loadShippedBoard(BOARDS_AS_SHIPPED, board);
  } catch (const std::exception& e) {
    return std::fprintf(stderr, "%s\n", e.what()), 2;
  }
  const std::string& mcu = rig.board.mcu;
  rig.avr = avr_make_mcu_by_name(mcu.c_str());
  if (!rig.avr) return std::fprintf(stderr, "simavr has no %s\n", mcu.c_str()), 2;
  if (rig.avr->flashend + 1 != rig.board.chip.flashBytes) return std::fprintf(stderr, "simavr's %s has %u B of flash\n", mcu.c_str(), rig.avr->flashend + 1), 2;
  if (!uv::resetsToBootloader(rig.board.fuses)) return std::fprintf(stderr, "the %s's fuses do not start the bootloader\n", board.c_str()), 2;
  rig.bootStart = uv::bootSectionStart(rig.board.chip, rig.board.fuses);
  avr_init(rig.avr);
  rig.avr->frequency = 16000000;
  rig.avr->vcc = rig.avr->avcc = rig.avr->aref = 5000;
  rig.avr->log = 0;
  rig.avr->sleep = noSleep;  // else simavr sleeps in real time whenever a firmware polls its UART
  std::memset(rig.avr->flash, 0xff, rig.avr->flashend + 1);  // an erased chip
  if (!loadHex(boot.c_str(), true)) return std::fprintf(stderr, "cannot load %s\n", boot.c_str()), 2;
  if (!app.empty() && !loadHex(app.c_str(), false)) return std::fprintf(stderr, "cannot load %s\n", app.c_str()), 2;
  // BOOTRST: every reset, the watchdog's too, starts the boot section. Below a bootloader smaller than
  // the section (Optiboot's 512 B in the Nano's 2 KB), the erased words (0xFFFF, SBRS r31,7) run through to it.
  rig.avr->reset_pc = rig.bootStart;
  rig.avr->codeend = rig.avr->flashend;
  for (avr_io_t* io = rig.avr->io_port; io; io = io->next)
    if (io->kind && std::strcmp(io->kind, "flash") == 0) rig.flash = io;
  if (!rig.flash) return std::fprintf(stderr, "simavr's %s has no self-programming\n", mcu.c_str()), 2;
  rig.spmGuard.kind = "spm-guard";
  rig.spmGuard.ioctl = spmGuardIoctl;
  avr_register_io(rig.avr, &rig.spmGuard);

  uint32_t flags = 0;
  avr_ioctl(rig.avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  rig.rx = avr_io_getirq(rig.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
  avr_irq_register_notify(avr_io_getirq(rig.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), onTx, nullptr);
  avr_irq_register_notify(avr_io_getirq(rig.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON), onXon, nullptr);
  avr_irq_register_notify(avr_io_getirq(rig.avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF), onXoff, nullptr);
  // The Nano's sensors at 25 °C (750 mV), so its firmware starts without a thermal fault.
  if (mcu == "atmega328p")
    for (int ch = 0; ch < 6; ch++) avr_raise_irq(avr_io_getirq(rig.avr, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC0 + ch), 750);
  resetChip(kPorf);  // plugged in: power-on reset (its own time-out long past when a host first opens the port)

  uv::RigFrames frames;
  const double start = wallSeconds();
  const uint64_t slice = rig.avr->frequency / 2000;  // 0.5 ms of simulated time between looks at stdin
  uint8_t in[4096];
  for (;;) {
    uint64_t end = now() + slice;
    while (now() < end) {
      applyDueEvents();
      if (rig.held) {
        // In reset: time passes, the chip does not run, and what crosses the wire meanwhile is lost.
        uint64_t until = std::min(end, rig.heldUntil);
        if (!rig.events.empty()) until = std::min(until, std::max(now(), rig.events.front().at));
        while (!rig.wire.empty() && rig.nextRxCycle <= until) {
          rig.wire.pop_front();
          rig.nextRxCycle += byteCycles();
        }
        rig.cycleBase += until - now();
        if (until >= rig.heldUntil) {
          rig.held = false;
          resetChip(rig.heldCause);
        }
        continue;
      }
      if (!rig.wire.empty() && rig.xon && now() >= rig.nextRxCycle) {
        uint8_t b = rig.wire.front();
        rig.wire.pop_front();
        if (baudsMatch()) avr_raise_irq(rig.rx, b);
        rig.nextRxCycle = now() + byteCycles();
      }
      const avr_cycle_count_t before = rig.avr->cycle;
      int state = avr_run(rig.avr);
      if (rig.avr->cycle < before) {
        // simavr reset the chip itself: the watchdog (Optiboot and stk500boot leave through it). The
        // time-out follows every reset, this one too.
        holdInReset(rig.avr->data[kMcusr], false);
        continue;
      }
      if (state == cpu_Crashed || state == cpu_Done) {
        // An erased word (0xFFFF) or a broken image: a real chip runs on through the erased flash into
        // the boot section; the bootloader then starts the application again, as it would there.
        rig.avr->state = cpu_Running;
        rig.avr->pc = rig.bootStart;
      }
    }
    std::vector<uint8_t> out;
    while (!rig.tx.empty() && rig.tx.front().first <= now()) {
      out.push_back(rig.tx.front().second);
      rig.tx.pop_front();
    }
    if (!out.empty()) writeAll(out);
    // Ahead of the wall clock: wait for it, taking in what the host sends meanwhile; the chip sees
    // those bytes once its time has caught up, as it would on a real line.
    for (;;) {
      double ahead = static_cast<double>(now()) / rig.avr->frequency - (wallSeconds() - start);
      pollfd p{0, POLLIN, 0};
      int ready = poll(&p, 1, ahead > 0 ? static_cast<int>(std::ceil(ahead * 1000)) : 0);
      if (ready <= 0) break;
      ssize_t n = read(0, in, sizeof in);
      if (n <= 0) return 0;  // the host closed the port for good
      frames.feed(in, static_cast<size_t>(n), [](const uv::RigFrame& f) {
        const uint64_t at = arrivalCycle(f.kind == 'R');
        if (f.kind == 'D')
          for (uint8_t b : f.bytes) rig.events.push_back({at, 'D', b});
        else
          rig.events.push_back({at, f.kind, f.kind == 'B' ? f.baud : 0});
      });
      if (ahead <= 0) break;
    }
  }
}
