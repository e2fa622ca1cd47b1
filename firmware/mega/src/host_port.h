// One host-facing serial port (USB or ESP): line splitting, acceptance and reply output.
#pragma once
#include <Arduino.h>

#include "dialect_receiver.h"
#include "line_splitter.h"

class Executor {
 public:
  // Runs an accepted command; it must write its payload lines and end with port.ok().
  virtual void execute(const uv::Frame& frame, class HostPort& port) = 0;
};

class HostPort : public uv::ReplySink, public uv::FlowCounters {
 public:
  explicit HostPort(Stream& stream) : stream_(stream), receiver_(*this), splitter_(line_, uv::kDialectMaxLine) {}

  // Reads what has arrived and handles complete lines; never waits.
  void poll(Executor& exec);

  void line(const char* text) override;
  // Ends the reply block of the line being executed (protocol/mega.md §2).
  void ok() {
    receiver_.markAnswered(answering_);
    receiver_.ok(*this, answering_);
  }
  void error(uint8_t code, const char* detail = nullptr);

  uint8_t movesFree() const override { return 8; }
  uint8_t windowFree() const override { return 8; }

 private:
  Stream& stream_;
  uv::LineReceiver receiver_;
  char line_[uv::kDialectMaxLine + 1];
  uv::LineSplitter splitter_;
  int32_t answering_ = -1;  // the number of the line being executed, -1 for a plain line
};
