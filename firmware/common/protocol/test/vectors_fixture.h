// Test-only: loads protocol/vectors/*.json, turns its strings into bytes, and counts checked cases.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace uvtest {

using json = nlohmann::json;

// UV_VECTORS_DIR in the environment overrides the built-in path (scripts/check-vectors-bind.py).
inline std::string vectorsDir() {
  const char* env = std::getenv("UV_VECTORS_DIR");
  return env ? env : UV_VECTORS_DIR;
}

inline json loadVectors(const std::string& file) {
  std::ifstream in(vectorsDir() + "/" + file);
  if (!in) throw std::runtime_error("cannot open vectors " + file);
  return json::parse(in);
}

// Vector strings stand for bytes: each code point 0-255 is one byte (Latin-1).
inline std::string bytes(const json& s) {
  const std::string utf8 = s.get<std::string>();
  std::string out;
  for (size_t i = 0; i < utf8.size(); i++) {
    unsigned char c = static_cast<unsigned char>(utf8[i]);
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if ((c & 0xE0) == 0xC0 && i + 1 < utf8.size()) {
      out += static_cast<char>(((c & 0x1F) << 6) | (static_cast<unsigned char>(utf8[++i]) & 0x3F));
    } else {
      throw std::runtime_error("vector string has a code point over 255");
    }
  }
  return out;
}

// Prints how many cases a file checked when the test program ends.
struct VectorCounter {
  explicit VectorCounter(const char* f) : file(f) {}
  ~VectorCounter() { std::printf("[vectors] %s: %d cases checked (C++)\n", file, n); }
  void operator()() { n++; }
  const char* file;
  int n = 0;
};

}  // namespace uvtest
