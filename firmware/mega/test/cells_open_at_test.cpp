// CellSource::openAt on the card's and the stream's cells (planner.md "Bands"): each goes straight to
// the column, and stands where walking from the row's end would, for every row, column and direction.
#include <gtest/gtest.h>

#include <vector>

#include "grid_cells.h"
#include "sd_cells.h"
#include "storage_fake.h"
#include "stream_cells.h"

using namespace mega;

namespace {

using Grid = std::vector<std::vector<uint8_t>>;

Grid randomGrid(uint32_t seed, uint16_t rows, uint16_t cols) {
  Grid g(rows, std::vector<uint8_t>(cols, 0));
  for (auto& r : g)
    for (auto& v : r) {
      seed = seed * 1664525u + 1013904223u;
      if ((seed >> 8) % 5 == 0) v = static_cast<uint8_t>(1 + (seed >> 16) % 255);
    }
  g[1].assign(cols, 0);  // an empty row
  return g;
}

// Every cell the cursor walks over from where openAt put it, as the reference walks them.
void expectSameWalks(uv::CellSource& source, const Grid& g) {
  uvtest::GridCells reference(g);
  const uint16_t cols = static_cast<uint16_t>(g[0].size());
  for (uint16_t row = 0; row < g.size(); row++)
    for (bool down : {false, true})
      for (uint16_t col = 0; col < cols; col++) {
        source.openAt(0, row, down, col);
        reference.openAt(0, row, down, col);
        uint16_t a, b;
        uint8_t va, vb;
        for (;;) {
          const bool more = source.next(0, a, va);
          ASSERT_EQ(more, reference.next(0, b, vb)) << "row " << row << " col " << col << (down ? " down" : " up");
          if (!more) break;
          ASSERT_EQ(a, b);
          ASSERT_EQ(va, vb);
        }
      }
}

}  // namespace

TEST(CellsOpenAt, TheStreamGoesStraightToTheColumn) {
  const Grid g = randomGrid(7, 6, 37);
  uint8_t buffer[1024];
  StreamCells cells(buffer, sizeof buffer);
  for (uint16_t r = 0; r < g.size(); r++)  // segments of up to 9 cells, gaps where the row is blank
    for (uint16_t c = 0; c < g[r].size(); c += 9) {
      const uint8_t n = static_cast<uint8_t>(g[r].size() - c < 9 ? g[r].size() - c : 9);
      bool any = false;
      for (uint8_t i = 0; i < n; i++) any = any || g[r][c + i];
      if (any) {
        ASSERT_TRUE(cells.add(r, c, &g[r][c], n));
      }
    }
  expectSameWalks(cells, g);
}

TEST(CellsOpenAt, TheCardGoesStraightToTheColumn) {
  const Grid g = randomGrid(11, 6, 41);
  FakeStorage sd;
  FileHandle cf = sd.open("J~c", Storage::Mode::Create), xf = sd.open("J~i", Storage::Mode::Create);
  uint32_t offset = 0;
  for (const auto& row : g) {  // each row's cells from its first to its last non-zero column
    int first = -1, last = -1;
    for (size_t c = 0; c < row.size(); c++)
      if (row[c]) {
        if (first < 0) first = static_cast<int>(c);
        last = static_cast<int>(c);
      }
    const uint16_t f = first < 0 ? 1 : static_cast<uint16_t>(first), l = first < 0 ? 0 : static_cast<uint16_t>(last);
    const uint8_t e[8] = {static_cast<uint8_t>(offset), static_cast<uint8_t>(offset >> 8), static_cast<uint8_t>(offset >> 16), static_cast<uint8_t>(offset >> 24),
                          static_cast<uint8_t>(f), static_cast<uint8_t>(f >> 8), static_cast<uint8_t>(l), static_cast<uint8_t>(l >> 8)};
    ASSERT_TRUE(sd.write(xf, reinterpret_cast<const char*>(e), 8));
    if (first < 0) continue;
    ASSERT_TRUE(sd.write(cf, reinterpret_cast<const char*>(&row[f]), static_cast<uint16_t>(l - f + 1)));
    offset += l - f + 1u;
  }
  sd.close(cf);
  sd.close(xf);
  SdCellsWith<1> cells(sd, sd.open("J~c", Storage::Mode::Read), sd.open("J~i", Storage::Mode::Read));
  expectSameWalks(cells, g);
  EXPECT_FALSE(cells.failed());
}
