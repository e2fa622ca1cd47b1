// Probing and the bed mesh on a whole simulated Mega: the CR Touch's pin closes on a tilted, bumpy
// bed; G30 finds it, G29 maps it into the EEPROM and the card, and exposures follow it in Z.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "grid_cells.h"
#include "job_encoder.h"
#include "mega_rig.h"
#include "planner.h"

using namespace mega;

namespace {

using Lines = std::vector<std::string>;

int32_t tiltedBed(int32_t x, int32_t y) {  // µm: a tilt and a bump, like a real plate on a real bed
  double mmX = x / 1000.0, mmY = y / 1000.0;
  return static_cast<int32_t>(std::lround(120 + 0.6 * mmX - 0.4 * mmY + 45 * std::exp(-((mmX - 60) * (mmX - 60) + (mmY - 140) * (mmY - 140)) / (2 * 35.0 * 35))));
}

bool has(const Lines& lines, const std::string& prefix) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.rfind(prefix, 0) == 0; });
}

// "Bed X: 50.000 Y: 60.000 Z: 0.123" → the Z in µm.
int32_t bedZ(const std::string& line) {
  double z = std::stod(line.substr(line.find("Z:") + 2));
  return static_cast<int32_t>(std::lround(z * 1000));
}

class ProbeTest : public ::testing::Test {
 protected:
  MegaRig m;
  void SetUp() override {
    m.bed = tiltedBed;
    m.rig.switchAt[2] = -4000;  // Z's switch 10 mm below where the head starts (400 steps/mm)
    m.begin();
    m.run(600000);
  }
  Lines payload(const std::string& body) { return MegaRig::payload(m.cmd(body)); }
};

}  // namespace

TEST_F(ProbeTest, G30NeedsHomingAndTheProbeOut) {
  EXPECT_EQ(payload("G30"), (Lines{"echo:E14 axis not homed: home first (G28)"}));
  m.cmd("G28");
  EXPECT_EQ(payload("G30"), (Lines{"Error:E41 probe did not trigger: deploy the probe (M401)"}));
}

TEST_F(ProbeTest, G30FindsTheBedWithinAFewMicrometresAndLiftsOff) {
  m.cmd("G28");
  m.cmd("G1 X50 Y60 Z4");
  EXPECT_EQ(payload("M401"), (Lines{"PROBE:deployed"}));
  Lines p = payload("G30");
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].rfind("Bed X: 50.000 Y: 60.000 Z: ", 0), 0u) << p[0];
  int32_t found = bedZ(p[0]), truth = tiltedBed(50000, 60000);
  EXPECT_NEAR(found, truth, 8);  // Z steps are 2.5 µm; a P poll at 3 mm/s is a few more
  std::printf("[mega probe] bed at %d um, found at %d um\n", truth, found);
  int32_t at[3];
  m.rig.motion.positionUm(at);
  EXPECT_NEAR(at[2], found + 5000, 3);
}

TEST_F(ProbeTest, AProbeThatNeverTouchesIsRecoveredTwiceThenReported) {
  m.bed = [](int32_t, int32_t) { return -20000; };  // nothing within reach
  m.cmd("G28");
  m.cmd("G1 Z2");
  m.cmd("M401");
  size_t before = m.nano.lines.size();
  EXPECT_EQ(payload("G30"), (Lines{"Error:E41 probe did not trigger"}));
  long releases = std::count(m.nano.lines.begin() + static_cast<long>(before), m.nano.lines.end(), "X");
  EXPECT_EQ(releases, 2);  // alarm release and deploy again, before each of the two retries
}

