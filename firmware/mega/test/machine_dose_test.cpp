// The dose the head delivered, reported (protocol/mega.md "Dose reports"): each stop's and each
// pass program's DOSE: line carries the Nano's own on-times, once per stop, and a resume says which
// stop it lit twice; a card job keeps the same lines beside it (name~d). On a whole simulated Mega
// with the printhead's fake Nano.
#include <gtest/gtest.h>

#include <map>

#include "dialect_reply.h"
#include "machine_job_fixture.h"
#include "machine_scan_fixture.h"

using namespace mega;
using namespace jobs;

namespace {

std::vector<uv::DoseReport> doses(const Lines& lines) {
  std::vector<uv::DoseReport> out;
  for (const std::string& l : lines) {
    if (l.rfind("DOSE:", 0) != 0) continue;
    uv::Reply r{};
    EXPECT_TRUE(uv::parseReply(l.data(), static_cast<uint8_t>(l.size()), r)) << l;
    EXPECT_EQ(r.kind, uv::ReplyKind::Dose) << l;
    out.push_back(r.dose);
  }
  return out;
}

using DoseScanTest = ScanMachineTest;

// The DOSE: lines a host got, and those a card job's dose file holds.
Lines doseLines(const Lines& lines) {
  Lines out;
  for (const std::string& l : lines)
    if (l.rfind("DOSE:", 0) == 0) out.push_back(l);
  return out;
}
Lines doseFile(const FakeStorage& sd, const std::string& job) {
  Lines out;
  const std::string text = sd.contents(job + "~d");
  for (size_t at = 0, nl; (nl = text.find('\n', at)) != std::string::npos; at = nl + 1) out.push_back(text.substr(at, nl - at));
  return out;
}

}  // namespace

TEST_F(JobTest, EveryLitStopIsReportedOnceWithWhatTheNanoTimed) {
  uv::JobHeader h = header(14, 9, uv::Strategy::Shortest);
  Grid g = pattern(14, 9, 7);
  uploadAndStart("D.UVJ", encode(h, g));
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  const std::vector<uv::Stop> stops = plan(h, g);
  const std::vector<uv::DoseReport> d = doses(m.usbLines);
  ASSERT_EQ(d.size(), m.nano.exposures.size());
  ASSERT_EQ(d.size(), stops.size());
  for (size_t i = 0; i < d.size(); i++) {
    EXPECT_EQ(d[i].stop, i);
    EXPECT_EQ(d[i].program, 0);
    EXPECT_FALSE(d[i].cut || d[i].again) << "stop " << i;
    EXPECT_FALSE(d[i].hasPlan);  // a whole F gives what was sent
    if (i) {
      EXPECT_EQ(d[i].exposure, d[i - 1].exposure + 1);
    }
    for (int k = 0; k < 4; k++) {
      EXPECT_EQ(d[i].onUs[k], m.nano.exposures[i].litUs[k]) << "stop " << i << " LED " << k;
      EXPECT_EQ(d[i].onUs[k], stops[i].us[k]) << "stop " << i << " LED " << k;
    }
  }
  // The ESP's port hears them too, and the card keeps them beside the job, line for line.
  EXPECT_EQ(doses(m.espLines).size(), d.size());
  EXPECT_EQ(doseFile(m.sd, "D.UVJ"), doseLines(m.usbLines));
  // Run again from its first stop, the file holds that run's alone.
  const size_t before = m.usbLines.size();
  m.cmd("M23 D.UVJ");
  m.cmd("M24");
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  const Lines again = doseLines(Lines(m.usbLines.begin() + static_cast<long>(before), m.usbLines.end()));
  EXPECT_EQ(again.size(), stops.size());
  EXPECT_EQ(doseFile(m.sd, "D.UVJ"), again);
}

