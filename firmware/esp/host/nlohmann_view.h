// Test support: the JSON view print_request.h expects, over nlohmann (the ESP has an ArduinoJson
// one), and a header parse that leaves gridData out as the ESP's filtered parse does.
#pragma once
#include <nlohmann/json.hpp>

#include <istream>
#include <string>

#include "json_numbers.h"

namespace uvtest {

struct View {
  const nlohmann::json* j;
  bool isObject() const { return j->is_object(); }
  bool isArray() const { return j->is_array(); }
  bool isString() const { return j->is_string(); }
  bool isBoolean() const { return j->is_boolean(); }
  bool boolean() const { return j->get<bool>(); }
  // An integer that int64 holds (json_numbers.h); integer() is only asked of those.
  bool isInteger() const {
    int64_t v;
    return asInt64(v);
  }
  int64_t integer() const {
    int64_t v = 0;
    asInt64(v);
    return v;
  }
  bool asInt64(int64_t& out) const {
    if (j->is_number_unsigned()) return uv::esp::exactInt64(j->get<uint64_t>(), out);
    if (j->is_number_integer()) return out = j->get<int64_t>(), true;
    if (j->is_number_float()) return uv::esp::exactInt64(j->get<double>(), out);
    return false;
  }
  const char* string() const { return j->get_ref<const std::string&>().c_str(); }
  size_t size() const { return j->size(); }
  View element(size_t i) const { return View{&(*j)[i]}; }
  bool has(const char* k) const { return j->contains(k); }
  View member(const char* k) const { return View{&j->at(k)}; }
  template <class F>
  void forEachKey(F f) const {
    for (auto it = j->begin(); it != j->end(); ++it)
      if (!f(it.key().c_str())) return;
  }
};

// The body parsed with the root's gridData member dropped; discarded (is_discarded()) when the
// body is not JSON. The syntax of gridData is still checked, as ArduinoJson's filter does.
inline nlohmann::json parseWithoutGridData(const std::string& body) {
  bool inGrid = false;
  auto filter = [&](int depth, nlohmann::json::parse_event_t event, nlohmann::json& parsed) {
    if (event == nlohmann::json::parse_event_t::key && depth == 1) inGrid = parsed == "gridData";
    return !(inGrid && depth > 1);  // gridData's contents are checked but never held
  };
  nlohmann::json j = nlohmann::json::parse(body, filter, false);
  if (j.is_object()) j.erase("gridData");
  return j;
}

// The Reader of grid_rows.h over a stream.
struct StreamReader {
  std::istream& in;
  int read() {
    int c = in.get();
    return c == std::char_traits<char>::eof() ? -1 : c;
  }
  bool rewind() {
    in.clear();
    in.seekg(0);
    return static_cast<bool>(in);
  }
};

}  // namespace uvtest
