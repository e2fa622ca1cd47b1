// The Mega's settings: the key table against CONFIG.md, values and ranges, CONFIG.TXT (including
// malformed files), the EEPROM copy, and saves cut short.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <regex>
#include <sstream>
#include <string>

#include "config.h"
#include "config_store.h"
#include "eeprom_fake.h"
#include "storage_fake.h"

using namespace mega;

namespace {

std::string value(const Config& c, Key k) {
  char out[kValueTextMax + 1];
  c.format(k, out);
  return out;
}
bool set(Config& c, Key k, const std::string& v) { return c.set(k, v.data(), static_cast<uint8_t>(v.size())); }
std::string name(Key k) {
  char out[kKeyNameMax + 1];
  keyName(k, out);
  return out;
}
uint8_t m850(Config& c, const std::string& arg, Key& k, bool& query) {
  return applyM850(c, arg.data(), static_cast<uint8_t>(arg.size()), k, query);
}

struct Row {
  std::string key, def, lo, hi;
  bool whole, pair, off;  // off: 0 is taken too, below the range
};

std::vector<Row> configDoc() {
  std::ifstream in(UV_MEGA_CONFIG_MD);
  std::string line;
  std::vector<Row> rows;
  std::regex row(R"(^\| `([a-z0-9_.]+)` \| [^|]+ \| ([^|]+) \| (0, or )?(-?[0-9.]+) to (-?[0-9.]+)( whole| each)? \|)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (!std::regex_search(line, m, row)) continue;
    std::string def = m[2];
    def.erase(def.find_last_not_of(' ') + 1);
    rows.push_back({m[1], def, m[4], m[5], m[6] == " whole", m[6] == " each", m[3].matched});
  }
  return rows;
}

}  // namespace

TEST(Config, TableIsCONFIGmdKeyForKeyWithDefaultsAndRanges) {
  std::vector<Row> doc = configDoc();
  ASSERT_EQ(doc.size(), kKeyCount);
  Config c;
  for (uint8_t i = 0; i < kKeyCount; i++) {
    Key k = static_cast<Key>(i);
    SCOPED_TRACE(doc[i].key);
    EXPECT_EQ(name(k), doc[i].key);
    EXPECT_EQ(value(c, k), doc[i].def);
    Config t;
    if (doc[i].pair) {
      EXPECT_TRUE(set(t, k, doc[i].lo + "," + doc[i].hi));
      EXPECT_EQ(value(t, k), doc[i].lo + "," + doc[i].hi);
      EXPECT_FALSE(set(t, k, std::to_string(std::stoi(doc[i].lo) - 1) + ",0"));
      EXPECT_FALSE(set(t, k, "0," + std::to_string(std::stoi(doc[i].hi) + 1)));
      EXPECT_FALSE(set(t, k, "0.5,0"));
      continue;
    }
    EXPECT_TRUE(set(t, k, doc[i].lo));
    EXPECT_EQ(value(t, k), doc[i].lo);
    EXPECT_TRUE(set(t, k, doc[i].hi));
    EXPECT_EQ(value(t, k), doc[i].hi);
    // A thousandth outside either end is refused, and the value stays.
    EXPECT_FALSE(set(t, k, std::to_string(std::stod(doc[i].hi) + 0.001)));
    EXPECT_FALSE(set(t, k, std::to_string(std::stod(doc[i].lo) - 0.001)));
    EXPECT_EQ(value(t, k), doc[i].hi);
    if (doc[i].whole) {
      EXPECT_FALSE(set(t, k, doc[i].lo + ".5"));
    }
    if (doc[i].off) {  // 0, off, below the range: and nothing else below it
      EXPECT_TRUE(set(t, k, "0"));
      EXPECT_EQ(value(t, k), "0");
      EXPECT_FALSE(set(t, k, "1"));
      EXPECT_FALSE(set(t, k, "-1"));
    }
  }
}

TEST(Config, ValuesKeepTheirShortestTextForm) {
  Config c;
  EXPECT_TRUE(set(c, Key::SpeedZ, "2.5"));
  EXPECT_EQ(value(c, Key::SpeedZ), "2.5");
  EXPECT_TRUE(set(c, Key::SpeedZ, "2.50"));
  EXPECT_EQ(value(c, Key::SpeedZ), "2.5");
  EXPECT_TRUE(set(c, Key::StepsX, "78.125"));
  EXPECT_EQ(c.milli(Key::StepsX), 78125);
  EXPECT_TRUE(set(c, Key::StepsX, "78.7402"));  // thousandths, rounded half away from zero
  EXPECT_EQ(value(c, Key::StepsX), "78.74");
  EXPECT_TRUE(set(c, Key::ThermalCoeff, "-12"));
  EXPECT_EQ(value(c, Key::ThermalCoeff), "-12");
  EXPECT_TRUE(set(c, Key::LedOffset1, "-2,4"));
  EXPECT_EQ(c.pairX(Key::LedOffset1), -2);
  EXPECT_EQ(c.pairY(Key::LedOffset1), 4);
  EXPECT_EQ(value(c, Key::LedOffset1), "-2,4");
  for (const char* bad : {"", "fast", "1,2", "+3", "3.", ".5", "1e3", "0x10", "3 4", "--1"}) {
    EXPECT_FALSE(set(c, Key::AccelX, bad)) << bad;
  }
  for (const char* bad : {"3", "1,", ",1", "1,2,3", "a,b", "1 ,2"}) EXPECT_FALSE(set(c, Key::LedOffset0, bad)) << bad;
  EXPECT_EQ(value(c, Key::AccelX), "2000");
}

