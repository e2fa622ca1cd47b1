// Test-only: a whole simulated Mega with a job uploaded, selected and run, for the job tests.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "job_fixture.h"
#include "mega_rig.h"

namespace mega {

using jobs::Lines;

// The last JOB: line among `lines`, or "(none)".
inline std::string lastJob(const Lines& lines) {
  for (auto it = lines.rbegin(); it != lines.rend(); ++it)
    if (it->rfind("JOB:", 0) == 0) return *it;
  return "(none)";
}

class JobTest : public ::testing::Test {
 protected:
  MegaRig m;
  void SetUp() override {
    m.begin();
    m.run(600000);  // temperatures known
  }
  Lines payload(const std::string& body) { return MegaRig::payload(m.cmd(body)); }
  Lines upload(const std::string& name, const Lines& records) {
    Lines all = m.cmd("M28 " + name);
    for (const std::string& r : records) {
      Lines b = m.cmd(r);
      all.insert(all.end(), b.begin(), b.end());
    }
    Lines end = m.cmd("M29");
    all.insert(all.end(), end.begin(), end.end());
    return all;
  }
  // Uploads the job, selects it, homes and starts it; returns the upload's lines.
  Lines uploadAndStart(const std::string& name, const Lines& records) {
    Lines got = upload(name, records);
    m.cmd("M23 " + name);
    m.cmd("G28");
    m.cmd("M24");
    return got;
  }
  // A raster job of 6 x 4 cells whose exposures last 400 ms, started and run into its second stop's
  // light, so that a restart or a fault lands inside an exposure; returns that exposure's index.
  size_t startLongJobIntoItsLight(const std::string& name, uv::JobHeader& h, jobs::Grid& g) {
    h = jobs::header(6, 4, uv::Strategy::Raster);
    h.fullUs = 400000;
    g = jobs::pattern(6, 4, 3);
    uploadAndStart(name, jobs::encode(h, g));
    for (int t = 0; t < 100000 && !(m.nano.lit() && m.nano.exposures.size() >= 2); t++) m.run(100);
    EXPECT_NE(m.nano.lit(), 0) << "no light to cut";
    return m.nano.exposures.size() - 1;
  }
  // Runs until a JOB: line in `states` arrives; returns it.
  std::string runUntilJob(std::initializer_list<const char*> states, uint64_t maxUs = 300000000) {
    size_t from = m.usbLines.size();
    for (uint64_t t = 0; t < maxUs; t += 1000) {
      m.run(1000);
      for (size_t i = from; i < m.usbLines.size(); i++)
        for (const char* s : states)
          if (m.usbLines[i].rfind(std::string("JOB:") + s, 0) == 0) return m.usbLines[i];
      from = m.usbLines.size();
    }
    return "(none)";
  }
  void expectExposed(const uv::JobHeader& h, const std::vector<uv::Stop>& stops, size_t from = 0) {
    ASSERT_GT(stops.size(), 0u);
    ASSERT_EQ(m.nano.exposures.size() - from, stops.size());
    for (size_t i = 0; i < stops.size(); i++) {
      const Exposure& e = m.nano.exposures[from + i];
      uint8_t mask = 0;
      for (int k = 0; k < 4; k++) {
        if (stops[i].us[k]) mask = static_cast<uint8_t>(mask | (1 << k));
        EXPECT_EQ(e.litUs[k], stops[i].us[k]) << "stop " << i << " LED " << k;
      }
      EXPECT_EQ(e.mask, mask) << "stop " << i;
      // 80 steps/mm: the head's bed position in µm × 0.08
      EXPECT_EQ(m.firedAt[from + i][0], (static_cast<int32_t>(h.originUm[0]) + stops[i].hx * 100) * 80 / 1000) << "stop " << i;
      EXPECT_EQ(m.firedAt[from + i][1], (static_cast<int32_t>(h.originUm[1]) + stops[i].hy * 100) * 80 / 1000) << "stop " << i;
    }
  }
};


}  // namespace mega
