// The JSON view print_request.h and the bridge expect, over ArduinoJson 7 (the host tests use
// nlohmann through the same interface: nlohmann_view.h).
#pragma once
#include <ArduinoJson.h>
#include <string.h>

#include "json_numbers.h"

namespace uv {
namespace esp {

struct JsonView {
  JsonVariantConst v;
  bool isObject() const { return v.is<JsonObjectConst>(); }
  bool isArray() const { return v.is<JsonArrayConst>(); }
  bool isString() const { return v.is<const char*>(); }
  // true or false only: ArduinoJson's is<bool>() holds for neither null nor 0 and 1.
  bool isBoolean() const { return v.is<bool>(); }
  bool boolean() const { return v.as<bool>(); }
  // An integer that int64 holds, 128 and 128.0 alike, as in the schema validator; a number out
  // of that range is refused, never wrapped or cast (json_numbers.h). integer() is only asked of
  // those.
  bool isInteger() const {
    int64_t i;
    return asInt64(i);
  }
  int64_t integer() const {
    int64_t i = 0;
    asInt64(i);
    return i;
  }
  bool asInt64(int64_t& out) const {
    // is<int64_t>() is true only for an integer that fits; is<uint64_t>() for one over INT64_MAX.
    if (v.is<int64_t>()) return out = v.as<int64_t>(), true;
    if (v.is<uint64_t>()) return exactInt64(static_cast<uint64_t>(v.as<uint64_t>()), out);
    if (v.is<double>()) return exactInt64(v.as<double>(), out);
    return false;
  }
  const char* string() const { return v.as<const char*>(); }
  size_t size() const { return v.size(); }
  JsonView element(size_t i) const { return JsonView{v[i]}; }
  // Present, even as null (ArduinoJson reads a missing member and a null one alike).
  bool has(const char* key) const {
    for (JsonPairConst p : v.as<JsonObjectConst>())
      if (strcmp(p.key().c_str(), key) == 0) return true;
    return false;
  }
  JsonView member(const char* key) const { return JsonView{v[key]}; }
  template <class F>
  void forEachKey(F f) const {
    for (JsonPairConst p : v.as<JsonObjectConst>())
      if (!f(p.key().c_str())) return;
  }
};

// Caps what one parse may take from the heap: a body's header is under 1 KB of JSON, so a
// request that stuffs unknown fields gets NoMemory (400) instead of starving the Wi-Fi stack.
class CappedAllocator : public ArduinoJson::Allocator {
 public:
  explicit CappedAllocator(size_t cap) : cap_(cap) {}
  void* allocate(size_t n) override {
    if (used_ + n > cap_) return nullptr;
    uint64_t* h = static_cast<uint64_t*>(malloc(n + sizeof(uint64_t)));  // 8-byte header keeps 8-byte alignment
    if (!h) return nullptr;
    *h = n;
    used_ += n;
    return h + 1;
  }
  void deallocate(void* p) override {
    if (!p) return;
    uint64_t* h = static_cast<uint64_t*>(p) - 1;
    used_ -= static_cast<size_t>(*h);
    free(h);
  }
  void* reallocate(void* p, size_t n) override {
    if (!p) return allocate(n);
    uint64_t* h = static_cast<uint64_t*>(p) - 1;
    size_t old = static_cast<size_t>(*h);
    if (used_ - old + n > cap_) return nullptr;
    uint64_t* q = static_cast<uint64_t*>(realloc(h, n + sizeof(uint64_t)));
    if (!q) return nullptr;
    *q = n;
    used_ = used_ - old + n;
    return q + 1;
  }

 private:
  size_t cap_;
  size_t used_ = 0;
};

}  // namespace esp
}  // namespace uv
