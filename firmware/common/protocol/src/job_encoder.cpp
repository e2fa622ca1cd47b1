// Encodes a job header and rows of cells as the canonical job text of protocol/job.md, one record at a time.
#include "job_encoder.h"

#include <string.h>

#include "crc32.h"
#include "text_scan.h"

namespace uv {

namespace {

// Builds one record with single spaces between fields.
struct Record {
  char buf[84];
  uint8_t n = 0;
  void word(const char* s) {
    if (n) buf[n++] = ' ';
    size_t k = strlen(s);
    memcpy(buf + n, s, k);
    n = static_cast<uint8_t>(n + k);
  }
  void num(int32_t v) {
    if (n) buf[n++] = ' ';
    n = static_cast<uint8_t>(n + putSigned(v, buf + n));
  }
  void u32(uint32_t v) {
    if (n) buf[n++] = ' ';
    n = static_cast<uint8_t>(n + putUnsigned(v, buf + n));
  }
};

}  // namespace

void JobEncoder::emit(const char* text, uint8_t len) {
  crc_ = crc32Update(crc_, text, len);
  crc_ = crc32Update(crc_, "\n", 1);
  sink_.record(text, len);
}

void JobEncoder::header(const JobHeader& h) {
  crc_ = 0;
  Record r;
  auto flush = [&]() {
    r.buf[r.n] = '\0';
    emit(r.buf, r.n);
    r.n = 0;
  };
  r.word("uvj");
  r.num(1);
  flush();
  r.word("grid");
  r.num(h.cols);
  r.num(h.rows);
  flush();
  r.word("pitch");
  r.u32(h.pitchUm[0]);
  r.u32(h.pitchUm[1]);
  flush();
  r.word("origin");
  r.u32(h.originUm[0]);
  r.u32(h.originUm[1]);
  flush();
  r.word("map");
  if (h.map == DoseMap::Linear) {
    r.word("linear");
  } else {
    r.word("threshold");
    r.num(h.level);
  }
  flush();
  if (h.byTarget) {
    r.word("target");
    r.u32(h.targetUJcm2);
    for (uint8_t i = 0; i < 4; i++) r.u32(h.irradianceUWcm2[i]);
  } else {
    r.word("full");
    r.u32(h.fullUs);
  }
  flush();
  r.word("gain");
  for (uint8_t i = 0; i < 4; i++) r.num(h.gainPermille[i]);
  flush();
  r.word("thermal");
  r.num(h.thermalCoeff);
  r.num(h.thermalRefDeciC);
  flush();
  r.word("leds");
  for (uint8_t i = 0; i < 8; i++) r.num(h.offsets[i / 2][i % 2]);
  flush();
  r.word("strategy");
  r.word(strategyName(h.strategy));
  r.u32(h.strategy == Strategy::Random ? h.seed : 0);
  flush();
}

void JobEncoder::row(uint16_t rowIndex, const uint8_t* cells, uint16_t cols) {
  uint16_t column = 0;
  while (nextRecord(rowIndex, cells, cols, column)) {
  }
}

bool JobEncoder::nextRecord(uint16_t rowIndex, const uint8_t* cells, uint16_t cols, uint16_t& column) {
  uint16_t c = column;
  while (c < cols && cells[c] == 0) c++;
  if (c >= cols) {
    column = cols;
    return false;
  }
  uint16_t start = c, last = c;
  for (;;) {
    uint16_t next = static_cast<uint16_t>(last + 1);
    while (next < cols && cells[next] == 0) next++;
    if (next < cols && next - last - 1 <= kJobMaxGap && next - start + 1 <= kJobMaxCellsPerRecord) {
      last = next;
    } else {
      break;
    }
  }
  Record r;
  r.word("r");
  r.num(rowIndex);
  r.num(start);
  r.buf[r.n++] = ' ';
  for (uint16_t i = start; i <= last; i++, r.n += 2) putHex(cells[i], 2, r.buf + r.n);
  r.buf[r.n] = '\0';
  emit(r.buf, r.n);
  column = static_cast<uint16_t>(last + 1);
  return true;
}

void JobEncoder::finish() {
  char buf[16] = "end ";
  crc32Hex(crc_, buf + 4);
  sink_.record(buf, 12);
}

}  // namespace uv
