// The exposure job's header as the job format (protocol/job.md) carries it.
#pragma once
#include <stdint.h>

namespace uv {

constexpr uint16_t kJobMaxSide = 4096;
constexpr uint8_t kJobMaxCellsPerRecord = 32;
constexpr uint8_t kJobMaxGap = 4;
// Format 2 (job.md "Run-length rows"): a run token holds this many equal cells or more; an `rl` record
// is at most as long as the longest `r` record.
constexpr uint8_t kJobMinRun = 4;
constexpr uint8_t kJobMaxRecordBytes = 76;

enum class DoseMap : uint8_t { Linear, Threshold };
// Scan exposes each pass on the move (protocol/planner.md "Scan mode"); the others stop and fire.
enum class Strategy : uint8_t { Raster, Serpentine, Shortest, Random, Scan, Mixed };
constexpr uint8_t kStrategyCount = 6;

struct JobHeader {
  uint16_t cols, rows;
  uint32_t pitchUm[2];
  uint32_t originUm[2];
  DoseMap map;
  uint8_t level;          // threshold level, 0 for linear
  bool byTarget;          // dose given as target + irradiance (else fullUs)
  uint32_t fullUs;
  uint32_t targetUJcm2;
  uint32_t irradianceUWcm2[4];
  uint16_t gainPermille[4];
  int16_t thermalCoeff;   // 0.01 %/°C
  int16_t thermalRefDeciC;
  int16_t offsets[4][2];  // cells
  Strategy strategy;
  uint32_t seed;
};

// The strategy's name (a flash pointer on AVR).
const char* strategyName(Strategy s);

}  // namespace uv
