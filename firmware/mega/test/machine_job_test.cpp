// Jobs end to end on a whole simulated Mega: upload with every record checked, planning onto the
// card, running through the printhead (the real Nano logic), pause, continue, abort, and the
// checks that keep a bad upload from ever running.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "machine_job_fixture.h"

using namespace mega;

using namespace jobs;

TEST_F(JobTest, UploadedPlannedAndRunStopByStopExactlyAsThePlannerSays) {
  uv::JobHeader h = header(14, 9, uv::Strategy::Shortest);
  Grid g = pattern(14, 9, 7);
  Lines got = upload("PCB.UVJ", encode(h, g));
  EXPECT_TRUE(has(got, "echo:Writing to file: PCB.UVJ"));
  EXPECT_TRUE(has(got, "echo:Done saving file."));
  EXPECT_FALSE(has(got, "Error:") || has(got, "echo:E"));
  Lines list = payload("M20");
  ASSERT_EQ(list.size(), 3u);  // the working files are not listed
  EXPECT_EQ(list[1].rfind("PCB.UVJ ", 0), 0u);
  EXPECT_EQ(payload("M23 PCB.UVJ")[1], "File selected");
  EXPECT_EQ(payload("M24"), (Lines{"echo:E14 axis not homed: home first (G28)"}));
  m.cmd("G28");
  EXPECT_EQ(payload("M24"), Lines{});
  std::string done = runUntilJob({"done"});
  std::vector<uv::Stop> stops = plan(h, g);
  EXPECT_EQ(done.rfind("JOB:done file=PCB.UVJ stop=" + std::to_string(stops.size()) + "/" + std::to_string(stops.size()), 0), 0u) << done;
  std::printf("[mega job] %zu stops of a 14x9 job exposed as planned in %.2f simulated s\n", stops.size(), m.nowUs / 1e6);
  expectExposed(h, stops);
  EXPECT_FALSE(m.sd.exists(kCheckpointFile));  // nothing to resume
  EXPECT_EQ(payload("M1000 S"), (Lines{"JOB:idle"}));
  EXPECT_EQ(m.sd.contents("PCB.UVJ").size(), [&] {
    size_t n = 0;
    for (const std::string& r : encode(h, g)) n += r.size() + 1;
    return n;
  }());
}

TEST_F(JobTest, AFormat2JobOfRunLengthRowsIsSpooledAndExposedAsPlanned) {
  uv::JobHeader h = header(60, 9, uv::Strategy::Serpentine);
  Grid g = runs(60, 9, 5);
  Lines records = encode(h, g, 2);
  EXPECT_EQ(records[0], "uvj 2");
  EXPECT_TRUE(std::any_of(records.begin(), records.end(), [](const std::string& r) { return r.rfind("rl ", 0) == 0; }));
  EXPECT_LT(records.size(), encode(h, g).size());
  ASSERT_TRUE(has(uploadAndStart("RL.UVJ", records), "echo:Done saving file."));
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  expectExposed(h, plan(h, g));
}

TEST_F(JobTest, EveryStrategyRunsAsPlanned) {
  for (uv::Strategy s : {uv::Strategy::Raster, uv::Strategy::Serpentine, uv::Strategy::Random}) {
    uv::JobHeader h = header(11, 7, s);
    h.seed = 99;
    Grid g = pattern(11, 7, static_cast<uint32_t>(s) + 3);
    size_t from = m.nano.exposures.size();
    ASSERT_TRUE(has(uploadAndStart("J.UVJ", encode(h, g)), "echo:Done saving file."));
    ASSERT_NE(runUntilJob({"done"}), "(none)");
    expectExposed(h, plan(h, g), from);
  }
}

TEST_F(JobTest, AMalformedRecordFailsTheUploadAndNothingIsKept) {
  uv::JobHeader h = header(8, 4, uv::Strategy::Raster);
  Lines records = encode(h, pattern(8, 4, 1));
  records[11][records[11].size() - 1] = 'G';  // a hex digit that is not one
  Lines got = upload("BAD.UVJ", records);
  EXPECT_TRUE(has(got, "echo:E23 job record malformed: line 12"));
  EXPECT_FALSE(has(got, "echo:Done saving file."));
  EXPECT_FALSE(m.sd.exists("BAD.UVJ"));
  EXPECT_FALSE(m.sd.exists("BAD.UVJ~c"));
  EXPECT_FALSE(m.sd.exists("BAD.UVJ~i"));
  EXPECT_EQ(payload("M23 BAD.UVJ"), (Lines{"echo:E21 file not found: BAD.UVJ"}));
}

