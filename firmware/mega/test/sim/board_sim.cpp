// Test rig: the real Mega and Nano images in one simavr process, wired as on the machine.
#include "board_sim.h"

#include <simavr/avr_adc.h>
#include <gelf.h>
#include <libelf.h>
#include <fcntl.h>
#include <simavr/avr_ioport.h>
#include <simavr/avr_twi.h>
#include <unistd.h>
#include <simavr/avr_uart.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_interrupts.h>

#include <stdexcept>

namespace {
// Receive-complete vectors: the rig counts a byte as taken when its interrupt is raised.
constexpr int kMegaUsart0Rx = 25, kMegaUsart1Rx = 36, kMegaUsart2Rx = 51, kNanoUsartRx = 18;
// The ATmega2560's last RAM address, and what the rig paints the free RAM with at power-up.
constexpr uint16_t kMegaRamEnd = 0x21ff;
constexpr uint8_t kPaint = 0xa5;
constexpr int kMegaTwiVector = 39;
void noSleep(avr_t*, avr_cycle_count_t) {}

// The address of the first symbol whose name starts with `prefix` (LTO may add a suffix), or 0:
// a function's, or with `anyType` any symbol's (the linker's `_end`, in the data space at 0x800000).
uint32_t symbolAddress(const std::string& elfPath, const std::string& prefix, bool anyType = false) {
  uint32_t found = 0;
  elf_version(EV_CURRENT);
  int fd = open(elfPath.c_str(), O_RDONLY);
  if (fd < 0) return 0;
  Elf* e = elf_begin(fd, ELF_C_READ, nullptr);
  for (Elf_Scn* scn = nullptr; e && !found && (scn = elf_nextscn(e, scn));) {
    GElf_Shdr sh;
    if (!gelf_getshdr(scn, &sh) || sh.sh_type != SHT_SYMTAB) continue;
    Elf_Data* data = elf_getdata(scn, nullptr);
    for (size_t i = 0; data && i < sh.sh_size / sh.sh_entsize; i++) {
      GElf_Sym sym;
      gelf_getsym(data, static_cast<int>(i), &sym);
      const char* name = elf_strptr(e, sh.sh_link, sym.st_name);
      if (name && (anyType || GELF_ST_TYPE(sym.st_info) == STT_FUNC) && std::string(name).rfind(prefix, 0) == 0) {
        found = static_cast<uint32_t>(sym.st_value);
        break;
      }
    }
  }
  if (e) elf_end(e);
  close(fd);
  return found;
}

uint16_t stackPointer(const avr_t* avr) { return static_cast<uint16_t>(avr->data[R_SPL] | avr->data[R_SPH] << 8); }

int runningVector(const avr_t* avr) {
  const auto& in = avr->interrupts;
  return in.running_ptr ? in.running[in.running_ptr - 1]->vector : 0;
}

avr_t* boot(const std::string& elf, const char* mcu) {
  elf_firmware_t fw = {};
  if (elf_read_firmware(elf.c_str(), &fw) != 0) throw std::runtime_error("cannot read " + elf);
  avr_t* avr = avr_make_mcu_by_name(mcu);
  if (!avr) throw std::runtime_error(std::string("simavr has no ") + mcu);
  avr_init(avr);
  avr->frequency = 16000000;
  avr->vcc = avr->avcc = avr->aref = 5000;
  avr_load_firmware(avr, &fw);
  avr->sleep = noSleep;
  return avr;
}

void quiet(avr_t* avr, char uart) {
  uint32_t flags = 0;  // no console echo, no real-time sleeping while the firmware polls
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS(uart), &flags);
}
}  // namespace

void BoardSim::Feed::push() {
  while (!pending.empty() && inFifo < 4) {
    char c = pending.front();
    pending.pop_front();
    inFifo++;
    avr_raise_irq(in, static_cast<uint8_t>(c));
  }
}

