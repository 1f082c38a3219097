// SPDX-FileCopyrightText: 2026 cubespring authors
// SPDX-License-Identifier: MIT
// A 5x7 pixel font for legend numbers and labels: digits, upper-case letters and a little
// punctuation. Built in so that frames need no font files and come out the same everywhere.
#pragma once

namespace cubespring {

inline constexpr int kGlyphWidth = 5;    // [font pixels]
inline constexpr int kGlyphHeight = 7;   // [font pixels]
inline constexpr int kGlyphAdvance = 6;  // one blank column between characters

/// Whether font pixel (column, row) of character c is set, row 0 at the top. Lower-case letters
/// use the upper-case glyphs; characters the font lacks show as '?'.
bool glyph_pixel(char c, int column, int row);

}  // namespace cubespring