TEST_F(JobTest, AWrongHashOrAMissingEndFailsAtM29) {
  uv::JobHeader h = header(8, 4, uv::Strategy::Raster);
  Lines records = encode(h, pattern(8, 4, 2));
  Lines wrongHash = records;
  wrongHash.back()[wrongHash.back().size() - 1] = wrongHash.back().back() == '0' ? '1' : '0';
  EXPECT_TRUE(has(upload("H.UVJ", wrongHash), "echo:E24"));
  EXPECT_FALSE(m.sd.exists("H.UVJ"));
  Lines cut(records.begin(), records.end() - 3);
  EXPECT_TRUE(has(upload("C.UVJ", cut), "echo:E25"));
  EXPECT_FALSE(m.sd.exists("C.UVJ"));
  EXPECT_EQ(payload("M29"), (Lines{"echo:E11 bad or missing parameter: not uploading"}));
}

TEST_F(JobTest, AJobCopiedOntoTheCardByAPcIsVerifiedAndPlannedWhenSelected) {
  uv::JobHeader h = header(10, 6, uv::Strategy::Serpentine);
  Grid g = pattern(10, 6, 5);
  std::string text;
  for (const std::string& r : encode(h, g)) text += r + "\n";
  m.sd.put("COPIED.UVJ", text);
  Lines sel = payload("M23 COPIED.UVJ");
  EXPECT_EQ(sel[1], "File selected");
  m.cmd("G28");
  m.cmd("M24");
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  expectExposed(h, plan(h, g));
  // A damaged copy is refused and stays on the card, untouched.
  text[text.size() - 3] = text[text.size() - 3] == 'a' ? 'b' : 'a';
  m.sd.put("DAMAGED.UVJ", text);
  EXPECT_TRUE(has(payload("M23 DAMAGED.UVJ"), "echo:E24"));
  EXPECT_TRUE(m.sd.exists("DAMAGED.UVJ"));
  EXPECT_FALSE(m.sd.exists("DAMAGED.UVJ~c"));
}

TEST_F(JobTest, PauseWaitsForTheStopContinueGoesOnAbortEndsItDark) {
  uv::JobHeader h = header(16, 12, uv::Strategy::Raster);
  Grid g = pattern(16, 12, 9);
  uploadAndStart("P.UVJ", encode(h, g));
  m.run(300000);
  m.cmd("M25");
  std::string paused = runUntilJob({"paused"});
  EXPECT_NE(paused.find("reason=user"), std::string::npos) << paused;
  size_t fired = m.nano.exposures.size();
  m.run(2000000);
  EXPECT_EQ(m.nano.exposures.size(), fired);  // nothing while paused
  EXPECT_EQ(m.nano.lit(), 0);
  m.cmd("M24");
  m.run(300000);
  EXPECT_GT(m.nano.exposures.size(), fired);
  size_t before = m.nano.lines.size();
  m.cmd("M524");
  EXPECT_TRUE(std::count(m.nano.lines.begin() + static_cast<long>(before), m.nano.lines.end(), "R") >= 1);
  EXPECT_EQ(m.nano.lit(), 0);
  size_t at = m.nano.exposures.size();
  m.run(1000000);
  EXPECT_EQ(m.nano.exposures.size(), at);
  EXPECT_EQ(payload("M27")[0].rfind("JOB:aborted", 0), 0u);
  EXPECT_FALSE(m.sd.exists(kCheckpointFile));
  // Every stop exposed so far was one of the plan's, each once, in order; the abort may have come
  // inside the last one's light, which then ended dark at once, short of its time.
  std::vector<uv::Stop> stops = plan(h, g);
  const Exposure& last = m.nano.exposures.back();
  bool cut = false;
  for (int k = 0; k < 4; k++) cut = cut || last.litUs[k] < last.askedUs[k];
  if (cut) {
    m.nano.exposures.pop_back();
    m.firedAt.pop_back();
    at--;
  }
  stops.resize(at);
  expectExposed(h, stops);
}

TEST_F(JobTest, ThePanelsPauseButtonPausesBetweenStopsAndContinues) {
  uv::JobHeader h = header(16, 12, uv::Strategy::Raster);
  Grid g = pattern(16, 12, 6);
  uploadAndStart("B.UVJ", encode(h, g));
  m.run(300000);
  size_t from = m.usbLines.size();
  m.io.pressed = kButtonPause;
  m.run(40000);
  m.io.pressed = 0;
  m.run(200000);  // the stop under way ends first
  Lines after(m.usbLines.begin() + static_cast<long>(from), m.usbLines.end());
  EXPECT_TRUE(has(after, "JOB:paused")) << "no pause";
  size_t fired = m.nano.exposures.size();
  m.run(1000000);
  EXPECT_EQ(m.nano.exposures.size(), fired);
  m.io.pressed = kButtonPause;
  m.run(40000);
  m.io.pressed = 0;
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  expectExposed(h, plan(h, g));
}

