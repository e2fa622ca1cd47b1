// The streaming gridData walker against a whole-document reference (nlohmann, checked in the
// schema validator's order) on thousands of generated bodies, valid and broken.
#include "grid_rows.h"

#include <gtest/gtest.h>

#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "job_conversion.h"
#include "nlohmann_view.h"

using namespace uv;
using namespace uvtest;
using nlohmann::json;

namespace {

const char* kHeader =
    R"("grid":{"cols":%u,"rows":%u},"pitchUm":{"x":100,"y":100},"originUm":{"x":0,"y":0},)"
    R"("dose":{"map":"linear","fullUs":1000},"leds":{"offsets":[[0,0],[0,1],[0,2],[0,3]]},"strategy":{"name":"raster"})";

struct Outcome {
  int status;
  std::string path;
  std::vector<std::vector<uint8_t>> rows;
};

struct Rows : RecordSink {
  void record(const char*, uint8_t) override {}
};

// What the ESP does: the header without gridData, the rows streamed.
Outcome streamed(const std::string& body) {
  json header = parseWithoutGridData(body);
  if (header.is_discarded()) return {400, "", {}};
  std::istringstream in(body);
  StreamReader reader{in};
  std::vector<uint8_t> cells(kJobMaxSide);
  Rows sink;
  esp::JobConversion<StreamReader> c(reader, sink, cells.data());
  Outcome o{202, "", {}};
  if (!c.begin(View{&header})) return {c.error().status, c.error().path, {}};
  esp::ConversionStep s;
  while ((s = c.step()) == esp::ConversionStep::More) o.rows.emplace_back(cells.begin(), cells.begin() + c.header().cols);
  if (s == esp::ConversionStep::Failed) return {c.error().status, c.error().path, {}};
  return o;
}

bool integral255(const json& v) {
  if (!v.is_number()) return false;
  double d = v.get<double>();
  return d >= 0 && d <= 255 && d == static_cast<double>(static_cast<int>(d));
}

// The whole document in memory, checked as print-request.ts does.
Outcome reference(const std::string& body, unsigned cols, unsigned rows) {
  json j = json::parse(body, nullptr, false);
  if (j.is_discarded()) return {400, "", {}};
  if (!j.contains("gridData")) return {400, "/gridData", {}};
  const json& g = j["gridData"];
  if (!g.is_array() || g.size() != rows) return {400, "/gridData", {}};
  Outcome o{202, "", {}};
  for (unsigned r = 0; r < rows; r++) {
    const json& row = g[r];
    std::string p = "/gridData/" + std::to_string(r);
    if (!row.is_array() || row.size() != cols) return {400, p, {}};
    std::vector<uint8_t> cells;
    for (unsigned c = 0; c < cols; c++) {
      if (!integral255(row[c])) return {400, p + "/" + std::to_string(c), {}};
      cells.push_back(static_cast<uint8_t>(row[c].get<double>()));
    }
    o.rows.push_back(cells);
  }
  return o;
}

std::string cellText(std::mt19937& rng, int& faults, double faultRate) {
  std::uniform_real_distribution<double> u(0, 1);
  int v = static_cast<int>(rng() % 256);
  if (u(rng) < faultRate) {
    faults++;
    switch (rng() % 10) {
      case 0: return "256";
      case 1: return "-1";
      case 2: return "12.5";
      case 3: return "\"7\"";
      case 4: return "null";
      case 5: return "[1]";
      case 6: return "{\"v\":\"]\"}";
      case 7: return std::to_string(v) + ".0";     // fine: integral
      case 8: return "2.55e2";                      // fine: 255
      default: return "-0";                          // fine: 0
    }
  }
  return std::to_string(v);
}

std::string space(std::mt19937& rng) {
  static const char* kSpaces[] = {"", "", "", " ", "\n", "\t ", "\r\n  "};
  return kSpaces[rng() % 7];
}

std::string body(std::mt19937& rng, unsigned cols, unsigned rows, double faultRate) {
  std::uniform_real_distribution<double> u(0, 1);
  int faults = 0;
  unsigned nRows = rows;
  if (u(rng) < faultRate) nRows = rows + (rng() % 2 ? 1 : 0) - (rng() % 2 && rows > 1 ? 1 : 0);
  std::string g = "[";
  for (unsigned r = 0; r < nRows; r++) {
    if (r) g += "," + space(rng);
    if (u(rng) < faultRate / 4) {
      g += rng() % 2 ? "7" : "\"row\"";
      continue;
    }
    unsigned n = cols;
    if (u(rng) < faultRate / 2) n = cols + 1 - (rng() % 3);
    g += "[" + space(rng);
    for (unsigned c = 0; c < n; c++) g += (c ? "," + space(rng) : "") + cellText(rng, faults, faultRate / 8);
    g += space(rng) + "]";
  }
  g += "]";
  char head[512];
  snprintf(head, sizeof head, kHeader, cols, rows);
  std::string name = rng() % 3 == 0 ? R"("name":"gridData",)" : "";  // a value that looks like the key
  switch (rng() % 3) {
    case 0: return "{" + name + "\"gridData\"" + space(rng) + ":" + space(rng) + g + "," + head + "}";
    case 1: return "{" + name + head + ",\"gridData\":" + g + "}";
    default: return "{" + std::string(head) + "," + space(rng) + "\"gridData\":" + g + "," + name + "\"thermal\":{\"coeffCentiPctPerC\":0,\"refDeciC\":250}}";
  }
}

}  // namespace