BoardSim::BoardSim(const std::string& megaElf, const std::string& nanoElf) {
  mega_ = boot(megaElf, "atmega2560");
  nano_ = boot(nanoElf, "atmega328p");
  for (char u : {'0', '1', '2', '3'}) quiet(mega_, u);
  quiet(nano_, '0');

  host_ = {mega_, avr_io_getirq(mega_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT), {}, 0};
  esp_ = {mega_, avr_io_getirq(mega_, AVR_IOCTL_UART_GETIRQ('2'), UART_IRQ_INPUT), {}, 0};
  avr_irq_register_notify(avr_io_getirq(mega_, AVR_IOCTL_UART_GETIRQ('2'), UART_IRQ_OUTPUT), onEspOut, this);
  avr_irq_register_notify(avr_get_interrupt_irq(mega_, kMegaUsart2Rx) + AVR_INT_IRQ_PENDING, onRxTaken, &esp_);
  toMega_ = {mega_, avr_io_getirq(mega_, AVR_IOCTL_UART_GETIRQ('1'), UART_IRQ_INPUT), {}, 0};
  toNano_ = {nano_, avr_io_getirq(nano_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT), {}, 0};
  avr_irq_register_notify(avr_io_getirq(mega_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), onHostOut, this);
  avr_irq_register_notify(avr_io_getirq(mega_, AVR_IOCTL_UART_GETIRQ('1'), UART_IRQ_OUTPUT), onMegaToNano, this);
  avr_irq_register_notify(avr_io_getirq(nano_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), onNanoToMega, this);
  avr_irq_register_notify(avr_get_interrupt_irq(mega_, kMegaUsart0Rx) + AVR_INT_IRQ_PENDING, onRxTaken, &host_);
  avr_irq_register_notify(avr_get_interrupt_irq(mega_, kMegaUsart1Rx) + AVR_INT_IRQ_PENDING, onRxTaken, &toMega_);
  avr_irq_register_notify(avr_get_interrupt_irq(nano_, kNanoUsartRx) + AVR_INT_IRQ_PENDING, onRxTaken, &toNano_);

  // CNC shield: X/Y/Z step on PE4, PE5, PG5; direction on PE3, PH3, PH4; endstops on PH6, PB4, PB5.
  const char stepPort[3] = {'E', 'E', 'G'}, dirPort[3] = {'E', 'H', 'H'}, switchPort[3] = {'H', 'B', 'B'};
  const int stepBit[3] = {4, 5, 5}, dirBit[3] = {3, 3, 4}, switchBit[3] = {6, 4, 5};
  for (int a = 0; a < 3; a++) {
    axisRefs_[a] = {this, a};
    avr_irq_register_notify(avr_io_getirq(mega_, AVR_IOCTL_IOPORT_GETIRQ(stepPort[a]), stepBit[a]), onStep, &axisRefs_[a]);
    avr_irq_register_notify(avr_io_getirq(mega_, AVR_IOCTL_IOPORT_GETIRQ(dirPort[a]), dirBit[a]), onDir, &axisRefs_[a]);
    switchIrq_[a] = avr_io_getirq(mega_, AVR_IOCTL_IOPORT_GETIRQ(switchPort[a]), switchBit[a]);
    avr_raise_irq(switchIrq_[a], 1);  // open: the pull-up holds it high
  }
  for (int k = 0; k < 4; k++) {  // the UV LEDs: PB2-PB5
    ledRefs_[k] = {this, k};
    avr_irq_register_notify(avr_io_getirq(nano_, AVR_IOCTL_IOPORT_GETIRQ('B'), 2 + k), onLed, &ledRefs_[k]);
  }
  for (int ch = 0; ch < 6; ch++) setNanoMv(ch, 750);  // 25.0 °C
  avr_raise_irq(avr_io_getirq(nano_, AVR_IOCTL_IOPORT_GETIRQ('D'), 7), 0);  // probe open

  // The SSD1306 on D20/D21: the model answers each byte with its acknowledge at once.
  twiIn_ = avr_io_getirq(mega_, AVR_IOCTL_TWI_GETIRQ(0), TWI_IRQ_INPUT);
  avr_irq_register_notify(avr_io_getirq(mega_, AVR_IOCTL_TWI_GETIRQ(0), TWI_IRQ_OUTPUT), onTwi, this);
  panelEntry_ = symbolAddress(megaElf, "_ZN4mega7Machine5panelEv");
  megaElf_ = megaElf;

  // The stack's high-water mark: every byte between the end of static RAM (the linker's _end; the
  // firmware has no heap) and the top of RAM is painted before the firmware runs, and the lowest
  // byte the stack ever wrote is found by the paint it left (stackDeepest()).
  staticEnd_ = static_cast<uint16_t>(symbolAddress(megaElf, "_end", true) & 0xffff);
  if (!staticEnd_) throw std::runtime_error("no _end symbol in " + megaElf);
  for (uint32_t a = staticEnd_; a <= kMegaRamEnd; a++) mega_->data[a] = kPaint;
}

uint16_t BoardSim::stackDeepest() const {
  uint16_t a = staticEnd_;
  while (a <= kMegaRamEnd && mega_->data[a] == kPaint) a++;
  return a;
}

uint16_t BoardSim::stackBytes() const { return static_cast<uint16_t>(kMegaRamEnd + 1 - stackDeepest()); }

void BoardSim::setNanoMv(int ch, uint32_t mv) {
  avr_raise_irq(avr_io_getirq(nano_, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC0 + ch), mv);
}

