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
  if (measuring_) {
    measured_ += static_cast<uint32_t>(len) + 1;
    return;
  }
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
  r.num(format_);
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

bool JobEncoder::runsShorter(uint16_t rowIndex, const uint8_t* cells, uint16_t cols) {
  if (format_ < 2) return false;
  measuring_ = true;
  measured_ = 0;
  uint16_t column = 0;
  while (nextRecord(rowIndex, cells, cols, column)) {
  }
  const uint32_t segments = measured_;
  measured_ = 0;
  column = 0;
  while (nextRunRecord(rowIndex, cells, cols, column)) {
  }
  const uint32_t runs = measured_;
  measuring_ = false;
  return segments && runs < segments;
}

void JobEncoder::row(uint16_t rowIndex, const uint8_t* cells, uint16_t cols) {
  uint16_t column = 0;
  if (runsShorter(rowIndex, cells, cols)) {
    while (nextRunRecord(rowIndex, cells, cols, column)) {
    }
    return;
  }
  while (nextRecord(rowIndex, cells, cols, column)) {
  }
}

namespace {

// A token of an `rl` record: cells [col, end), a run of one value when `run`, else literal.
struct Token {
  uint16_t col, end;
  bool run;
};

// The token at `c`: a run of kJobMinRun or more equal cells, or the short runs that follow up to
// `last`. From inside a literal token (where the previous record split it) it is that token's rest.
Token tokenAt(const uint8_t* cells, uint16_t c, uint16_t last) {
  auto runEnd = [&](uint16_t at) {
    uint16_t e = static_cast<uint16_t>(at + 1);
    while (e <= last && cells[e] == cells[at]) e++;
    return e;
  };
  uint16_t e = runEnd(c);
  if (e - c >= kJobMinRun) return {c, e, true};
  while (e <= last) {
    uint16_t next = runEnd(e);
    if (next - e >= kJobMinRun) break;
    e = next;
  }
  return {c, e, false};
}

}  // namespace

bool JobEncoder::nextRunRecord(uint16_t rowIndex, const uint8_t* cells, uint16_t cols, uint16_t& column) {
  int32_t last = static_cast<int32_t>(cols) - 1;
  while (last >= column && cells[last] == 0) last--;
  int32_t c = column;
  if (c == 0) {  // the row's tokens start at its first non-zero cell
    while (c <= last && cells[c] == 0) c++;
  }
  Record rec;
  bool open = false;
  uint8_t keep = 0;  // the record's length without the zero runs at its end
  while (c <= last) {
    Token t = tokenAt(cells, static_cast<uint16_t>(c), static_cast<uint16_t>(last));
    const bool zeroRun = t.run && cells[t.col] == 0;
    if (!open) {
      if (zeroRun) {  // a record never starts, nor ends, with zeros of a run
        c = t.end;
        continue;
      }
      rec.word("rl");
      rec.num(rowIndex);
      rec.num(t.col);
      open = true;
    }
    char count[6];
    const uint8_t countLen = static_cast<uint8_t>(t.run ? putUnsigned(t.end - t.col, count) : 0);
    const uint16_t len = t.run ? static_cast<uint16_t>(countLen + 3) : static_cast<uint16_t>(2 * (t.end - t.col));
    if (rec.n + 1 + len <= kJobMaxRecordBytes) {
      rec.buf[rec.n++] = ' ';
      if (t.run) {
        memcpy(rec.buf + rec.n, count, countLen);
        rec.n = static_cast<uint8_t>(rec.n + countLen);
        rec.buf[rec.n++] = 'x';
        putHex(cells[t.col], 2, rec.buf + rec.n);
        rec.n = static_cast<uint8_t>(rec.n + 2);
      } else {
        for (uint16_t i = t.col; i < t.end; i++, rec.n += 2) putHex(cells[i], 2, rec.buf + rec.n);
      }
      if (!zeroRun) keep = rec.n;
      c = t.end;
      continue;
    }
    // It does not fit: a literal puts what fits here (the next record takes its rest), a run goes
    // whole into the next record.
    const int room = (kJobMaxRecordBytes - rec.n - 1) / 2;
    if (!t.run && room >= 1) {
      rec.buf[rec.n++] = ' ';
      for (int i = 0; i < room; i++, rec.n += 2) putHex(cells[t.col + i], 2, rec.buf + rec.n);
      keep = rec.n;
      c = t.col + room;
    }
    break;
  }
  column = static_cast<uint16_t>(c > last ? cols : c);
  if (!open) return false;
  rec.buf[keep] = '\0';
  emit(rec.buf, keep);
  return true;
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