TEST_F(JobTest, AnOverTemperatureMidJobPausesItAndItContinuesOnceCool) {
  uv::JobHeader h = header(16, 12, uv::Strategy::Raster);
  Grid g = pattern(16, 12, 4);
  uploadAndStart("T.UVJ", encode(h, g));
  m.run(200000);
  m.nano.setTemps(560);  // over the Mega's 55 °C soft limit, under the Nano's 60
  std::string paused = runUntilJob({"paused"});
  EXPECT_NE(paused.find("reason=overtemp"), std::string::npos) << paused;
  EXPECT_TRUE(has(m.usbLines, "FAULT:E31"));
  EXPECT_TRUE(has(payload("M24"), "Error:E31"));
  m.nano.setTemps(300);
  m.run(1200000);
  EXPECT_EQ(payload("M24"), Lines{});
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  expectExposed(h, plan(h, g));
}

TEST_F(JobTest, AJobUploadedThroughTheEspPortRunsAndAHostThatGoesSilentPausesIt) {
  uv::JobHeader h = header(12, 12, uv::Strategy::Raster);
  h.map = uv::DoseMap::Threshold;  // every lit cell its full 1.5 s: 30 s pass mid-job
  h.level = 1;
  h.fullUs = 1500000;
  Grid g = pattern(12, 12, 17);
  ASSERT_TRUE(has(m.cmd("M28 E.UVJ", true), "echo:Writing to file: E.UVJ"));
  for (const std::string& r : encode(h, g)) m.cmd(r, true);
  ASSERT_TRUE(has(m.cmd("M29", true), "echo:Done saving file."));
  m.cmd("M23 E.UVJ", true);
  m.cmd("G28", true);
  m.cmd("M24", true);
  // No line from either host for 30 s while it runs: the host is gone, so the job pauses.
  std::string paused = runUntilJob({"paused"}, 40000000);
  EXPECT_NE(paused.find("reason=host"), std::string::npos) << paused;
  EXPECT_GE(m.nowUs, 30000000u);
  EXPECT_EQ(m.nano.lit(), 0);
  m.cmd("M24", true);  // a host is back and continues it
  ASSERT_NE(runUntilJob({"done"}, 600000000), "(none)");
  expectExposed(h, plan(h, g));
}

TEST_F(JobTest, M1000CDiscardsAnInterruptedJob) {
  uploadAndStart("K.UVJ", encode(header(8, 8, uv::Strategy::Raster), pattern(8, 8, 1)));
  m.run(300000);
  m.reset(200000);
  EXPECT_EQ(payload("M1000 S")[0].rfind("JOB:interrupted file=K.UVJ", 0), 0u);
  EXPECT_EQ(payload("M1000 C"), Lines{});
  EXPECT_EQ(payload("M1000 S"), (Lines{"JOB:idle"}));
  m.cmd("G28");
  EXPECT_EQ(payload("M1000"), (Lines{"echo:E27 no interrupted job to resume"}));
}

TEST_F(JobTest, AJobWhoseLedRowsSpreadTooFarForTheMegasPlannerIsRefusedNotRunEmpty) {
  uv::JobHeader h = header(4, 4, uv::Strategy::Raster);
  h.offsets[3][1] = 1024;  // valid for job.md, beyond the C++ planner's 1024-row window
  Lines got = upload("W.UVJ", encode(h, pattern(4, 4, 1)));
  EXPECT_TRUE(has(got, "echo:E23 job record malformed: the LEDs' rows span 1024 rows or more"));
  EXPECT_FALSE(has(got, "echo:Done saving file."));
  EXPECT_FALSE(m.sd.exists("W.UVJ~s"));
}

TEST_F(JobTest, M30DeletesAJobAndItsWorkingFiles) {
  upload("D.UVJ", encode(header(4, 4, uv::Strategy::Raster), pattern(4, 4, 3)));
  EXPECT_TRUE(m.sd.exists("D.UVJ~s"));
  EXPECT_EQ(payload("M30 D.UVJ"), Lines{});
  EXPECT_FALSE(m.sd.exists("D.UVJ"));
  EXPECT_FALSE(m.sd.exists("D.UVJ~s"));
  EXPECT_EQ(payload("M30 D.UVJ"), (Lines{"echo:E21 file not found: D.UVJ"}));
}

