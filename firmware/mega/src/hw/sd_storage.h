// The SD card behind the Storage interface. Built with SdFat (PlatformIO's lib_deps, -DUV_WITH_SDFAT);
// without it (the Debian toolchain build, which cannot fetch SdFat), the card is absent and the
// Mega runs jobs in stream mode only, as it would with no card in the slot.
#pragma once
#include "storage.h"

#ifdef UV_WITH_SDFAT
#include <SdFat.h>
#endif

namespace mega {

class SdStorage : public Storage {
 public:
  static constexpr uint8_t kFiles = kCardFiles;  // storage.h

  // Mounts the card; false if there is none. Call again to retry after a card is inserted.
  bool begin(uint8_t csPin);
  bool present() override;
  FileHandle open(const char* name, Mode mode) override;
  int16_t read(FileHandle f, char* buf, uint16_t n) override;
  bool write(FileHandle f, const char* buf, uint16_t n) override;
  bool seek(FileHandle f, uint32_t pos) override;
  uint32_t size(FileHandle f) override;
  bool sync(FileHandle f) override;
  void close(FileHandle f) override;
  bool exists(const char* name) override;
  bool remove(const char* name) override;
  bool rename(const char* from, const char* to) override;
  bool entry(uint16_t index, char* name, uint32_t& size) override;
  uint8_t* scratch() override;

 private:
#ifdef UV_WITH_SDFAT
  FatFile* file(FileHandle f) { return f >= 0 && f < kFiles && files_[f].isOpen() ? &files_[f] : nullptr; }
  SdFat32 sd_;
  // FatFile, not File32: File32 adds Arduino's Stream (a vtable in RAM, a timeout, an error flag),
  // 12 bytes a file that nothing here uses.
  FatFile files_[kFiles];
#else
  uint8_t scratch_[kScratchBytes];  // without SdFat there is no sector cache to lend
#endif
  bool mounted_ = false;
};

}  // namespace mega
