// A scan job (strategy `scan`, exposure on the move) uploaded to the card: this firmware runs scan
// jobs only as streams (machine_scan_stream_test.cpp), so it refuses it before any light with E29,
// and the machine stays fine for the next job.
#include <gtest/gtest.h>

#include "machine_job_fixture.h"

using namespace mega;
using namespace jobs;

namespace {

bool startsWith(const Lines& lines, const std::string& prefix) {
  for (const std::string& l : lines)
    if (l.rfind(prefix, 0) == 0) return true;
  return false;
}

}  // namespace

TEST_F(JobTest, AnUploadedScanJobIsRefusedWithE29AndNothingIsPlannedOrLit) {
  uv::JobHeader h = header(12, 6, uv::Strategy::Scan);
  Lines got = uploadAndStart("SCAN.UVJ", encode(h, pattern(12, 6, 4)));
  EXPECT_TRUE(has(got, "echo:E29 scan jobs need newer Mega firmware")) << ::testing::PrintToString(got);
  EXPECT_FALSE(m.sd.exists("SCAN.UVJ~s"));  // no stop file half-built
  EXPECT_FALSE(m.sd.exists("SCAN.UVJ~c"));
  m.run(2000000);
  EXPECT_TRUE(m.nano.exposures.empty());
  EXPECT_EQ(m.nano.lit(), 0);
  EXPECT_FALSE(startsWith(m.usbLines, "JOB:running"));
  // Selecting it again refuses it again; nothing is left selected to start.
  EXPECT_TRUE(has(m.cmd("M23 SCAN.UVJ"), "echo:E29 scan jobs need newer Mega firmware"));
  EXPECT_EQ(payload("M24"), (Lines{"echo:E26 no job selected"}));
  // A stop-and-fire job runs as before.
  uv::JobHeader r = header(8, 4, uv::Strategy::Raster);
  Grid g = pattern(8, 4, 2);
  Lines second = uploadAndStart("R.UVJ", encode(r, g));
  ASSERT_TRUE(has(second, "echo:Done saving file.")) << ::testing::PrintToString(second);
  ASSERT_NE(runUntilJob({"done"}), "(none)");
  expectExposed(r, plan(r, g));
}
