// The SD card behind the Storage interface, through SdFat (FAT16/FAT32 only: SdFat32 keeps the
// exFAT code and its RAM out of the image).
#include "hw/sd_storage.h"

#ifdef UV_WITH_SDFAT
#include <Arduino.h>
#include <SPI.h>
#endif

namespace mega {

#ifdef UV_WITH_SDFAT

namespace {

// SdFat gives a card SD_INIT_TIMEOUT (2 s, a constant a build cannot change) to answer CMD0 and
// leave idle, so with the slot empty the Mega said `start` after 2 s (3.8 s with U8x8's set-up
// too), and a host that waits 2 s gave up. A card answers CMD0 at once: it needs 1 ms and 74 clocks
// after its supply is up, and the bootloader has run by then. So the Mega asks first, for at most
// kProbeMs; only a card that answered goes through SdFat's begin, which keeps its full 2 s for
// ACMD41 (cards take up to about 1 s to leave idle).
constexpr uint32_t kProbeMs = 100;

bool cardAnswers(uint8_t csPin) {
  pinMode(csPin, OUTPUT);
  digitalWrite(csPin, HIGH);
  SPI.begin();
  SPI.beginTransaction(SPISettings(250000, MSBFIRST, SPI_MODE0));  // the init rate: at most 400 kHz
  for (uint8_t i = 0; i < 10; i++) SPI.transfer(0xff);              // 80 clocks with CS high
  digitalWrite(csPin, LOW);
  bool answered = false;
  uint32_t since = millis();
  do {
    SPI.transfer(0x40);  // CMD0, GO_IDLE_STATE: argument 0, then its CRC
    for (uint8_t i = 0; i < 4; i++) SPI.transfer(0);
    SPI.transfer(0x95);
    // R1 comes within 8 bytes. An empty slot reads 0xff (MISO pulled up); 0x00 is no R1 to CMD0
    // either (MISO held low), so neither counts: anything else is a card.
    for (uint8_t i = 0; i < 9 && !answered; i++) {
      uint8_t r1 = SPI.transfer(0xff);
      answered = !(r1 & 0x80) && r1 != 0;
    }
  } while (!answered && millis() - since < kProbeMs);
  digitalWrite(csPin, HIGH);
  SPI.transfer(0xff);  // let the card release MISO
  SPI.endTransaction();
  return answered;
}

}  // namespace

bool SdStorage::begin(uint8_t csPin) {
  mounted_ = cardAnswers(csPin) && sd_.begin(SdSpiConfig(csPin, DEDICATED_SPI, SD_SCK_MHZ(16)));
  return mounted_;
}

bool SdStorage::present() { return mounted_; }

FileHandle SdStorage::open(const char* name, Mode mode) {
  if (!mounted_) return -1;
  oflag_t flags = mode == Mode::Read ? O_RDONLY : mode == Mode::Create ? (O_RDWR | O_CREAT | O_TRUNC) : (O_RDWR | O_CREAT);
  for (FileHandle h = 0; h < kFiles; h++) {
    if (files_[h].isOpen()) continue;
    return files_[h].open(name, flags) ? h : -1;
  }
  return -1;
}

int16_t SdStorage::read(FileHandle f, char* buf, uint16_t n) {
  FatFile* file = this->file(f);
  return file ? static_cast<int16_t>(file->read(buf, n)) : -1;
}

bool SdStorage::write(FileHandle f, const char* buf, uint16_t n) {
  FatFile* file = this->file(f);
  return file && file->write(buf, n) == n;
}

bool SdStorage::seek(FileHandle f, uint32_t pos) {
  FatFile* file = this->file(f);
  return file && file->seekSet(pos);
}

uint32_t SdStorage::size(FileHandle f) {
  FatFile* file = this->file(f);
  return file ? file->fileSize() : 0;
}

bool SdStorage::sync(FileHandle f) {
  FatFile* file = this->file(f);
  return file && file->sync();
}

void SdStorage::close(FileHandle f) {
  FatFile* file = this->file(f);
  if (file) file->close();
}

bool SdStorage::exists(const char* name) { return mounted_ && sd_.exists(name); }
bool SdStorage::remove(const char* name) { return mounted_ && sd_.remove(name); }
bool SdStorage::rename(const char* from, const char* to) { return mounted_ && sd_.rename(from, to); }

bool SdStorage::entry(uint16_t index, char* name, uint32_t& size) {
  if (!mounted_) return false;
  FatFile root, file;
  if (!root.open("/")) return false;
  uint16_t i = 0;
  bool found = false;
  while (file.openNext(&root, O_RDONLY)) {
    bool listed = !file.isDir() && !file.isHidden();
    if (listed && i++ == index) {
      file.getName(name, kFileNameMax + 1);
      size = file.fileSize();
      found = true;
    }
    file.close();
    if (found) break;
  }
  root.close();
  return found;
}

uint8_t* SdStorage::scratch() {
  // The volume's sector cache, flushed and handed over: nothing may touch the card until the
  // stream ends (the Mega refuses card commands while one runs).
  // With no card mounted the cache is just as much there, and unused.
  return sd_.vol()->cacheClear();
}

#else  // no SdFat in this build: no card

bool SdStorage::begin(uint8_t) { return false; }
bool SdStorage::present() { return false; }
FileHandle SdStorage::open(const char*, Mode) { return -1; }
int16_t SdStorage::read(FileHandle, char*, uint16_t) { return -1; }
bool SdStorage::write(FileHandle, const char*, uint16_t) { return false; }
bool SdStorage::seek(FileHandle, uint32_t) { return false; }
uint32_t SdStorage::size(FileHandle) { return 0; }
bool SdStorage::sync(FileHandle) { return false; }
void SdStorage::close(FileHandle) {}
bool SdStorage::exists(const char*) { return false; }
bool SdStorage::remove(const char*) { return false; }
bool SdStorage::rename(const char*, const char*) { return false; }
bool SdStorage::entry(uint16_t, char*, uint32_t&) { return false; }
uint8_t* SdStorage::scratch() { return scratch_; }

#endif

}  // namespace mega