TEST_F(JobTest, WithoutACardJobCommandsSayE20) {
  m.sd.inserted = false;
  EXPECT_EQ(payload("M28 X.UVJ"), (Lines{"echo:E20 no SD card"}));
  EXPECT_EQ(payload("M20"), (Lines{"echo:E20 no SD card"}));
}

namespace {

}  // namespace

TEST_F(JobTest, ResetsAtRandomPointsResumeAndExposeEveryStopExactlyOnce) {
  uv::JobHeader h = header(24, 16, uv::Strategy::Shortest);
  Grid g = pattern(24, 16, 21);
  std::vector<uv::Stop> stops = plan(h, g);
  ASSERT_TRUE(has(uploadAndStart("R.UVJ", encode(h, g)), "echo:Done saving file."));
  uint32_t seed = 5;
  auto rnd = [&seed](uint32_t n) {
    seed = seed * 1664525u + 1013904223u;
    return (seed >> 8) % n;
  };
  int resets = 0;
  for (int i = 0; i < 40; i++) {
    m.run(2000 + rnd(60000));
    if (i % 3 == 2) {  // and every third time right in an exposure, the LEDs on
      for (int t = 0; t < 200000 && !m.nano.lit() && !has(m.usbLines, "JOB:done"); t++) m.run(100);
    }
    if (has(m.usbLines, "JOB:done")) break;
    // Somewhere in a move, a settle, an exposure, a checkpoint write: the Mega restarts, and is
    // back 0.1-1.5 s later with the Nano still powered.
    m.reset(100000 + rnd(1400000));
    resets++;
    ASSERT_EQ(m.usbLines.back(), "start");
    Lines status = payload("M1000 S");
    ASSERT_EQ(status.size(), 1u);
    ASSERT_EQ(status[0].rfind("JOB:interrupted file=R.UVJ stop=", 0), 0u) << status[0];
    m.cmd("G28");
    size_t verdicts = static_cast<size_t>(std::count_if(m.usbLines.begin(), m.usbLines.end(), [](const std::string& l) { return l.rfind("echo:resume:", 0) == 0; }));
    EXPECT_EQ(payload("M1000"), Lines{});
    for (int t = 0; t < 1000; t++) {  // the judgement comes once the Nano has answered C
      if (static_cast<size_t>(std::count_if(m.usbLines.begin(), m.usbLines.end(), [](const std::string& l) { return l.rfind("echo:resume:", 0) == 0; })) > verdicts) break;
      m.run(1000);
    }
  }
  if (!has(m.usbLines, "JOB:done")) {
    ASSERT_NE(runUntilJob({"done"}), "(none)");
  }
  EXPECT_GE(resets, 3);
  long notSent = std::count_if(m.usbLines.begin(), m.usbLines.end(), [](const std::string& l) { return l.find("had not been sent") != std::string::npos; });
  long whole = std::count_if(m.usbLines.begin(), m.usbLines.end(), [](const std::string& l) { return l.find("had been exposed whole") != std::string::npos; });
  std::printf("[mega resume] %d restarts at random points (%ld before a stop was sent, %ld after it was exposed), %zu stops each exposed once\n",
              resets, notSent, whole, stops.size());
  EXPECT_EQ(notSent + whole, resets);
  EXPECT_FALSE(has(m.usbLines, "echo:resume: stop") && has(m.usbLines, "exposed again"));
  expectExposed(h, stops);  // each stop once, in order, where the planner put it
}

TEST_F(JobTest, AResetThatCutsAnExposureShortSaysSoAndExposesItAgain) {
  uv::JobHeader h;
  Grid g;
  size_t cut = startLongJobIntoItsLight("L.UVJ", h, g);
  ASSERT_NE(m.nano.lit(), 0);
  m.reset(0);  // back at once: its R at start-up cuts the exposure
  EXPECT_EQ(m.nano.lit(), 0);
  EXPECT_LT(m.nano.exposures[cut].litUs[0] + m.nano.exposures[cut].litUs[1] + m.nano.exposures[cut].litUs[2] +
                m.nano.exposures[cut].litUs[3],
            4 * 400000u);
  m.cmd("G28");
  m.cmd("M1000");
  m.run(50000);
  EXPECT_TRUE(has(m.usbLines, "echo:resume: stop " + std::to_string(cut) + " was cut short, and is exposed again"));
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  // The cut exposure, then the whole plan from that stop on.
  std::vector<uv::Stop> stops = plan(h, g);
  ASSERT_EQ(m.nano.exposures.size(), stops.size() + 1);
  m.nano.exposures.erase(m.nano.exposures.begin() + static_cast<long>(cut));
  m.firedAt.erase(m.firedAt.begin() + static_cast<long>(cut));
  expectExposed(h, stops);
}

