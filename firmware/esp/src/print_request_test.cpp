// Host tests of POST /print validation and conversion to job text against protocol/vectors/esp.json.
#include "print_request.h"

#include <gtest/gtest.h>

#include <vector>

#include "job_encoder.h"
#include "vectors_fixture.h"

using namespace uv;
using namespace uvtest;

namespace {

const json V = loadVectors("esp.json");
VectorCounter counted("esp.json");

// The JSON view print_request.h expects, over nlohmann (the ESP uses an ArduinoJson one).
struct View {
  const json* j;
  bool isObject() const { return j->is_object(); }
  bool isArray() const { return j->is_array(); }
  bool isString() const { return j->is_string(); }
  bool isInteger() const {
    return j->is_number_integer() || (j->is_number_float() && j->get<double>() == static_cast<double>(static_cast<int64_t>(j->get<double>())));
  }
  int64_t integer() const { return j->is_number_unsigned() ? static_cast<int64_t>(j->get<uint64_t>()) : static_cast<int64_t>(j->get<double>()); }
  const char* string() const { return j->get_ref<const std::string&>().c_str(); }
  size_t size() const { return j->size(); }
  View element(size_t i) const { return View{&(*j)[i]}; }
  bool has(const char* k) const { return j->contains(k); }
  View member(const char* k) const { return View{&j->at(k)}; }
  template <class F>
  void forEachKey(F f) const {
    for (auto it = j->begin(); it != j->end(); ++it)
      if (!f(it.key().c_str())) return;
  }
};

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
    json body = json::parse(c["body"].get<std::string>(), nullptr, false);
    esp::RequestError e{};
    JobHeader h{};
    Text out;
    if (body.is_discarded()) {
      e = {400, "bad_json", "", ""};
    } else if (esp::validateHeader(View{&body}, h, e)) {
      JobEncoder enc(out);
      enc.header(h);
      std::vector<uint8_t> cells(h.cols);
      for (uint16_t r = 0; r < h.rows; r++) {
        if (!esp::validateRow(View{&body}.member("gridData").element(r), r, h, cells.data(), e)) break;
        enc.row(r, cells.data(), h.cols);
      }
      if (!e.status) {
        enc.finish();
        e.status = 202;
      }
    }
    EXPECT_EQ(e.status, c["status"].get<int>()) << name << ": " << e.path << " " << e.message;
    if (e.status == 202) {
      EXPECT_EQ(out.text, c["text"].get<std::string>()) << name;
    } else {
      EXPECT_STREQ(e.code, c["error"].get<std::string>().c_str()) << name;
      if (c.contains("path")) {
        EXPECT_EQ(std::string(e.path), c["path"].get<std::string>()) << name;
      }
    }
    counted();
  }
}