TEST_F(JobTest, AResetThatCutsAStopReportsItsCutLightThenItsLightAgain) {
  uv::JobHeader h;
  Grid g;
  const size_t cut = startLongJobIntoItsLight("L.UVJ", h, g);
  ASSERT_NE(m.nano.lit(), 0);
  m.reset(0);  // its R at start-up cuts the exposure; the Nano keeps the record
  m.cmd("G28");
  m.cmd("M1000");
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  const std::vector<uv::Stop> stops = plan(h, g);
  const std::vector<uv::DoseReport> d = doses(m.usbLines);
  // Every stop once whole; the cut one also once cut, its cut light as the Nano timed it.
  std::map<uint32_t, int> whole, cuts, again;
  for (const uv::DoseReport& r : d) (r.cut ? cuts : whole)[r.stop]++;
  for (const uv::DoseReport& r : d) again[r.stop] += r.again;
  EXPECT_EQ(whole.size(), stops.size());
  for (const auto& [stop, n] : whole) EXPECT_EQ(n, 1) << "stop " << stop;
  ASSERT_EQ(cuts.size(), 1u);
  EXPECT_EQ(cuts.begin()->first, cut);
  EXPECT_EQ(again.at(static_cast<uint32_t>(cut)), 1);
  for (const auto& [stop, n] : again) {
    if (stop != cut) {
      EXPECT_EQ(n, 0) << "stop " << stop;
    }
  }
  const auto cutLine = std::find_if(d.begin(), d.end(), [](const uv::DoseReport& r) { return r.cut; });
  for (int k = 0; k < 4; k++) EXPECT_EQ(cutLine->onUs[k], m.nano.exposures[cut].litUs[k]) << "LED " << k;
  EXPECT_LT(cutLine->onUs[0] + cutLine->onUs[1] + cutLine->onUs[2] + cutLine->onUs[3], 4 * 400000u);
  // The resume added to the dose file: what reached the card before the reset (its last sync), then
  // every line since, each one a host got, in order.
  const Lines file = doseFile(m.sd, "L.UVJ"), host = doseLines(m.usbLines);
  ASSERT_FALSE(file.empty());
  size_t at = 0;
  for (const std::string& l : file) {
    while (at < host.size() && host[at] != l) at++;
    ASSERT_LT(at, host.size()) << "not a host's line, or out of order: " << l;
    at++;
  }
  EXPECT_EQ(file.back(), host.back());
  const std::vector<uv::DoseReport> kept = doses(file);  // the cut stop's light again: after the resume
  EXPECT_TRUE(std::any_of(kept.begin(), kept.end(), [&](const uv::DoseReport& r) { return r.again && r.stop == cut; }));
}

TEST_F(JobTest, AFaultThatCutsAStopReportsItCutAndItsExposureAgainOnContinue) {
  uv::JobHeader h;
  Grid g;
  const size_t cut = startLongJobIntoItsLight("F.UVJ", h, g);
  ASSERT_NE(m.nano.lit(), 0);
  m.nano.setTemps(650);  // over the Nano's own 60 °C: it cuts the light
  ASSERT_NE(runUntilJob({"paused"}), "(none)");
  m.run(100000);
  m.nano.setTemps(300);
  m.run(1200000);
  EXPECT_EQ(payload("M24"), Lines{});
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  const std::vector<uv::DoseReport> d = doses(m.usbLines);
  const auto cutLine = std::find_if(d.begin(), d.end(), [](const uv::DoseReport& r) { return r.cut; });
  ASSERT_NE(cutLine, d.end());
  EXPECT_EQ(cutLine->stop, cut);
  EXPECT_TRUE(cutLine->hasPlan);
  const auto againLine = std::find_if(d.begin(), d.end(), [](const uv::DoseReport& r) { return r.again; });
  ASSERT_NE(againLine, d.end());
  EXPECT_EQ(againLine->stop, cut);
  EXPECT_EQ(d.size(), plan(h, g).size() + 1);
  EXPECT_EQ(doseFile(m.sd, "F.UVJ"), doseLines(m.usbLines));  // the cut line and the again line too
}

