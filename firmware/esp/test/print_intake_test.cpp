// POST /print from spool to answer, as the ESP and the host hub run it: every esp.json vector
// gets its status and field, and an accepted body starts its upload to the Mega.
#include "print_intake.h"

#include <gtest/gtest.h>

#include <fstream>

#include "host_body.h"
#include "noisy_mega.h"
#include "vectors_fixture.h"

using namespace uv::esp;
using nlohmann::json;

namespace {

struct Hub : esptest::NoisyMega {
  esptest::NoClients clients;
  LiveChannel live{clients};
  Bridge bridge{*this, live};
  std::string spool = std::string(testing::TempDir()) + "intake-body.json";
  uvtest::HostBody body{spool};
  PrintIntake<uvtest::HostBody, uvtest::HostHeaderParse> intake{body, bridge, uvtest::HostHeaderParse{}};
  uint32_t ids = 0;

  void start() {
    mega.begin();
    bridge.begin(nowMs());
    run(1500000);
  }
  void run(uint64_t us) {
    NoisyMega::run(
        us, [&](char c, uint32_t ms) { bridge.received(c, ms); }, [&](uint32_t ms) { bridge.poll(ms); });
  }
  // The body arrives whole; the hub's loop steps the check.
  Intake post(const std::string& text) {
    EXPECT_EQ(bridge.admitPrint(nowMs()), Admission::Accepted);
    std::ofstream(spool, std::ios::binary) << text;
    intake.begin();
    Intake r;
    int steps = 0;
    while ((r = intake.step([&] { return ++ids; })) == Intake::Working) {
      run(1000);  // the loop goes on between steps
      steps++;
    }
    lastSteps = steps;
    return r;
  }
  int lastSteps = 0;
};

}  // namespace

TEST(PrintIntake, EveryVectorGetsItsStatusAndField) {
  const json v = uvtest::loadVectors("esp.json");
  Hub h;
  h.start();
  for (const json& c : v["requests"]) {
    const std::string name = c["name"];
    Intake r = h.post(c["body"].get<std::string>());
    json answer = json::parse(h.intake.response());
    ASSERT_EQ(h.intake.status(), c["status"].get<int>()) << name << ": " << answer;
    if (r == Intake::Accepted) {
      EXPECT_EQ(answer["job"]["state"], "uploading");
      h.bridge.cancel();  // not this test's business: give the Mega back
      for (int i = 0; i < 500 && h.bridge.uploading(); i++) h.run(10000);
      continue;
    }
    EXPECT_EQ(answer["error"]["code"], c["error"]) << name;
    if (c.contains("path")) {
      EXPECT_EQ(answer["error"].value("path", ""), c["path"]) << name;
    }
  }
}

TEST(PrintIntake, ALargeBodyIsCheckedInManyStepsAndUploaded) {
  Hub h;
  h.start();
  h.mega.cmd("G28");
  json j = {{"grid", {{"cols", 256}, {"rows", 128}}},
            {"pitchUm", {{"x", 50}, {"y", 50}}},
            {"originUm", {{"x", 5000}, {"y", 5000}}},
            {"dose", {{"map", "threshold"}, {"level", 100}, {"fullUs", 2000}}},
            {"leds", {{"offsets", {{0, 0}, {0, 1}, {0, 2}, {0, 3}}}}},
            {"strategy", {{"name", "raster"}}}};
  json g = json::array();
  for (int r = 0; r < 128; r++) {
    json row = json::array();
    for (int c = 0; c < 256; c++) row.push_back(((r / 8 + c / 8) % 2) * 255);
    g.push_back(row);
  }
  j["gridData"] = g;
  ASSERT_EQ(h.post(j.dump()), Intake::Accepted);
  EXPECT_GE(h.lastSteps, 3);  // 32768 cells: a share at a time
  EXPECT_EQ(json::parse(h.intake.response())["job"]["cells"], 32768);
  for (int i = 0; i < 30000 && h.bridge.uploading(); i++) h.run(10000);
  ASSERT_EQ(h.bridge.lastUpload()->state, UploadState::Started) << h.bridge.lastUpload()->message;
  EXPECT_EQ(h.bridge.lastUpload()->id, 1u);
  EXPECT_NE(h.mega.sd.contents("JOB1.UVJ").find("\nend "), std::string::npos);
}

