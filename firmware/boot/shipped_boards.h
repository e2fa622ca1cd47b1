// Reads boards-as-shipped.json: one board's chip facts, fuses and auto-reset parts, for the rig and its test.
#pragma once
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "board_fuses.h"

namespace uv {

struct ShippedBoard {
  std::string mcu;
  ChipFacts chip{};
  ShippedFuses fuses{};
  uint32_t maximumSize = 0;  // boards.txt upload.maximum_size
  double capacitorNf = 0, pullUpOhms = 0;
};

inline ShippedBoard loadShippedBoard(const std::string& path, const std::string& board) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  const nlohmann::json all = nlohmann::json::parse(in);
  if (!all["boards"].contains(board)) throw std::runtime_error("no board '" + board + "' in " + path);
  const auto& b = all["boards"][board];
  const auto& c = all["chips"][b["chip"].get<std::string>()];
  auto byte = [](const nlohmann::json& v) { return static_cast<uint8_t>(std::stoul(v.get<std::string>(), nullptr, 16)); };
  ShippedBoard s;
  s.mcu = b["chip"].get<std::string>();
  s.chip.flashBytes = c["flashBytes"];
  s.chip.pageBytes = c["pageBytes"];
  for (int i = 0; i < 4; i++) s.chip.bootWordsByBootsz[i] = c["bootWordsByBootsz"][i];
  s.chip.spmMs = c["spmMs"];
  s.fuses = {byte(b["lowFuse"]), byte(b["highFuse"]), byte(b["extendedFuse"]), byte(b["lockBits"])};
  s.maximumSize = b["maximumSize"];
  s.capacitorNf = all["autoReset"]["capacitorNf"];
  s.pullUpOhms = all["autoReset"]["pullUpOhms"];
  return s;
}

}  // namespace uv
