// The panel's 8x8 font for printable ASCII (' ' to '~'), drawn for this project. Kept in flash as
// SSD1306 columns (bit 0 the top pixel), so a glyph goes to the display as it is stored.
#pragma once
#include <stdint.h>

namespace mega {

constexpr char kFontFirst = ' ', kFontLast = '~';
constexpr uint8_t kGlyphWidth = 8;

// Column `col` (0-7) of c's glyph. A character outside the font draws as '?'.
uint8_t glyphColumn(char c, uint8_t col);

// The character whose glyph is exactly these 8 columns, or 0 (for the simavr panel model and tests).
char glyphChar(const uint8_t columns[kGlyphWidth]);

}  // namespace mega
