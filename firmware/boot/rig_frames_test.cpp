// The rig's stdin framing, fed whole and split at every place.
#include "rig_frames.h"

#include <gtest/gtest.h>

#include <string>

namespace {

std::string describe(const std::vector<uint8_t>& stream, size_t cut) {
  uv::RigFrames frames;
  std::string seen;
  auto on = [&](const uv::RigFrame& f) {
    seen += f.kind;
    if (f.kind == 'D') seen += std::string(f.bytes.begin(), f.bytes.end());
    if (f.kind == 'B') seen += std::to_string(f.baud);
    seen += '|';
  };
  frames.feed(stream.data(), cut, on);
  frames.feed(stream.data() + cut, stream.size() - cut, on);
  return seen;
}

TEST(RigFrames, BytesBaudAndResetWhereverTheStreamIsCut) {
  std::vector<uint8_t> s = {'B', 0x00, 0xc2, 0x01, 0x00, 'R', 'D', 3, '0', ' ', 'x', 'D', 0, 'D', 1, 'R'};
  for (size_t cut = 0; cut <= s.size(); cut++) EXPECT_EQ(describe(s, cut), "B115200|R|D0 x|DR|") << "cut at " << cut;
}

TEST(RigFrames, AnUnknownKindIsSkipped) {
  std::vector<uint8_t> s = {'?', 'R'};
  EXPECT_EQ(describe(s, 1), "R|");
}

}  // namespace
