// Host tests' and the simulated printer's SD card, in memory: what the card durably holds, by name
// in the order a directory lists it, and each open file's own copy. What is written stays in that
// copy until sync() or close(), as in SdFat's block cache, so powerCut() loses exactly what a real
// card would. No file system: it builds for WebAssembly too.
#pragma once
#include <stdio.h>
#include <string.h>

#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "storage.h"

namespace mega {

class FakeStorage : public Storage {
 public:
  static constexpr uint8_t kHandles = kCardFiles;  // as many as the board's card (storage.h)

  bool inserted = true;
  long failWritesAfter = -1;  // bytes the card still takes before every write fails; -1 = never
  std::string refuseWritesTo;  // a file whose name ends in this refuses every write (a bad block under it)

  bool present() override { return inserted; }

  FileHandle open(const char* name, Mode mode) override {
    if (!inserted) return -1;
    for (FileHandle h = 0; h < kHandles; h++) {
      File& f = files_[h];
      if (f.open) continue;
      auto there = card_.find(name);
      if (mode == Mode::Read && there == card_.end()) return -1;
      f = File{};
      f.open = true;
      f.name = name;
      f.writable = mode != Mode::Read;
      if (mode != Mode::Create && there != card_.end()) f.data.assign(there->second.begin(), there->second.end());
      f.dirty = mode == Mode::Create;
      return h;
    }
    return -1;
  }

  int16_t read(FileHandle h, char* buf, uint16_t n) override {
    File* f = file(h);
    if (!f) return -1;
    size_t left = f->pos < f->data.size() ? f->data.size() - f->pos : 0;
    size_t k = n < left ? n : left;
    if (k) memcpy(buf, f->data.data() + f->pos, k);
    f->pos += k;
    return static_cast<int16_t>(k);
  }

  bool write(FileHandle h, const char* buf, uint16_t n) override {
    File* f = file(h);
    if (!f || !f->writable) return false;
    if (!refuseWritesTo.empty() && f->name.size() >= refuseWritesTo.size() &&
        f->name.compare(f->name.size() - refuseWritesTo.size(), refuseWritesTo.size(), refuseWritesTo) == 0)
      return false;
    if (failWritesAfter >= 0) {
      if (failWritesAfter < n) return false;
      failWritesAfter -= n;
    }
    if (n == 0) return true;
    if (f->data.size() < f->pos + n) f->data.resize(f->pos + n);
    memcpy(f->data.data() + f->pos, buf, n);
    f->pos += n;
    f->dirty = true;
    bytesWritten += n;
    return true;
  }

  bool seek(FileHandle h, uint32_t pos) override {
    File* f = file(h);
    if (!f || pos > f->data.size()) return false;
    f->pos = pos;
    return true;
  }
  uint32_t size(FileHandle h) override {
    File* f = file(h);
    return f ? static_cast<uint32_t>(f->data.size()) : 0;
  }
  bool sync(FileHandle h) override {
    File* f = file(h);
    if (!f) return false;
    if (f->dirty) {
      card_[f->name].assign(f->data.data(), f->data.size());
      f->dirty = false;
      syncs++;
      revision++;
    }
    return true;
  }
  void close(FileHandle h) override {
    if (!file(h)) return;
    sync(h);
    files_[h].open = false;
  }
  bool exists(const char* name) override { return inserted && card_.count(name); }
  bool remove(const char* name) override {
    if (!inserted || !card_.erase(name)) return false;
    revision++;
    return true;
  }
  bool rename(const char* from, const char* to) override {
    if (!inserted || !exists(from) || exists(to)) return false;
    card_[to] = std::move(card_[from]);
    card_.erase(from);
    revision++;
    return true;
  }
  bool entry(uint16_t index, char* name, uint32_t& size) override {
    if (!inserted || index >= card_.size()) return false;
    auto it = card_.begin();
    std::advance(it, index);
    snprintf(name, kFileNameMax + 1, "%s", it->first.c_str());
    size = static_cast<uint32_t>(it->second.size());
    return true;
  }

  uint8_t* scratch() override { return scratch_; }

  // Power fails: every open file loses what was written since its last sync.
  void powerCut() {
    for (File& f : files_) f.open = false;
  }
  uint8_t openFiles() const {
    uint8_t n = 0;
    for (const File& f : files_) n += f.open;
    return n;
  }
  // What the card durably holds.
  std::string contents(const std::string& name) const {
    auto f = card_.find(name);
    return f == card_.end() ? std::string() : f->second;
  }
  void put(const std::string& name, const std::string& text) {
    card_[name] = text;
    revision++;
  }
  long bytesWritten = 0;
  long revision = 0;  // counts every change of what the card durably holds
  long syncs = 0;

 private:
  struct File {
    bool open = false, writable = false, dirty = false;
    std::string name;
    std::vector<char> data;
    size_t pos = 0;
  };
  File* file(FileHandle h) { return h >= 0 && h < kHandles && files_[h].open && inserted ? &files_[h] : nullptr; }
  std::map<std::string, std::string> card_;  // what the card durably holds, by name
  File files_[kHandles];
  uint8_t scratch_[kScratchBytes];
};

}  // namespace mega