void BoardSim::onTwi(avr_irq_t*, uint32_t value, void* param) {
  auto* s = static_cast<BoardSim*>(param);
  avr_twi_msg_irq_t m;
  m.u.v = value;
  bool ack = false;
  if (m.u.twi.msg & TWI_COND_STOP) s->panel.stop();
  if (m.u.twi.msg & TWI_COND_START) ack = s->panel.start(m.u.twi.addr >> 1, m.u.twi.addr & 1);
  else if (m.u.twi.msg & TWI_COND_WRITE) ack = s->panel.write(m.u.twi.data);
  if (ack) avr_raise_irq(s->twiIn_, avr_twi_irq_msg(TWI_COND_ACK, m.u.twi.addr, 1));
}

void BoardSim::profilePanel(uint64_t cycles, bool wasInPanel, int wasVector) {
  if (wasVector == kMegaTwiVector) {
    passCycles_ += cycles;
    twiIsrCycles += cycles;
    isrRun_ += cycles;
  } else if (wasInPanel && wasVector == 0) {
    passCycles_ += cycles;
    callCycles_ += cycles;
  }
  int vector = runningVector(mega_);
  if (lastVector_ == kMegaTwiVector && vector != kMegaTwiVector) {
    if (isrRun_ > twiIsrMax) twiIsrMax = isrRun_;
    isrRun_ = 0;
  }
  lastVector_ = vector;
  if (inPanel_ && vector == 0 && stackPointer(mega_) > panelSp_) {  // returned
    inPanel_ = false;
    if (callCycles_ > panelCallMax) panelCallMax = callCycles_;
    callCycles_ = 0;
  }
  if (!inPanel_ && panelEntry_ && mega_->pc == panelEntry_) {  // a new pass's panel
    if (panelPasses && passCycles_ > panelPassMax) panelPassMax = passCycles_;
    panelPasses++;
    passCycles_ = 0;
    inPanel_ = true;
    panelSp_ = stackPointer(mega_);
  }
}

bool BoardSim::timeCalls(const std::string& symbol) {
  const uint32_t entry = symbolAddress(megaElf_, symbol);
  if (entry) timed_.push_back({symbol, entry});
  return entry != 0;
}

const std::vector<BoardSim::TimedCall>& BoardSim::timedCalls(const std::string& symbol) const {
  static const std::vector<TimedCall> none;
  for (const TimedFunction& f : timed_)
    if (f.symbol == symbol) return f.calls;
  return none;
}

bool BoardSim::inTimed() const {
  for (const TimedFunction& f : timed_)
    if (f.in) return true;
  return false;
}

void BoardSim::timeCall(uint64_t cycles, int wasVector) {
  const int vector = runningVector(mega_);
  for (TimedFunction& f : timed_) {
    if (f.in && wasVector == 0) f.calls.back().cycles += cycles;
    if (f.in && vector == 0 && stackPointer(mega_) > f.sp) {  // returned
      f.in = false;
      f.calls.back().to = mega_->cycle;
    }
    if (!f.in && vector == 0 && mega_->pc == f.entry) {
      f.in = true;
      f.sp = stackPointer(mega_);
      f.calls.push_back({0, mega_->cycle, 0});
    }
  }
}

uint64_t BoardSim::megaCycle() const { return mega_->cycle; }

void BoardSim::setSwitch(int a) {
  bool closed = pos[a] <= switchAt[a];
  if (closed == switchClosed_[a]) return;
  switchClosed_[a] = closed;
  avr_raise_irq(switchIrq_[a], closed ? 0 : 1);
}

void BoardSim::onStep(avr_irq_t*, uint32_t value, void* param) {
  auto* ref = static_cast<AxisRef*>(param);
  if (!value) return;  // count rising edges
  BoardSim* s = ref->sim;
  s->pos[ref->axis] += s->dirHigh[ref->axis] ? -1 : 1;  // direction pin high: towards the switch
  s->setSwitch(ref->axis);
  if (s->logging && ref->axis < 2) s->headSteps.push_back({s->mega_->cycle, s->pos[0], s->pos[1]});
}

void BoardSim::onLed(avr_irq_t*, uint32_t value, void* param) {
  auto* ref = static_cast<AxisRef*>(param);
  BoardSim* s = ref->sim;
  const bool on = value != 0;
  if (on == s->ledOn_[ref->axis]) return;  // a write that left the pin as it was
  s->ledOn_[ref->axis] = on;
  if (s->logging) s->ledEdges.push_back({static_cast<uint64_t>(static_cast<double>(s->nano_->cycle) / s->nanoClock), ref->axis, on});
}