TEST(Config, NumbersPastThe32BitRangeAreRefusedNotWrapped) {
  // 4295167 * 1000 wraps 32 bits to 199704: it once set a 199.704 mm bed.
  Config c;
  c.defaults();
  int32_t before = c.milli(Key::BedX);
  for (const char* big : {"4295167", "4294968", "99999999", "2001", "4294967.296"}) {
    EXPECT_FALSE(set(c, Key::BedX, big)) << big;
    EXPECT_EQ(c.milli(Key::BedX), before) << big;
  }
  EXPECT_FALSE(set(c, Key::LedOffset0, "4294967297,0"));
}

TEST(Config, M850SetsQueriesAndRefusesWithE50) {
  Config c;
  Key k;
  bool query;
  EXPECT_EQ(m850(c, "accel.x 2500", k, query), 0);
  EXPECT_FALSE(query);
  EXPECT_EQ(k, Key::AccelX);
  EXPECT_EQ(value(c, Key::AccelX), "2500");
  EXPECT_EQ(m850(c, "accel.x", k, query), 0);
  EXPECT_TRUE(query);
  EXPECT_EQ(m850(c, "accel.w 1", k, query), 50);
  EXPECT_EQ(m850(c, "accel.x fast", k, query), 50);
  EXPECT_EQ(m850(c, "accel.x 0", k, query), 50);
  EXPECT_EQ(m850(c, "thermal.limit.0 61", k, query), 50);  // above the Nano's hard limit
  EXPECT_EQ(m850(c, "esp.port 1", k, query), 50);
  EXPECT_EQ(m850(c, "report.position_ms 20", k, query), 50);  // M154's floor: a shorter period floods the link
  EXPECT_EQ(m850(c, "report.position_ms 0", k, query), 0);    // off
  EXPECT_EQ(m850(c, "", k, query), 50);
  EXPECT_EQ(value(c, Key::AccelX), "2500");
}

TEST(Config, FileLinesAreTakenOnlyWhenWhollyGood) {
  Config c;
  const char* lines[] = {"# a comment", "", "accel.x=2500", "  speed.z = 2.5  ", "accel.y = fast", "nozzle = 3",
                         "led.offset.1 = 1,4", "bed.x 300", "bed.y = 300 mm", "bed.z == 20", "steps_per_mm.z = 0",
                         "mesh.nx = 4.5", "\tsettle_ms\t=\t7\t", "speed.travel =", "= 5", "accel.x.y = 3"};
  int taken = 0;
  for (const char* l : lines) taken += applyConfigLine(c, l, static_cast<uint8_t>(strlen(l)));
  EXPECT_EQ(taken, 4);
  EXPECT_EQ(value(c, Key::AccelX), "2500");
  EXPECT_EQ(value(c, Key::SpeedZ), "2.5");
  EXPECT_EQ(value(c, Key::AccelY), "1500");
  EXPECT_EQ(value(c, Key::LedOffset1), "1,4");
  EXPECT_EQ(value(c, Key::BedX), "200");
  EXPECT_EQ(value(c, Key::BedY), "200");
  EXPECT_EQ(value(c, Key::StepsZ), "400");
  EXPECT_EQ(value(c, Key::MeshNx), "3");
  EXPECT_EQ(value(c, Key::SettleMs), "7");
}

TEST(Config, RandomBytesNeverTakeAValueOutsideItsRange) {
  std::mt19937 rng(7);
  const std::string alphabet = "abcdefghijklmnopqrstuvwxyz_.=, -0123456789\t#\r";
  for (int trial = 0; trial < 20000; trial++) {
    Config c;
    std::string line;
    if (trial % 2) {  // a real key with a random value
      line = name(static_cast<Key>(rng() % kKeyCount)) + " = ";
    }
    int n = static_cast<int>(rng() % 24);
    for (int i = 0; i < n; i++) line += trial % 3 ? alphabet[rng() % alphabet.size()] : static_cast<char>(rng() % 256);
    applyConfigLine(c, line.data(), static_cast<uint8_t>(line.size()));
    for (uint8_t i = 0; i < kKeyCount; i++) {
      Config probe;
      EXPECT_TRUE(probe.setHeld(static_cast<Key>(i), c.raw()[i])) << line;
    }
  }
}

