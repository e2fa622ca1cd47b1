// Fuzzes the job verifier with job text as an upload delivers it, a record a line. Holds: a job
// that verifies, encoded again from the cells it describes (in format 1, and in format 2 with its
// run-length rows), verifies to the same header and the same cells, and encoding that again gives
// the same text (the encoder's form is a fixed point).
#include <fuzzer/FuzzedDataProvider.h>

#include <string>
#include <vector>

#include "fuzz_checks.h"
#include "job_encoder.h"
#include "job_verifier.h"

namespace {

struct Cells : uv::SegmentSink {
  uint16_t cols = 0;
  std::vector<uint8_t> grid;
  void segment(uint16_t row, uint16_t col, const uint8_t* cells, uint8_t n) override {
    for (uint8_t i = 0; i < n; i++) {
      size_t at = static_cast<size_t>(row) * cols + col + i;
      FUZZ_REQUIRE(at < grid.size(), "a segment outside the grid the header declared");
      grid[at] = cells[i];
    }
  }
};

struct Text : uv::RecordSink {
  std::string text;
  void record(const char* t, uint8_t len) override { text += std::string(t, len) + "\n"; }
};

// Verifies text; fills cells (sized from the header once it is read). Returns the error code.
uint8_t verify(const std::string& text, Cells& cells, uv::JobHeader& header) {
  uv::JobVerifier v(&cells);
  size_t start = 0;
  bool sized = false;
  for (size_t nl; (nl = text.find('\n', start)) != std::string::npos; start = nl + 1) {
    if (nl - start > 255) return 5;
    if (uint8_t e = v.push(text.data() + start, static_cast<uint8_t>(nl - start))) return e;
    if (v.headerDone() && !sized) {
      sized = true;
      cells.cols = v.header().cols;
      size_t n = static_cast<size_t>(v.header().cols) * v.header().rows;
      if (n > (1u << 22)) return 255;  // too big to hold here: the property is not checked
      cells.grid.assign(n, 0);
    }
  }
  if (start != text.size()) return 25;
  uint8_t e = v.finish();
  header = v.header();
  return e;
}

bool sameHeader(const uv::JobHeader& a, const uv::JobHeader& b) {
  bool same = a.cols == b.cols && a.rows == b.rows && a.map == b.map && a.level == b.level && a.byTarget == b.byTarget &&
              a.fullUs == b.fullUs && a.targetUJcm2 == b.targetUJcm2 && a.thermalCoeff == b.thermalCoeff &&
              a.thermalRefDeciC == b.thermalRefDeciC && a.strategy == b.strategy && a.seed == b.seed;
  for (int i = 0; i < 2; i++) same = same && a.pitchUm[i] == b.pitchUm[i] && a.originUm[i] == b.originUm[i];
  for (int k = 0; k < 4; k++)
    same = same && a.irradianceUWcm2[k] == b.irradianceUWcm2[k] && a.gainPermille[k] == b.gainPermille[k] &&
           a.offsets[k][0] == b.offsets[k][0] && a.offsets[k][1] == b.offsets[k][1];
  return same;
}

std::string encode(const uv::JobHeader& h, const std::vector<uint8_t>& grid, uint8_t format = 1) {
  Text out;
  uv::JobEncoder enc(out, format);
  enc.header(h);
  for (uint16_t r = 0; r < h.rows; r++) enc.row(r, grid.data() + static_cast<size_t>(r) * h.cols, h.cols);
  enc.finish();
  return out.text;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);
  Cells first;
  uv::JobHeader h{};
  if (verify(text, first, h) != 0) return 0;
  std::string again = encode(h, first.grid);
  Cells second;
  uv::JobHeader h2{};
  FUZZ_REQUIRE(verify(again, second, h2) == 0, "a verified job, encoded again, does not verify");
  FUZZ_REQUIRE(sameHeader(h, h2), "a verified job's header changed on encoding again");
  FUZZ_REQUIRE(first.grid == second.grid, "a verified job's cells changed on encoding again");
  FUZZ_REQUIRE(encode(h2, second.grid) == again, "the encoder's text is not a fixed point");
  // Format 2 (run-length rows) holds the same: the same cells, a fixed point, never longer than format 1.
  std::string runs = encode(h, first.grid, 2);
  Cells third;
  uv::JobHeader h3{};
  FUZZ_REQUIRE(verify(runs, third, h3) == 0, "a verified job, encoded in format 2, does not verify");
  FUZZ_REQUIRE(sameHeader(h, h3) && first.grid == third.grid, "a verified job changed on encoding in format 2");
  FUZZ_REQUIRE(encode(h3, third.grid, 2) == runs, "the format 2 encoder's text is not a fixed point");
  FUZZ_REQUIRE(runs.size() <= again.size(), "format 2 is longer than format 1");
  return 0;
}