TEST_F(JobTest, APowerCutResumesAndNamesTheStopThatMayHaveBeenCut) {
  uv::JobHeader h = header(16, 8, uv::Strategy::Serpentine);
  Grid g = pattern(16, 8, 13);
  std::vector<uv::Stop> stops = plan(h, g);
  uploadAndStart("W.UVJ", encode(h, g));
  m.run(500000);
  size_t before = m.nano.exposures.size();
  bool litAtCut = m.nano.lit() != 0;
  m.reset(300000, true);  // the Nano loses power too
  Lines status = payload("M1000 S");
  ASSERT_EQ(status[0].rfind("JOB:interrupted file=W.UVJ stop=", 0), 0u);
  uint32_t next = static_cast<uint32_t>(std::stoul(status[0].substr(status[0].find("stop=") + 5)));
  m.cmd("G28");
  m.cmd("M1000");
  m.run(50000);
  EXPECT_TRUE(has(m.usbLines, "echo:resume: stop " + std::to_string(next) + " may have been cut short by the printhead's restart"));
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  // Stops before the checkpoint once; from it on, the plan again. The one stop in between, if it
  // was under way when the power went, got its partial light and then its whole.
  ASSERT_GE(next, before - 1);
  size_t extra = m.nano.exposures.size() - stops.size();
  EXPECT_LE(extra, 1u);
  if (extra) {
    EXPECT_TRUE(litAtCut || next + 1 == before);
    m.nano.exposures.erase(m.nano.exposures.begin() + static_cast<long>(next));
    m.firedAt.erase(m.firedAt.begin() + static_cast<long>(next));
  }
  expectExposed(h, stops);
}

TEST_F(JobTest, AnUploadTakesRecordsOnlyFromItsPortAndCommandsStillRunBetweenThem) {
  // The ESP uploads while the USB host polls, and the ESP's own console asks between records.
  uv::JobHeader h = header(12, 8, uv::Strategy::Raster);
  Grid g = pattern(12, 8, 4);
  Lines records = encode(h, g);
  Lines got = m.cmd("M28 SHARED.UVJ", true);
  EXPECT_TRUE(has(got, "echo:Writing to file: SHARED.UVJ"));
  for (size_t i = 0; i < records.size(); i++) {
    Lines b = m.cmd(records[i], true);
    got.insert(got.end(), b.begin(), b.end());
    if (i % 5 == 0) {
      EXPECT_TRUE(has(m.cmd("M105"), "T:"));                      // the other port
      EXPECT_TRUE(has(m.cmd("M114", true), "X:"));                // a command on the upload's own port
      EXPECT_TRUE(has(m.cmd("M28 OTHER.UVJ"), "echo:E12"));      // one upload at a time
      EXPECT_TRUE(has(m.cmd("M29"), "echo:E12"));                // nor is it the other port's to end
    }
  }
  Lines end = m.cmd("M29", true);
  EXPECT_TRUE(has(end, "echo:Done saving file.")) << end.back();
  EXPECT_FALSE(has(got, "Error:") || has(got, "echo:E"));
  std::string text;
  for (const std::string& r : records) text += r + "\n";
  EXPECT_EQ(m.sd.contents("SHARED.UVJ"), text);
  EXPECT_FALSE(m.sd.exists("OTHER.UVJ"));
}

TEST_F(JobTest, APlainLineDuringAnUploadIsRefusedNotRecorded) {
  // A damaged byte that becomes '\n' splits a numbered record; its tail arrives as a plain line.
  uv::JobHeader h = header(8, 4, uv::Strategy::Raster);
  Lines records = encode(h, pattern(8, 4, 3));
  m.cmd("M28 SPLIT.UVJ");
  for (size_t i = 0; i < records.size(); i++) {
    if (i == 4) {
      m.usb.toMega += "2#3932\n";
      m.run(20000);
      EXPECT_TRUE(std::find(m.usbLines.begin(), m.usbLines.end(), "Error:E4 checksum without line number: a job record needs a line number") !=
                  m.usbLines.end())
          << m.usbLines[m.usbLines.size() - 2];
    }
    m.cmd(records[i]);
  }
  EXPECT_TRUE(has(m.cmd("M29"), "echo:Done saving file."));
  std::string text;
  for (const std::string& r : records) text += r + "\n";
  EXPECT_EQ(m.sd.contents("SPLIT.UVJ"), text);
}