TEST(ConfigStore, SavesCONFIGTXTInTableOrderAndLoadsItBack) {
  FakeStorage sd;
  FakeEeprom ee;
  Config c;
  ConfigStore store(c, sd, ee);
  set(c, Key::AccelX, "2500");
  set(c, Key::LedOffset3, "1,-3");
  EXPECT_EQ(store.save(), 0);
  std::istringstream file(sd.contents(kConfigFile));
  std::string first;
  std::getline(file, first);
  EXPECT_EQ(first, "steps_per_mm.x = 80");
  EXPECT_NE(sd.contents(kConfigFile).find("accel.x = 2500\n"), std::string::npos);
  EXPECT_NE(sd.contents(kConfigFile).find("led.offset.3 = 1,-3\n"), std::string::npos);
  EXPECT_FALSE(sd.exists("CONFIG.NEW"));
  EXPECT_EQ(sd.openFiles(), 0);
  Config loaded;
  ConfigStore again(loaded, sd, ee);
  EXPECT_EQ(again.load() & ConfigStore::kFromFile, ConfigStore::kFromFile);
  for (uint8_t i = 0; i < kKeyCount; i++) EXPECT_EQ(loaded.raw()[i], c.raw()[i]) << name(static_cast<Key>(i));
}

TEST(ConfigStore, TheFileWinsOverTheEepromKeyByKey) {
  FakeStorage sd;
  FakeEeprom ee;
  Config c;
  ConfigStore store(c, sd, ee);
  set(c, Key::AccelX, "2500");
  set(c, Key::AccelY, "900");
  store.save();
  while (store.saving()) store.poll();
  sd.put(kConfigFile, "accel.y = 1200\r\n# edited on a PC\r\nspeed.z=7");
  Config loaded;
  ConfigStore again(loaded, sd, ee);
  EXPECT_EQ(again.load(), ConfigStore::kFromEeprom | ConfigStore::kFromFile);
  EXPECT_EQ(value(loaded, Key::AccelX), "2500");  // only in the EEPROM copy
  EXPECT_EQ(value(loaded, Key::AccelY), "1200");  // the file's
  EXPECT_EQ(value(loaded, Key::SpeedZ), "7");     // a last line without '\n'
}

TEST(ConfigStore, WithoutACardTheEepromCopyIsTheFallback) {
  FakeStorage sd;
  sd.inserted = false;
  FakeEeprom ee;
  Config c;
  ConfigStore store(c, sd, ee);
  set(c, Key::BedX, "300");
  EXPECT_EQ(store.save(), 0);
  while (store.saving()) store.poll();
  Config loaded;
  ConfigStore again(loaded, sd, ee);
  EXPECT_EQ(again.load(), ConfigStore::kFromEeprom);
  EXPECT_EQ(value(loaded, Key::BedX), "300");
}

TEST(ConfigStore, EepromIsWrittenAByteAtATimeAndOnlyWhereItChanged) {
  FakeStorage sd;
  FakeEeprom ee;
  ee.busyPolls = 5;
  Config c;
  ConfigStore store(c, sd, ee);
  store.save();
  int polls = 0;
  for (uint32_t before = ee.writes; store.saving(); polls++) {
    store.poll();
    EXPECT_LE(ee.writes - before, 1u);  // never more than one byte started per call
    before = ee.writes;
  }
  EXPECT_EQ(ee.writes, ConfigStore::kImageSize);  // a blank (0xff) EEPROM: every byte
  EXPECT_GT(polls, 5 * static_cast<int>(ConfigStore::kImageSize));
  set(c, Key::AccelX, "2500");
  uint32_t before = ee.writes;
  store.save();
  while (store.saving()) store.poll();
  EXPECT_LE(ee.writes - before, 4u + 4u);  // at most the changed value's 4 bytes and the CRC's 4
}

TEST(ConfigStore, ADamagedOrForeignEepromCopyIsIgnored) {
  FakeStorage sd;
  sd.inserted = false;
  FakeEeprom ee;
  Config c;
  ConfigStore store(c, sd, ee);
  set(c, Key::BedX, "300");
  store.save();
  while (store.saving()) store.poll();
  ee.bytes[10] ^= 0x01;  // one bit
  Config loaded;
  ConfigStore again(loaded, sd, ee);
  EXPECT_EQ(again.load(), ConfigStore::kFromDefaults);
  EXPECT_EQ(value(loaded, Key::BedX), "200");
  ee.bytes[10] ^= 0x01;
  ee.bytes[3] = kKeyCount - 1;  // written by a firmware with other keys
  EXPECT_EQ(again.load(), ConfigStore::kFromDefaults);
}

TEST(ConfigStore, ACardThatFailsMidSaveKeepsTheOldFile) {
  FakeStorage sd;
  FakeEeprom ee;
  sd.put(kConfigFile, "accel.x = 2500\n");
  Config c;
  ConfigStore store(c, sd, ee);
  store.load();
  set(c, Key::AccelX, "3000");
  sd.failWritesAfter = 200;
  EXPECT_EQ(store.save(), 22);
  EXPECT_EQ(sd.contents(kConfigFile), "accel.x = 2500\n");
  EXPECT_EQ(sd.openFiles(), 0);
  while (store.saving()) store.poll();  // the EEPROM copy is still made
  sd.inserted = false;
  Config loaded;
  ConfigStore again(loaded, sd, ee);
  again.load();
  EXPECT_EQ(value(loaded, Key::AccelX), "3000");
}