TEST(PrintIntake, ABodyStuffedWithFieldsOrCancelledIsRefusedAndTheMegaFreed) {
  Hub h;
  h.start();
  std::string stuffed = R"({"junk":")" + std::string(9000, 'x') + R"("})";
  ASSERT_EQ(h.post(stuffed), Intake::Refused);
  EXPECT_EQ(h.intake.status(), 400);
  EXPECT_EQ(json::parse(h.intake.response())["error"]["code"], "bad_job");
  ASSERT_EQ(h.post("{\"grid\":"), Intake::Refused);
  EXPECT_EQ(json::parse(h.intake.response())["error"]["code"], "bad_json");
  EXPECT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Accepted);  // each refusal gave the Mega back
  h.bridge.release();
  // DELETE while a body is being checked.
  EXPECT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Accepted);
  std::ofstream(h.spool, std::ios::binary) << R"({"grid":{"cols":2,"rows":1}})";
  h.intake.begin();
  EXPECT_TRUE(h.intake.busy());
  h.intake.cancel();
  EXPECT_FALSE(h.intake.busy());
  EXPECT_EQ(h.intake.status(), 409);
  EXPECT_EQ(json::parse(h.intake.response())["error"]["code"], "cancelled");
  EXPECT_EQ(h.bridge.admitPrint(h.nowMs()), Admission::Accepted);
}

// "paced": true starts the job with M24 P1 (mega.md "Pacing"), and the Mega runs it paced; without
// it, or false, the job runs as before.
TEST(PrintIntake, APacedBodyStartsItsJobPaced) {
  for (const char* paced : {"", R"(,"paced":false)", R"(,"paced":true)"}) {
    Hub h;
    h.start();
    h.mega.cmd("G28");
    std::string body = R"({"grid":{"cols":4,"rows":2},"pitchUm":{"x":100,"y":100},"originUm":{"x":10000,"y":10000},)"
                       R"("dose":{"map":"linear","fullUs":4000},"leds":{"offsets":[[0,0],[0,1],[0,2],[0,3]]},)"
                       R"("strategy":{"name":"raster"},"gridData":[[0,1,2,3],[4,5,6,7]])" +
                       std::string(paced) + "}";
    ASSERT_EQ(h.post(body), Intake::Accepted) << paced << ": " << h.intake.response();
    for (int i = 0; i < 3000 && h.bridge.uploading(); i++) h.run(10000);
    ASSERT_EQ(h.bridge.lastUpload()->state, UploadState::Started) << h.bridge.lastUpload()->message;
    std::string running;
    for (int i = 0; i < 500 && running.empty(); i++) {
      h.run(10000);
      for (const std::string& l : h.mega.espLines)
        if (l.rfind("JOB:running", 0) == 0) running = l;
    }
    ASSERT_FALSE(running.empty()) << paced;
    EXPECT_EQ(running.find(" paced=1") != std::string::npos, std::string(paced).find("true") != std::string::npos) << running;
  }
}

// Issue 15, defect 7: the 400 names the field at fault even when its name escapes to six times
// its length (control characters), and the answer is always whole JSON.
TEST(PrintIntake, AnUnknownFieldWithALongEscapedNameIsNamedInWholeJson) {
  Hub h;
  h.start();
  for (const std::string& key : {std::string(47, '\x01'), std::string(23, '\x7f') + std::string(30, '\x1f'), std::string("é") + std::string(46, '\x02'),
                                 std::string("ééééééééééééééééééééééé") + "\x03"}) {
    json body = {{"grid", {{"cols", 1}, {"rows", 1}}}, {key, 1}};
    ASSERT_EQ(h.post(body.dump()), Intake::Refused);
    EXPECT_EQ(h.intake.status(), 400);
    json answer = json::parse(h.intake.response(), nullptr, false);
    ASSERT_FALSE(answer.is_discarded()) << h.intake.response();
    EXPECT_EQ(answer["error"]["code"], "bad_job");
    std::string path = "/" + key;
    EXPECT_EQ(answer["error"]["path"], path.substr(0, 47));
  }
}

// Issue 15, defect 8: a number no int64 holds is refused as out of range, never cast.
TEST(PrintIntake, ANumberBeyondAnyIntegerIsOutOfRange) {
  Hub h;
  h.start();
  for (const char* cols : {"1e300", "-1e300", "18446744073709551615", "9223372036854775808", "1.5e19"}) {
    std::string body = R"({"grid":{"cols":4,"rows":2},"pitchUm":{"x":100,"y":100},"originUm":{"x":10000,"y":10000},)"
                       R"("dose":{"map":"linear","fullUs":4000},"leds":{"offsets":[[0,0],[0,1],[0,2],[0,3]]},)"
                       R"("strategy":{"name":"raster"},"gridData":[[0,1,2,3],[4,5,6,7]]})";
    body.replace(body.find("4,"), 1, cols);
    ASSERT_EQ(h.post(body), Intake::Refused) << cols;
    json answer = json::parse(h.intake.response());
    EXPECT_EQ(answer["error"]["path"], "/grid/cols") << cols;
  }
}

