// G-code files on the card, driven as OctoPrint drives them: M28 ... M29 stores the lines without
// running them, M20 lists, M23/M24 run the file between the hosts' lines to `Done printing file`.
#include "machine.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "gcode_file.h"
#include "mega_rig.h"

using namespace mega;

namespace {

using Lines = std::vector<std::string>;

bool has(const Lines& lines, const std::string& prefix) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(prefix, 0) == 0; });
}

class CardGcodeTest : public ::testing::Test {
 protected:
  MegaRig m;
  void SetUp() override { m.begin(); }
  Lines payload(const std::string& body) { return MegaRig::payload(m.cmd(body)); }
  void upload(const std::string& name, const Lines& lines) {
    EXPECT_EQ(payload("M28 " + name), (Lines{"echo:Writing to file: " + name.substr(name[0] == '/' ? 1 : 0)}));
    for (const std::string& l : lines) EXPECT_EQ(payload(l), Lines{}) << l;  // stored: nothing runs, nothing said
    EXPECT_EQ(payload("M29"), (Lines{"echo:Done saving file."}));
  }
  std::string card(const std::string& name) {
    char buf[256] = {};
    FileHandle f = m.sd.open(name.c_str(), Storage::Mode::Read);
    if (f < 0) return "(none)";
    int16_t n = m.sd.read(f, buf, sizeof buf - 1);
    m.sd.close(f);
    return std::string(buf, n > 0 ? static_cast<size_t>(n) : 0);
  }
  bool waitFor(const std::string& line, uint64_t us) {
    for (uint64_t t = 0; t < us; t += 10000) {
      if (std::find(m.usbLines.begin(), m.usbLines.end(), line) != m.usbLines.end()) return true;
      m.run(10000);
    }
    return false;
  }
};

}  // namespace

TEST(GcodeName, GcodeIsToldFromJobsByTheName) {
  EXPECT_TRUE(isGcodeName("a.gco") && isGcodeName("B.GCODE") && isGcodeName("c.g") && isGcodeName("MY_LON~1.GCO"));
  EXPECT_FALSE(isGcodeName("PCB.UVJ") || isGcodeName("gco") || isGcodeName("a.gc") || isGcodeName(".g"));
}

TEST_F(CardGcodeTest, AnUploadIsStoredNotRunAndAppearsOnlyAtM29) {
  EXPECT_EQ(payload("M21"), (Lines{"echo:SD card ok"}));
  EXPECT_EQ(payload("M28 /part.gco"), (Lines{"echo:Writing to file: part.gco"}));
  EXPECT_EQ(payload("G28"), Lines{});
  EXPECT_EQ(payload("G1 X10 ; to the start"), Lines{});
  EXPECT_FALSE(m.sd.exists("part.gco"));  // nothing half-received is seen
  EXPECT_EQ(payload("M29"), (Lines{"echo:Done saving file."}));
  EXPECT_EQ(m.machine.homed(), 0);  // nothing ran
  EXPECT_EQ(card("part.gco"), "G28\nG1 X10\n");
  EXPECT_TRUE(has(payload("M20"), "part.gco 11"));
}

TEST_F(CardGcodeTest, AnUploadCutShortLeavesNoFileAndPlainLinesAreNotStored) {
  upload("keep.gco", {"G4 P1"});
  m.cmd("M28 keep.gco");
  m.usb.toMega += "G28\n";  // no line number, no check
  m.run(20000);
  EXPECT_TRUE(has(m.usbLines, "Error:E4 checksum without line number: a stored line needs a line number"));
  m.cmd("G1 X5");
  m.send("M112");
  m.run(20000);
  m.cmd("M999");
  EXPECT_EQ(card("keep.gco"), "G4 P1\n");  // the older file stays as it was
  EXPECT_FALSE(has(payload("M20"), "keep.gco~"));
  EXPECT_EQ(payload("M28 job~c"), (Lines{"echo:E11 bad or missing parameter: a job's name has no ~"}));
}

TEST_F(CardGcodeTest, AFileRunsFromTheCardToDonePrintingFile) {
  upload("run.gco", {"G28", "G1 X20 Y10 F6000", "G4 P10", "G1 X30", "M400"});
  EXPECT_EQ(payload("M23 /run.gco"), (Lines{"File opened: run.gco Size: 40", "File selected"}));
  EXPECT_EQ(payload("M27"), (Lines{"SD printing byte 0/40"}));
  m.cmd("M27 S1");
  size_t from = m.usbLines.size();
  m.cmd("M24");
  ASSERT_TRUE(waitFor("Done printing file", 30000000));
  EXPECT_TRUE(has(Lines(m.usbLines.begin() + static_cast<long>(from), m.usbLines.end()), "SD printing byte "));  // M27 S too
  m.cmd("M27 S0");
  EXPECT_EQ(payload("M114"), (Lines{"X:30.000 Y:10.000 Z:0.000 E:0.000 Count X:2400 Y:800 Z:0"}));
  EXPECT_TRUE(has(payload("M27"), "JOB:"));  // deselected
}

TEST_F(CardGcodeTest, PauseRewindAndHostLinesInBetween) {
  upload("slow.gco", {"G28", "G4 S1", "G1 X50", "G4 S1", "G1 X60"});
  m.cmd("M32 slow.gco");
  m.run(200000);
  EXPECT_TRUE(has(m.cmd("M105"), "T:"));  // answered while the file runs
  m.cmd("M25");
  m.run(5000000);
  Lines at = payload("M27");
  ASSERT_EQ(at.size(), 1u);
  EXPECT_NE(at[0], "SD printing byte 30/30");
  m.cmd("M26 S12");  // inside "G1 X50": on to the next line's start
  EXPECT_EQ(payload("M27"), (Lines{"SD printing byte 17/30"}));
  m.cmd("M24");
  ASSERT_TRUE(waitFor("Done printing file", 30000000));
  m.cmd("M400");
  EXPECT_TRUE(has(payload("M114"), "X:60.000"));
}

TEST_F(CardGcodeTest, AFileStartsNoOtherFileAndAFaultStopsIt) {
  upload("a.gco", {"M23 a.gco", "M117 still here"});
  m.cmd("M32 a.gco");
  ASSERT_TRUE(waitFor("Done printing file", 2000000));
  EXPECT_TRUE(has(m.usbLines, "echo:E12 not allowed while a job is running: M23 a.gco"));
  m.rig.switchAt[1] = INT32_MIN;  // homing Y fails: E44, a fault
  upload("b.gco", {"G28 Y", "M117 never"});
  m.cmd("M32 b.gco");
  m.run(30000000);
  EXPECT_TRUE(has(m.usbLines, "Error:E44"));
  EXPECT_FALSE(has(m.usbLines, "Done printing file") && m.usbLines.back() == "Done printing file");
  EXPECT_TRUE(has(payload("M27"), "JOB:"));  // stopped and deselected
  EXPECT_EQ(payload("M28 c.gco"), (Lines{"echo:Writing to file: c.gco"}));  // nothing runs any more
}
