// Internal to src/io: a check of the cell values of an ESRI ASCII grid as text. GDAL's AAIGrid
// driver reads a token that is not a number ("n/a", "1,5", "-") as 0 without a word, which in a DEM
// is a pit of the surrounding height; the scan finds such a token and where it stands.
#pragma once
#include <string>

namespace talus::io::detail {

/// Scans the data tokens of the ESRI ASCII grid at path (a header of "keyword value" lines, then
/// nx * ny whitespace-separated numbers, row 0 at the top). Returns "" when the first nx * ny data
/// tokens are all numbers, else a description of the first one that is not: "'n/a' at column 3,
/// row 7 (counting from 0 at the top left)". Tokens longer than 64 characters are reported
/// truncated. Unreadable files return "" (GDAL's own read reports them).
std::string findNonNumericAsciiCell(const std::string& path, long long nx, long long ny);

}  // namespace talus::io::detail
