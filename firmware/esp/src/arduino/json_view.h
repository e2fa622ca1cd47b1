// The JSON view print_request.h and the bridge expect, over ArduinoJson 7 (the host tests use
// nlohmann through the same interface: nlohmann_view.h).
#pragma once
#include <ArduinoJson.h>
#include <string.h>

namespace uv {
namespace esp {

struct JsonView {
  JsonVariantConst v;
  bool isObject() const { return v.is<JsonObjectConst>(); }
  bool isArray() const { return v.is<JsonArrayConst>(); }
  bool isString() const { return v.is<const char*>(); }
  // 128 and 128.0 alike, as in the schema validator.
  bool isInteger() const {
    if (v.is<int64_t>() || v.is<uint64_t>()) return true;
    if (!v.is<double>()) return false;
    double d = v.as<double>();
    return d > -9.2e18 && d < 9.2e18 && d == static_cast<double>(static_cast<int64_t>(d));
  }
  int64_t integer() const {
    if (v.is<int64_t>()) return v.as<int64_t>();
    if (v.is<uint64_t>()) return static_cast<int64_t>(v.as<uint64_t>());
    return static_cast<int64_t>(v.as<double>());
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
