// The ESP8266's file system under the yield that re-enters it (issue 36 item 7): loop() reads a
// spooled body through the flash model, whose every operation yields to the network callbacks.
// A callback that reads an app file while loop() is inside a read re-enters LittleFS, which the
// model counts; with the gate, the callback answers 503 flash_busy instead, and is served once
// loop() is out of the file system.
#include "flash_gate.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "host_body.h"
#include "host_flash.h"

using uv::esp::FlashGate;

namespace {

std::string writeFile(const char* name, const std::string& text) {
  std::string path = std::string(testing::TempDir()) + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// The network callbacks: a GET of an app file, asked again at each yield until it is answered.
struct Network {
  uvtest::HostFlash& flash;
  FlashGate& gate;
  std::string app;
  bool guarded;
  int served = 0, busy = 0;
  size_t bytes = 0;

  void get() {
    if (guarded && gate.held()) {
      busy++;  // 503 flash_busy, Retry-After: 1
      return;
    }
    bytes += flash.callbackOperation([&] {
      std::ifstream f(app, std::ios::binary);
      return std::string(std::istreambuf_iterator<char>(f), {}).size();
    });
    served++;
  }
};

struct Rig {
  uvtest::HostFlash flash;
  FlashGate gate;
  std::string body = std::string(20000, 'x');
  uvtest::HostBody spool{writeFile("gate-body.json", body), &flash, &gate};
  Network network;
  explicit Rig(bool guarded) : network{flash, gate, writeFile("gate-app.js.gz", std::string(3000, 'a')), guarded} {
    flash.yield = [this] { network.get(); };
  }
  // loop(): the whole body read back, as the intake and the upload read it.
  std::string readBody() {
    std::string text;
    EXPECT_TRUE(spool.rewind());
    for (int c; (c = spool.read()) >= 0;) text += static_cast<char>(c);
    spool.close();
    return text;
  }
};

TEST(FlashGate, WithoutItANetworkCallbackInsideAFlashOperationReentersTheFileSystem) {
  Rig rig(false);
  EXPECT_EQ(rig.readBody(), rig.body);
  EXPECT_GT(rig.flash.reentered(), 0u);  // what would corrupt LittleFS on the ESP8266
  EXPECT_EQ(rig.network.busy, 0);
}

TEST(FlashGate, WithItTheCallbackIsAnsweredBusyAndServedOnceLoopIsOutOfTheFileSystem) {
  Rig rig(true);
  EXPECT_EQ(rig.readBody(), rig.body);
  EXPECT_EQ(rig.flash.reentered(), 0u);
  EXPECT_GE(rig.network.busy, 40);  // every open, block (20000 B in 512 B) and close yields once
  EXPECT_EQ(rig.network.served, 0);
  rig.network.get();  // between loop()'s passes: the gate is free
  EXPECT_EQ(rig.network.served, 1);
  EXPECT_EQ(rig.network.bytes, 3000u);
  EXPECT_EQ(rig.flash.reentered(), 0u);
}

TEST(FlashGate, HoldsNest) {
  FlashGate gate;
  {
    FlashGate::Hold a(gate);
    {
      FlashGate::Hold b(gate);
      EXPECT_TRUE(gate.held());
    }
    EXPECT_TRUE(gate.held());
  }
  EXPECT_FALSE(gate.held());
}

}  // namespace