TEST(GridRows, MatchesAWholeDocumentCheckOnGeneratedBodies) {
  std::mt19937 rng(7);
  int accepted = 0, refused = 0;
  for (int i = 0; i < 3000; i++) {
    unsigned cols = 1 + rng() % 9, rows = 1 + rng() % 6;
    double faultRate = i % 3 == 0 ? 0 : 0.3;
    std::string b = body(rng, cols, rows, faultRate);
    Outcome want = reference(b, cols, rows);
    Outcome got = streamed(b);
    ASSERT_EQ(got.status, want.status) << b << "\n" << got.path;
    ASSERT_EQ(got.path, want.path) << b;
    ASSERT_EQ(got.rows, want.rows) << b;
    (want.status == 202 ? accepted : refused)++;
  }
  EXPECT_GT(accepted, 1000);
  EXPECT_GT(refused, 500);
}

TEST(GridRows, SaysWhereGridDataIsMissingOrNotAnArray) {
  char head[512];
  snprintf(head, sizeof head, kHeader, 2u, 1u);
  EXPECT_EQ(streamed("{" + std::string(head) + "}").path, "/gridData");
  EXPECT_EQ(streamed("{" + std::string(head) + ",\"gridData\":{\"0\":[1,2]}}").path, "/gridData");
  EXPECT_EQ(streamed("{" + std::string(head) + ",\"gridData\":[[1,2]]}").status, 202);
}

TEST(GridRows, ALargeRowIsReadWithoutTheWholeBodyInMemory) {
  // 4096 x 64 (the ESP's cell limit): the walker holds one 4 KB row.
  std::string g = "[";
  for (int r = 0; r < 64; r++) {
    g += r ? ",[" : "[";
    for (int c = 0; c < 4096; c++) g += (c ? "," : "") + std::to_string((r * 7 + c) % 256);
    g += "]";
  }
  g += "]";
  char head[512];
  snprintf(head, sizeof head, kHeader, 4096u, 64u);
  Outcome o = streamed("{" + std::string(head) + ",\"gridData\":" + g + "}");
  ASSERT_EQ(o.status, 202);
  ASSERT_EQ(o.rows.size(), 64u);
  EXPECT_EQ(o.rows[63][4095], (63 * 7 + 4095) % 256);
}