TEST_F(DoseScanTest, APassReportsEachProgramAndTheirOnTimesAddUpToItsLight) {
  job(40, 10, 2000);
  ASSERT_TRUE(has(upload("S.UVJ", encode(h, g)), "echo:Done saving file."));
  m.cmd("M23 S.UVJ");
  m.cmd("G28");
  m.cmd("M24");
  const std::string end = runUntilJob({"done", "paused", "failed", "aborted"}, 60000000);
  ASSERT_NE(end.find("JOB:done"), std::string::npos) << end;
  const std::vector<uv::DoseReport> d = doses(m.usbLines);
  ASSERT_FALSE(d.empty());
  uint64_t reported[4] = {}, shone[4] = {};
  std::map<uint32_t, uint16_t> programs;  // per pass, how many, in order from 0
  for (const uv::DoseReport& r : d) {
    EXPECT_FALSE(r.cut || r.again || r.hasPlan);
    EXPECT_EQ(r.program, programs[r.stop]++) << "pass " << r.stop;
    for (int k = 0; k < 4; k++) reported[k] += r.onUs[k];
  }
  EXPECT_EQ(programs.size(), 3u);  // every pass
  EXPECT_EQ(doseFile(m.sd, "S.UVJ"), doseLines(m.usbLines));
  for (const ScanLight& l : m.nano.scanLight) shone[l.led] += l.offUs - l.onUs;
  for (int k = 0; k < 4; k++) EXPECT_NEAR(static_cast<double>(reported[k]), static_cast<double>(shone[k]), 2.0 * static_cast<double>(d.size())) << "LED " << k;
  std::printf("[mega dose] 3 passes: %zu programs reported, LED 0 %llu us reported of %llu us shone\n", d.size(),
              static_cast<unsigned long long>(reported[0]), static_cast<unsigned long long>(shone[0]));
}

// A card that stops taking writes mid-job (full, or pulled): the next line it refuses, the dose
// file's or the checkpoint's, pauses the job with E22 (as any card error), every LED off.
// A card that stops taking some writes while a stop job runs on it.
class CardWriteTest : public JobTest {
 protected:
  // The job running, its first three stops exposed.
  void startAndExposeThree() {
    uv::JobHeader h = header(14, 9, uv::Strategy::Shortest);
    uploadAndStart("W.UVJ", encode(h, pattern(14, 9, 7)));
    for (int i = 0; i < 20000 && m.nano.exposures.size() < 3; i++) m.run(1000);
    ASSERT_GE(m.nano.exposures.size(), 3u);
  }
};

TEST_F(CardWriteTest, ACardThatStopsTakingWritesStopsTheJobDark) {
  ASSERT_NO_FATAL_FAILURE(startAndExposeThree());
  m.sd.failWritesAfter = 0;
  const std::string end = runUntilJob({"failed", "done", "paused"}, 20000000);
  EXPECT_NE(end.find("reason=sd"), std::string::npos) << end;
  EXPECT_EQ(m.nano.lit(), 0);
  bool said = false;
  for (const std::string& l : m.usbLines) said |= l.rfind("FAULT:E22", 0) == 0;
  EXPECT_TRUE(said);
}

// A card that refuses the dose file alone (a bad block under it) while the checkpoint's writes go on:
// the line it refuses pauses the job with E22, every LED off, the stops before it reported.
TEST_F(CardWriteTest, ACardThatRefusesTheDoseFileStopsTheJobDark) {
  ASSERT_NO_FATAL_FAILURE(startAndExposeThree());
  m.sd.refuseWritesTo = "~d";
  const std::string end = runUntilJob({"failed", "done", "paused"}, 20000000);
  EXPECT_EQ(end.rfind("JOB:paused", 0), 0u) << end;
  EXPECT_NE(end.find("reason=sd"), std::string::npos) << end;
  EXPECT_EQ(m.nano.lit(), 0);
  bool said = false;
  for (const std::string& l : m.usbLines) said |= l.rfind("FAULT:E22", 0) == 0;
  EXPECT_TRUE(said);
  EXPECT_TRUE(m.sd.contents("JOB~CKP").size() > 0);  // the checkpoint's writes were taken
}