TEST_F(ProbeTest, G29MapsTheBedKeepsItAndExposuresFollowIt) {
  m.cmd("G28");
  m.cmd("G1 Z4");
  m.cmd("M401");
  Lines level = payload("G29 X3 Y4");
  long points = std::count_if(level.begin(), level.end(), [](const std::string& l) { return l.rfind("Bed X:", 0) == 0; });
  ASSERT_EQ(points, 12) << (level.empty() ? "" : level.back());
  for (const std::string& l : level) {
    if (l.rfind("Bed X:", 0) != 0) continue;
    int32_t x = static_cast<int32_t>(std::lround(std::stod(l.substr(7)) * 1000));
    int32_t y = static_cast<int32_t>(std::lround(std::stod(l.substr(l.find("Y:") + 2)) * 1000));
    EXPECT_NEAR(bedZ(l), tiltedBed(x, y), 8) << l;
  }
  EXPECT_TRUE(has(level, "MESH:grid 3 4 x0=10.000 y0=10.000 dx=90.000 dy=60.000"));
  EXPECT_TRUE(has(level, "MESH:row 3 "));
  EXPECT_NE(m.sd.contents("MESH.TXT").find("MESH:grid 3 4"), std::string::npos);
  Lines shown = payload("M420 V");
  EXPECT_EQ(shown.size(), 5u);

  // A job now follows the mesh: each stop's Z is where it started plus the mesh under it.
  uv::JobHeader h{};
  h.cols = 8;
  h.rows = 8;
  h.pitchUm[0] = h.pitchUm[1] = 20000;  // 20 mm cells: the stops spread over the bed
  h.originUm[0] = 10000;
  h.originUm[1] = 10000;
  h.map = uv::DoseMap::Threshold;
  h.level = 1;
  h.fullUs = 1000;
  h.thermalRefDeciC = 250;
  for (int k = 0; k < 4; k++) {
    h.gainPermille[k] = 1000;
    h.offsets[k][1] = static_cast<int16_t>(k);
  }
  std::vector<std::vector<uint8_t>> g(8, std::vector<uint8_t>(8, 0));
  for (int r = 0; r < 8; r++) g[r][(r * 3) % 8] = 255;
  struct Records : uv::RecordSink {
    Lines lines;
    void record(const char* t, uint8_t n) override { lines.emplace_back(t, n); }
  } rec;
  uv::JobEncoder enc(rec);
  enc.header(h);
  for (uint16_t r = 0; r < 8; r++) enc.row(r, g[r].data(), 8);
  enc.finish();
  m.cmd("M402");
  m.cmd("G1 Z3");
  m.cmd("M28 Z.UVJ");
  for (const std::string& r : rec.lines) m.cmd(r);
  ASSERT_TRUE(has(m.cmd("M29"), "echo:Done saving file."));
  m.cmd("M23 Z.UVJ");
  m.cmd("M24");
  for (int t = 0; t < 600 && !has(m.usbLines, "JOB:done"); t++) m.run(100000);
  ASSERT_TRUE(has(m.usbLines, "JOB:done"));
  ASSERT_EQ(m.firedAt.size(), 8u);
  uv::Mesh mesh{};
  mesh.nx = 3;
  mesh.ny = 4;
  mesh.x0 = mesh.y0 = 10000;
  mesh.dx = 90000;
  mesh.dy = 60000;
  for (int j = 0; j < 4; j++)
    for (int i = 0; i < 3; i++) mesh.z[j][i] = static_cast<int16_t>(m.machine.meshPoint(static_cast<uint8_t>(i), static_cast<uint8_t>(j)));
  for (const auto& at : m.firedAt) {
    int32_t x = at[0] * 1000 / 80, y = at[1] * 1000 / 80;
    int32_t expected = 3000 + uv::meshZ(mesh, x, y);
    EXPECT_NEAR(at[2], expected * 400 / 1000, 1) << "at " << x << "," << y;
  }
}

TEST_F(ProbeTest, TheMeshOutlivesARestartButIsAppliedOnlyWhenAsked) {
  m.cmd("G28");
  m.cmd("G1 Z4");
  m.cmd("M401");
  ASSERT_TRUE(has(payload("G29 X3 Y3"), "MESH:row 2 "));
  m.run(200000);
  m.reset(200000);
  Lines shown = payload("M420 V");
  EXPECT_TRUE(has(shown, "MESH:grid 3 3"));
  EXPECT_FALSE(m.machine.leveling());
  EXPECT_EQ(payload("M420"), Lines{"echo:leveling off"});
  EXPECT_EQ(payload("M420 S1"), Lines{});
  EXPECT_TRUE(m.machine.leveling());
  EXPECT_EQ(payload("M420"), Lines{"echo:leveling on"});
}

TEST_F(ProbeTest, WithoutAMeshM420Refuses) {
  EXPECT_EQ(payload("M420 V"), (Lines{"echo:E11 bad or missing parameter: no mesh"}));
  EXPECT_EQ(payload("M420 S1"), (Lines{"echo:E11 bad or missing parameter: no mesh"}));
  EXPECT_EQ(payload("G29 X2"), (Lines{"echo:E11 bad or missing parameter"}));
}
