// The host's spooled body (a file) and header parse (nlohmann), for PrintIntake in the host tests
// and the host hub: what FileBody and ArduinoJson are on the ESP.
#pragma once
#include <stdio.h>

#include <string>

#include "nlohmann_view.h"

namespace uvtest {

class HostBody {
 public:
  explicit HostBody(std::string path) : path_(std::move(path)) {}
  ~HostBody() { close(); }
  bool rewind() {
    close();
    f_ = fopen(path_.c_str(), "rb");
    return f_ != nullptr;
  }
  void close() {
    if (f_) fclose(f_);
    f_ = nullptr;
  }
  int read() { return f_ ? fgetc(f_) : -1; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  FILE* f_ = nullptr;
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
