// Fuzzes the Mega's settings as they load at start-up: any CONFIG.TXT on the card and any EEPROM
// copy. Holds: every value loaded is one M850 would take (its text form sets it back, in range);
// saved, the settings load back equal from the card and from the EEPROM alone.
#include <fuzzer/FuzzedDataProvider.h>

#include <string.h>

#include <string>

#include "config_store.h"
#include "eeprom_fake.h"
#include "fuzz_checks.h"
#include "storage_fake.h"

namespace {

void requireSettable(const mega::Config& c) {
  for (uint8_t i = 0; i < mega::kKeyCount; i++) {
    mega::Key k = static_cast<mega::Key>(i);
    char text[32];
    uint8_t n = c.format(k, text);
    mega::Config fresh;
    fresh.defaults();
    FUZZ_REQUIRE(fresh.set(k, text, n), ("a loaded value M850 would refuse: " + std::string(text, n)).c_str());
    FUZZ_REQUIRE(fresh.milli(k) == c.milli(k), ("a value that reads back as another: " + std::string(text, n)).c_str());
  }
}

void settle(mega::ConfigStore& store, mega::FakeEeprom& ee) {
  ee.busyPolls = 0;
  for (int i = 0; i < 4 * mega::ConfigStore::kImageSize && store.saving(); i++) store.poll();
  FUZZ_REQUIRE(!store.saving(), "the EEPROM copy never finished");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  mega::FakeStorage sd;
  mega::FakeEeprom ee;
  if (in.ConsumeBool()) {  // a damaged or foreign EEPROM copy
    std::string image = in.ConsumeBytesAsString(in.ConsumeIntegralInRange<size_t>(0, mega::ConfigStore::kImageSize));
    memcpy(ee.bytes, image.data(), image.size());
  }
  std::string file = in.ConsumeRemainingBytesAsString();
  mega::FileHandle f = sd.open("CONFIG.TXT", mega::Storage::Mode::Create);
  sd.write(f, file.data(), static_cast<uint16_t>(file.size() > 60000 ? 60000 : file.size()));
  sd.close(f);

  mega::Config loaded;
  mega::ConfigStore store(loaded, sd, ee);
  store.load();
  requireSettable(loaded);

  FUZZ_REQUIRE(store.save() == 0, "the card refused CONFIG.TXT");
  settle(store, ee);
  mega::Config fromCard;
  mega::ConfigStore cardStore(fromCard, sd, ee);
  cardStore.load();
  FUZZ_REQUIRE(memcmp(fromCard.raw(), loaded.raw(), sizeof(int32_t) * mega::kKeyCount) == 0, "saved settings load back changed");
  sd.inserted = false;
  mega::Config fromEeprom;
  mega::ConfigStore eeStore(fromEeprom, sd, ee);
  eeStore.load();
  FUZZ_REQUIRE(memcmp(fromEeprom.raw(), loaded.raw(), sizeof(int32_t) * mega::kKeyCount) == 0, "the EEPROM copy loads back changed");
  return 0;
}