void BoardSim::onDir(avr_irq_t*, uint32_t value, void* param) {
  auto* ref = static_cast<AxisRef*>(param);
  ref->sim->dirHigh[ref->axis] = value != 0;
}

namespace {
// A byte of a line-based link: the line it ends, or the partial line it extends.
template <class Lines>
void collect(char c, std::string& partial, Lines& lines) {
  if (c == '\n') {
    lines.push_back(partial);
    partial.clear();
  } else {
    partial += c;
  }
}
}  // namespace

void BoardSim::onEspOut(avr_irq_t*, uint32_t value, void* param) {
  auto* s = static_cast<BoardSim*>(param);
  collect(static_cast<char>(value), s->espPartial_, s->espLines_);
}

void BoardSim::onHostOut(avr_irq_t*, uint32_t value, void* param) {
  auto* s = static_cast<BoardSim*>(param);
  collect(static_cast<char>(value), s->hostPartial_, s->hostLines_);
}

void BoardSim::onMegaToNano(avr_irq_t*, uint32_t value, void* param) {
  auto* s = static_cast<BoardSim*>(param);
  s->toNano_.pending.push_back(static_cast<char>(value));
  if (s->nanoPartial_.empty()) s->nanoLineFirst.push_back(s->megaCycle());
  if (value == '\n') s->nanoLineLast.push_back(s->megaCycle());
  collect(static_cast<char>(value), s->nanoPartial_, s->nanoLines);
  if (s->logging && value == '\n') s->linkLines.push_back({s->megaCycle(), true, s->nanoLines.back()});
}

void BoardSim::onNanoToMega(avr_irq_t*, uint32_t value, void* param) {
  auto* s = static_cast<BoardSim*>(param);
  s->toMega_.pending.push_back(static_cast<char>(value));
  collect(static_cast<char>(value), s->replyPartial_, s->nanoReplies);
  if (s->logging && value == '\n') s->linkLines.push_back({s->megaCycle(), false, s->nanoReplies.back()});
}

void BoardSim::onRxTaken(avr_irq_t*, uint32_t value, void* param) {
  auto* f = static_cast<Feed*>(param);
  if (value && f->inFifo > 0) f->inFifo--;
}

void BoardSim::step() {
  host_.push();
  esp_.push();
  toMega_.push();
  toNano_.push();
  // Keep the two chips within an instruction of each other, the Nano at `nanoClock` of the Mega's rate.
  avr_t* next = static_cast<double>(mega_->cycle) * nanoClock <= static_cast<double>(nano_->cycle) ? mega_ : nano_;
  uint64_t before = next->cycle;
  bool wasInPanel = inPanel_, wasTimed = profileTimedOnly && inTimed();
  int wasVector = next == mega_ ? runningVector(mega_) : 0;
  const uint32_t pc = next->pc;
  avr_run(next);
  if (next == mega_) {
    if (megaProfile && (!profileTimedOnly || (wasTimed && wasVector == 0))) {
      if (megaProfile->size() <= pc / 2) megaProfile->resize(pc / 2 + 1);
      (*megaProfile)[pc / 2].cycles += next->cycle - before;
      (*megaProfile)[pc / 2].runs++;
    }
    profilePanel(next->cycle - before, wasInPanel, wasVector);
    if (!timed_.empty()) timeCall(next->cycle - before, wasVector);
    bool off = !mega_->sreg[S_I];
    if (off && !megaOff_) {
      megaOffSince_ = mega_->cycle;
      megaOffPc_ = mega_->pc;  // an interrupt's vector, or the code that cleared the flag
    }
    if (off && mega_->cycle - megaOffSince_ > megaMaxInterruptsOff) {
      megaMaxInterruptsOff = mega_->cycle - megaOffSince_;
      megaMaxOffPc = megaOffPc_;
    }
    megaOff_ = off;
  }
  if (next->state == cpu_Crashed || next->state == cpu_Done) throw std::runtime_error("a simulated CPU stopped");
}

void BoardSim::runUs(double us) {
  uint64_t end = megaCycle() + static_cast<uint64_t>(us * kCyclesPerUs);
  while (megaCycle() < end) step();
}

void BoardSim::send(const std::string& bytes) { host_.pending.insert(host_.pending.end(), bytes.begin(), bytes.end()); }

void BoardSim::sendEsp(const std::string& bytes) { esp_.pending.insert(esp_.pending.end(), bytes.begin(), bytes.end()); }

std::vector<std::string> BoardSim::takeEspLines() {
  std::vector<std::string> out(espLines_.begin(), espLines_.end());
  espLines_.clear();
  return out;
}

std::vector<std::string> BoardSim::takeLines() {
  std::vector<std::string> out(hostLines_.begin(), hostLines_.end());
  hostLines_.clear();
  return out;
}
