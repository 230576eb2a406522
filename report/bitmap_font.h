#pragma once
// A built-in 5x7 bitmap font (ASCII 32..126) and text drawing onto RGB images, for
// chart labels without a font library.
//
// Each glyph is 5 columns by 8 rows: rows 0-6 hold capitals and digits (baseline under
// row 6), row 7 holds descenders (g, j, p, q, y, ',', '_'). Text is proportional:
// a glyph advances by its inked width plus one blank column, except digits, which keep
// all 5 columns so numbers line up; a space advances 3 columns. Characters outside
// 32..126 are drawn as '?'. Every pixel of the font becomes a scale x scale block.
#include <array>
#include <string>

#include "io/png_export.h"

namespace snapfit {

constexpr int kGlyphColumns = 5;
constexpr int kGlyphRows = 8;

// Rows of the glyph for `c`, top first; bit 4 of a row is its leftmost column.
const std::array<unsigned char, kGlyphRows>& glyph_rows(char c);

// Width in pixels of `text` at `scale` (no trailing blank column); 0 for "".
int text_width(const std::string& text, int scale);

// Height in pixels of one line of text at `scale`, descender row included.
inline int text_height(int scale) { return kGlyphRows * scale; }

// Draws `text` with its top-left corner at pixel (x, y). Vertical text is turned a
// quarter left (it reads bottom to top) and occupies text_height wide by text_width
// tall from (x, y). Pixels outside the image are skipped.
void draw_text(SliceImage& image, int x, int y, const std::string& text, const std::array<unsigned char, 3>& color,
               int scale = 1, bool vertical = false);

}  // namespace snapfit
