// The host's spooled body (a file) and header parse (nlohmann), for PrintIntake in the host tests
// and the host hub: what FileBody and ArduinoJson are on the ESP.
#pragma once
#include <stdio.h>

#include <string>

#include "flash_gate.h"
#include "host_flash.h"
#include "nlohmann_view.h"

namespace uvtest {

// Read a block at a time, as FileBody is; with a flash model (the host hub), each open, block and
// close is one flash operation of loop()'s, made with the gate held (flash_gate.h), and it yields.
class HostBody {
 public:
  explicit HostBody(std::string path, HostFlash* flash = nullptr, uv::esp::FlashGate* gate = nullptr)
      : path_(std::move(path)), flash_(flash), gate_(gate) {}
  ~HostBody() { close(); }
  bool rewind() {
    close();
    return onFlash([&] { return (f_ = fopen(path_.c_str(), "rb")) != nullptr; });
  }
  void close() {
    if (f_) onFlash([&] { return fclose(f_); });
    f_ = nullptr;
    at_ = len_ = 0;
  }
  int read() {
    if (at_ == len_) {
      if (!f_) return -1;
      len_ = onFlash([&] { return fread(buf_, 1, sizeof buf_, f_); });
      at_ = 0;
      if (!len_) return -1;
    }
    return buf_[at_++];
  }
  const std::string& path() const { return path_; }

 private:
  template <class F>
  auto onFlash(F f) -> decltype(f()) {
    if (!flash_) return f();
    uv::esp::FlashGate::Hold hold(*gate_);
    return flash_->loopOperation(f);
  }

  std::string path_;
  HostFlash* flash_;
  uv::esp::FlashGate* gate_;
  FILE* f_ = nullptr;
  unsigned char buf_[512];
  size_t at_ = 0, len_ = 0;
};

// Parses the whole body without gridData's contents, as ArduinoJson's filtered parse does.
struct HostHeaderParse {
  size_t maxHeader = 8192;  // the ESP's cap on what the header parse may take
  template <class F>
  int operator()(HostBody& body, F use) const {
    std::string text;
    if (!body.rewind()) return 400;
    for (int c; (c = body.read()) >= 0;) text += static_cast<char>(c);
    nlohmann::json header = parseWithoutGridData(text);
    if (header.is_discarded()) return 400;
    if (header.dump().size() > maxHeader) return 413;
    use(View{&header});
    return 0;
  }
};

}  // namespace uvtest
