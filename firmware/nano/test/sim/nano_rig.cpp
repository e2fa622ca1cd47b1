// Test rig: runs the real printhead image (build/avr/nano.elf) in simavr and records, with CPU-cycle
// timestamps, its UART traffic, pin edges and how long interrupts stay off.
#include "nano_rig.h"

#include <simavr/avr_adc.h>
#include <simavr/avr_ioport.h>
#include <simavr/avr_uart.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_elf.h>
#include <simavr/sim_interrupts.h>

#include <stdexcept>

namespace {
constexpr int kUsartRxVector = 18;  // ATmega328P USART_RX_vect
void noSleep(avr_t*, avr_cycle_count_t) {}
}  // namespace

NanoRig::NanoRig(const std::string& elf) {
  elf_firmware_t fw = {};
  if (elf_read_firmware(elf.c_str(), &fw) != 0) throw std::runtime_error("cannot read " + elf);
  avr_ = avr_make_mcu_by_name("atmega328p");
  if (!avr_) throw std::runtime_error("simavr has no atmega328p");
  avr_init(avr_);
  avr_->frequency = 16000000;
  avr_->vcc = avr_->avcc = avr_->aref = 5000;
  avr_load_firmware(avr_, &fw);
  avr_->sleep = noSleep;  // the firmware never sleeps; don't let simavr sleep in real time

  uint32_t flags = 0;  // no console echo, no sleeping while the firmware polls
  avr_ioctl(avr_, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  uartIn_ = avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
  avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT), onOutput, this);
  avr_irq_register_notify(avr_get_interrupt_irq(avr_, kUsartRxVector) + AVR_INT_IRQ_PENDING, onRxPending, this);

  for (int i = 0; i < 16; i++) pinRefs_[i] = {this, i};
  for (int bit = 0; bit < 6; bit++) {
    avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ('B'), bit), onPin, &pinRefs_[bit]);
  }
  avr_irq_register_notify(avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ('D'), 3), onPin, &pinRefs_[8 + 3]);
  for (int ch = 0; ch < 6; ch++) setMv(ch, 750);  // 25.0 °C
  setProbe(false);
}

NanoRig::~NanoRig() {
  // simavr 1.6 has no call that frees an avr_t completely; one rig per test keeps this small.
}

uint64_t NanoRig::cycle() const { return avr_->cycle; }

void NanoRig::onPin(avr_irq_t*, uint32_t value, void* param) {
  auto* ref = static_cast<PinRef*>(param);
  ref->rig->edges_[ref->index].push_back({ref->rig->avr_->cycle, value != 0});
}

void NanoRig::onOutput(avr_irq_t*, uint32_t value, void* param) {
  auto* rig = static_cast<NanoRig*>(param);
  rig->output.push_back({rig->avr_->cycle, static_cast<char>(value)});
}

void NanoRig::onRxPending(avr_irq_t*, uint32_t value, void* param) {
  auto* rig = static_cast<NanoRig*>(param);
  if (!value || rig->delivered_.empty()) return;
  char c = rig->delivered_.front();
  rig->delivered_.pop_front();
  rig->inFifo_--;
  if (c == '\n') rig->lineEnds.push_back(rig->avr_->cycle);
}

void NanoRig::feed() {
  // Keep simavr's receive FIFO topped up, so bytes arrive back to back.
  while (!pending_.empty() && inFifo_ < 4) {
    char c = pending_.front();
    pending_.pop_front();
    delivered_.push_back(c);
    inFifo_++;
    avr_raise_irq(uartIn_, static_cast<uint8_t>(c));
  }
}

void NanoRig::step() {
  feed();
  avr_run(avr_);
  bool off = !avr_->sreg[S_I];
  if (off && !wasOff_) offSince_ = avr_->cycle;
  if (off && avr_->cycle - offSince_ > maxInterruptsOff) maxInterruptsOff = avr_->cycle - offSince_;
  wasOff_ = off;
  if (avr_->state == cpu_Crashed || avr_->state == cpu_Done) throw std::runtime_error("simulated CPU stopped");
}

void NanoRig::runUs(double us) {
  uint64_t end = cycle() + static_cast<uint64_t>(us * kCyclesPerUs);
  while (cycle() < end) step();
}

std::vector<std::string> NanoRig::takeLines() {
  std::vector<std::string> lines;
  for (; linesTaken_ < output.size(); linesTaken_++) {
    char c = output[linesTaken_].c;
    if (c == '\n') {
      lines.push_back(partial_);
      partial_.clear();
    } else {
      partial_ += c;
    }
  }
  return lines;
}

void NanoRig::setMv(int channel, int mv) {
  avr_raise_irq(avr_io_getirq(avr_, AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_ADC0 + channel), static_cast<uint32_t>(mv));
}

void NanoRig::hangAt(uint32_t byteAddress) { avr_->pc = byteAddress; }

void NanoRig::setProbe(bool high) { avr_raise_irq(avr_io_getirq(avr_, AVR_IOCTL_IOPORT_GETIRQ('D'), 7), high ? 1 : 0); }

void NanoRig::clearEdges() {
  for (auto& e : edges_) e.clear();
}

bool NanoRig::level(char port, int bit) const {
  const auto& e = edges(port, bit);
  return !e.empty() && e.back().high;
}
