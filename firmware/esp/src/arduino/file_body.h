// A spooled file read a buffer at a time: the Reader of grid_rows.h and streamed_job_text.h, and
// a custom reader for ArduinoJson (read, readBytes). Each refill first runs `service`, so the
// Mega's UART and the clients keep being served while a 1.2 MB body is parsed. It is loop()'s:
// each of its calls into LittleFS holds the gate (flash_gate.h), since the flash may yield inside.
#pragma once
#include <Arduino.h>
#include <FS.h>

#include "flash_gate.h"

namespace uv {
namespace esp {

class FileBody {
 public:
  using Service = void (*)();
  FileBody(fs::FS& fs, const char* path, Service service, FlashGate& gate) : fs_(fs), path_(path), service_(service), gate_(gate) {}

  bool open() {
    close();
    FlashGate::Hold hold(gate_);
    file_ = fs_.open(path_, "r");
    at_ = len_ = 0;
    return static_cast<bool>(file_);
  }
  void close() {
    FlashGate::Hold hold(gate_);
    if (file_) file_.close();
  }
  bool rewind() { return open(); }
  size_t size() {
    FlashGate::Hold hold(gate_);
    return file_ ? file_.size() : 0;
  }

  int read() {
    if (at_ == len_ && !refill()) return -1;
    return buf_[at_++];
  }
  size_t readBytes(char* out, size_t n) {
    size_t k = 0;
    while (k < n) {
      int c = read();
      if (c < 0) break;
      out[k++] = static_cast<char>(c);
    }
    return k;
  }

 private:
  bool refill() {
    if (service_) service_();
    if (!file_) return false;
    FlashGate::Hold hold(gate_);
    int n = file_.read(buf_, sizeof buf_);
    at_ = 0;
    len_ = n > 0 ? static_cast<uint16_t>(n) : 0;
    return len_ > 0;
  }

  fs::FS& fs_;
  const char* path_;
  Service service_;
  FlashGate& gate_;
  fs::File file_;
  uint8_t buf_[512];
  uint16_t at_ = 0, len_ = 0;
};

}  // namespace esp
}  // namespace uv
