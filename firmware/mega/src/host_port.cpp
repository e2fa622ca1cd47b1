// One host-facing serial port (USB or ESP): line splitting, acceptance and reply output.
#include "host_port.h"

#include "error_codes.h"

void HostPort::poll(Executor& exec) {
  int budget = 64;  // bytes per call, so one busy port cannot starve the other
  while (budget-- > 0 && stream_.available()) {
    if (!splitter_.push(static_cast<char>(stream_.read()))) continue;
    uv::Frame frame;
    uv::Acceptance a = receiver_.accept(splitter_.text(), splitter_.length(), splitter_.overflow(), *this, frame);
    if (a == uv::Acceptance::Execute) {
      answering_ = frame.hasN ? static_cast<int32_t>(frame.n) : -1;
      exec.execute(frame, *this);
    }
  }
}

void HostPort::line(const char* text) {
  stream_.write(text, strlen(text));
  stream_.write('\n');
}

void HostPort::error(uint8_t code, const char* detail) {
  char buf[96];
  int n = snprintf(buf, sizeof buf, "Error:E%u ", code);
  uv::errorMessage(code, buf + n, static_cast<uint8_t>(sizeof buf - n));
  if (detail) {
    size_t k = strlen(buf);
    snprintf(buf + k, sizeof buf - k, ": %s", detail);
  }
  line(buf);
  ok();
}