namespace {

// A filled job as its body, at 60 µm.
std::string filledBody(int cols, int rows) {
  std::string row = "[255";
  for (int c = 1; c < cols; c++) row += ",255";
  row += "]";
  std::string body = "{\"grid\":{\"cols\":" + std::to_string(cols) + ",\"rows\":" + std::to_string(rows) +
                     "},\"pitchUm\":{\"x\":60,\"y\":60},\"originUm\":{\"x\":10000,\"y\":10000},"
                     "\"dose\":{\"map\":\"threshold\",\"level\":128,\"fullUs\":4000},\"leds\":{\"offsets\":[[0,0],[0,1],[0,2],[0,3]]},"
                     "\"strategy\":{\"name\":\"serpentine\"},\"gridData\":[";
  for (int r = 0; r < rows; r++) body += (r ? "," : "") + row;
  return body + "]}";
}

}  // namespace

// Issue 41: a Mega whose M115 says Cap:JOB_FORMAT:2 gets format 2 (run-length rows where shorter),
// and the upload's bytes count that text; one whose M115 says no such cap gets format 1.
TEST(PrintIntake, TheHubWritesTheJobFormatTheMegaSaysItReads) {
  for (bool older : {false, true}) {
    Hub h;
    h.start();
    if (older) {  // an older Mega's M115 answer: its name and no Cap:JOB_FORMAT
      for (char c : std::string("FIRMWARE_NAME:UVExposure 0.0.9 (Mega) PROTOCOL_VERSION:1\n")) h.bridge.received(c, h.nowMs());
    }
    EXPECT_EQ(h.bridge.jobFormat(), older ? 1 : 2);
    h.mega.cmd("G28");
    ASSERT_EQ(h.post(filledBody(120, 40)), Intake::Accepted) << h.intake.response();
    for (int i = 0; i < 30000 && h.bridge.uploading(); i++) h.run(10000);
    const UploadProgress* p = h.bridge.lastUpload();
    ASSERT_EQ(p->state, UploadState::Started) << p->message;
    const std::string card = h.mega.sd.contents("JOB1.UVJ");
    EXPECT_EQ(card.rfind(older ? "uvj 1\n" : "uvj 2\n", 0), 0u);
    EXPECT_EQ(card.find("\nrl 0 0 120xff\n") != std::string::npos, !older);
    EXPECT_EQ(p->bytesTotal, card.size());
    EXPECT_EQ(p->bytesSent, card.size());
    EXPECT_EQ(p->bytesVerified, card.size());
  }
}

// The bytes the hub sends the Mega for a filled 30 x 30 mm job, in each format: the job text
// (bytesTotal) and every byte on the UART (line numbers, checksums, M28/M29). At 60 µm: 500 x 500
// cells, as 50 µm's 600 x 600 is over the hub's 262 144 cells.
TEST(PrintIntake, AFilled30mmJobInEachFormat) {
  uint64_t wire[2] = {};
  for (bool older : {true, false}) {
    Hub h;
    h.start();
    if (older) {
      for (char c : std::string("FIRMWARE_NAME:UVExposure 0.0.9 (Mega) PROTOCOL_VERSION:1\n")) h.bridge.received(c, h.nowMs());
    }
    h.mega.cmd("G28");
    ASSERT_EQ(h.post(filledBody(500, 500)), Intake::Accepted) << h.intake.response();
    const uint64_t before = h.written;
        for (int i = 0; i < 200000 && h.bridge.uploading(); i++) h.run(10000);
    const UploadProgress* p = h.bridge.lastUpload();
    ASSERT_EQ(p->state, UploadState::Started) << p->message;
    std::printf("[esp upload] filled 30 x 30 mm at 60 um (500 x 500 cells), format %u: %u bytes of job text, %llu bytes on the UART\n",
                older ? 1u : 2u, p->bytesTotal, static_cast<unsigned long long>(h.written - before));
    wire[older ? 0 : 1] = h.written - before;
  }
  EXPECT_LT(wire[1] * 20, wire[0]);  // a filled row is one `rl` record in place of 16 `r` records
}
