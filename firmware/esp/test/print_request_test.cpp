// Host tests of POST /print validation and conversion to job text against protocol/vectors/esp.json.
#include "print_request.h"

#include <gtest/gtest.h>

#include <sstream>
#include <vector>

#include "job_conversion.h"
#include "nlohmann_view.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace {

const json V = loadVectors("esp.json");
VectorCounter counted("esp.json");

struct Text : RecordSink {
  std::string text;
  void record(const char* t, uint8_t len) override { text += std::string(t, len) + "\n"; }
};

}  // namespace

TEST(EspVectors, Limits) {
  EXPECT_EQ(esp::kMaxBody, V["maxBody"].get<uint32_t>());
  EXPECT_EQ(esp::kMaxCells, V["maxCells"].get<uint32_t>());
  esp::RequestError e{};
  EXPECT_FALSE(esp::bodyTooLarge(esp::kMaxBody, e));
  EXPECT_TRUE(esp::bodyTooLarge(esp::kMaxBody + 1, e));
  EXPECT_EQ(e.status, 413);
  counted();
}

TEST(EspVectors, PrintRequests) {
  for (const json& c : V["requests"]) {
    const std::string name = c["name"];
    // As on the ESP: the header from a parse without gridData, the rows streamed from the body.
    const std::string text = c["body"].get<std::string>();
    json header = parseWithoutGridData(text);
    esp::RequestError e{};
    Text out;
    std::istringstream in(text);
    StreamReader reader{in};
    std::vector<uint8_t> cells(kJobMaxSide);
    esp::JobConversion<StreamReader> conversion(reader, out, cells.data());
    if (header.is_discarded()) {
      e = {400, "bad_json", "", ""};
    } else if (!conversion.begin(View{&header})) {
      e = conversion.error();
    } else {
      esp::ConversionStep s;
      while ((s = conversion.step()) == esp::ConversionStep::More) {
      }
      e = conversion.error();
      if (s == esp::ConversionStep::Done) {
        e.status = 202;
        EXPECT_EQ(conversion.textBytes(), out.text.size()) << name;
      }
    }
    EXPECT_EQ(e.status, c["status"].get<int>()) << name << ": " << e.path << " " << e.message;
    if (e.status == 202) {
      EXPECT_EQ(out.text, c["text"].get<std::string>()) << name;
      EXPECT_EQ(conversion.paced(), c.at("paced").get<bool>()) << name;  // beside the job, not in its text
    } else {
      EXPECT_STREQ(e.code, c["error"].get<std::string>().c_str()) << name;
      if (c.contains("path")) {
        EXPECT_EQ(std::string(e.path), c["path"].get<std::string>()) << name;
      }
    }
    counted();
  }
}
