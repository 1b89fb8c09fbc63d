// Map rendering for reports (MapRender.hpp): colour ramps, hillshade, a small bitmap font for the
// legend, and the PNG output through GDAL's MEM and PNG drivers.
#include "io/MapRender.hpp"

#include <gdal.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include "core/Error.hpp"
#include "io/GdalErrors.hpp"
#include "io/RasterIO.hpp"

namespace talus::io {
namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- colour ramps -----------------------------------------------------------------------------

struct Stop {
  double t;
  Rgb c;
};

const std::vector<Stop>& stops(Ramp ramp) {
  static const std::vector<Stop> depth{
      {0.0, {198, 233, 250}}, {0.35, {90, 170, 225}}, {0.7, {30, 80, 180}}, {1.0, {45, 20, 110}}};
  static const std::vector<Stop> heat{
      {0.0, {255, 240, 130}}, {0.35, {250, 160, 50}}, {0.7, {215, 45, 30}}, {1.0, {110, 0, 20}}};
  static const std::vector<Stop> viridis{{0.0, {68, 1, 84}},     {0.25, {59, 82, 139}}, {0.5, {33, 145, 140}},
                                         {0.75, {94, 201, 98}}, {1.0, {253, 231, 37}}};
  static const std::vector<Stop> cohesion{{0.0, {200, 20, 30}}, {0.5, {250, 210, 50}}, {1.0, {30, 150, 60}}};
  switch (ramp) {
    case Ramp::Depth: return depth;
    case Ramp::Heat: return heat;
    case Ramp::Viridis: return viridis;
    case Ramp::Cohesion: return cohesion;
  }
  return depth;
}

// ---- a 5 x 7 bitmap font for the legend ----------------------------------------------------------
// Each glyph is 7 rows, top to bottom; bit 4 (0x10) is the leftmost of 5 columns. Upper-case letters
// are drawn with the lower-case glyphs; characters without a glyph are drawn as a small box.

struct Glyph {
  char ch;
  std::uint8_t rows[7];
};

const Glyph kFont[] = {
    {' ', {0, 0, 0, 0, 0, 0, 0}},
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {'.', {0, 0, 0, 0, 0, 0x0C, 0x0C}},                {',', {0, 0, 0, 0, 0x0C, 0x04, 0x08}},
    {'-', {0, 0, 0, 0x1F, 0, 0, 0}},                   {'+', {0, 0x04, 0x04, 0x1F, 0x04, 0x04, 0}},
    {'=', {0, 0, 0x1F, 0, 0x1F, 0, 0}},                {'/', {0, 0x01, 0x02, 0x04, 0x08, 0x10, 0}},
    {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}}, {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
    {'[', {0x0E, 0x08, 0x08, 0x08, 0x08, 0x08, 0x0E}}, {']', {0x0E, 0x02, 0x02, 0x02, 0x02, 0x02, 0x0E}},
    {':', {0, 0x0C, 0x0C, 0, 0x0C, 0x0C, 0}},          {'%', {0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03}},
    {'_', {0, 0, 0, 0, 0, 0, 0x1F}},                   {'<', {0x02, 0x04, 0x08, 0x10, 0x08, 0x04, 0x02}},
    {'>', {0x08, 0x04, 0x02, 0x01, 0x02, 0x04, 0x08}}, {'a', {0, 0, 0x0E, 0x01, 0x0F, 0x11, 0x0F}},
    {'b', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E}}, {'c', {0, 0, 0x0E, 0x10, 0x10, 0x11, 0x0E}},
    {'d', {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F}}, {'e', {0, 0, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
    {'f', {0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08}}, {'g', {0, 0x0F, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
    {'h', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}}, {'i', {0x04, 0, 0x0C, 0x04, 0x04, 0x04, 0x0E}},
    {'j', {0x02, 0, 0x06, 0x02, 0x02, 0x12, 0x0C}},    {'k', {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}},
    {'l', {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'m', {0, 0, 0x1A, 0x15, 0x15, 0x11, 0x11}},
    {'n', {0, 0, 0x16, 0x19, 0x11, 0x11, 0x11}},       {'o', {0, 0, 0x0E, 0x11, 0x11, 0x11, 0x0E}},
    {'p', {0, 0, 0x1E, 0x11, 0x1E, 0x10, 0x10}},       {'q', {0, 0, 0x0D, 0x13, 0x0F, 0x01, 0x01}},
    {'r', {0, 0, 0x16, 0x19, 0x10, 0x10, 0x10}},       {'s', {0, 0, 0x0E, 0x10, 0x0E, 0x01, 0x1E}},
    {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}}, {'u', {0, 0, 0x11, 0x11, 0x11, 0x13, 0x0D}},
    {'v', {0, 0, 0x11, 0x11, 0x11, 0x0A, 0x04}},       {'w', {0, 0, 0x11, 0x11, 0x15, 0x15, 0x0A}},
    {'x', {0, 0, 0x11, 0x0A, 0x04, 0x0A, 0x11}},       {'y', {0, 0, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
    {'z', {0, 0, 0x1F, 0x02, 0x04, 0x08, 0x1F}},
};
const std::uint8_t kUnknownGlyph[7] = {0, 0x1F, 0x11, 0x11, 0x11, 0x1F, 0};

const std::uint8_t* glyphRows(char ch) {
  if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
  for (const Glyph& g : kFont)
    if (g.ch == ch) return g.rows;
  return kUnknownGlyph;
}

/// An RGB picture in memory.
struct Canvas {
  int w = 0, h = 0;
  std::vector<Rgb> px;
  Canvas(int width, int height, Rgb fill) : w(width), h(height), px(static_cast<std::size_t>(width) * height, fill) {}
  void set(int x, int y, Rgb c) {
    if (x >= 0 && y >= 0 && x < w && y < h) px[static_cast<std::size_t>(y) * w + x] = c;
  }
  void fill(int x0, int y0, int x1, int y1, Rgb c) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) set(x, y, c);
  }
  /// Draws text with its top-left corner at (x, y), each font pixel as s x s pixels; returns the
  /// x after the text.
  int text(int x, int y, const std::string& s, int size, Rgb c) {
    for (char ch : s) {
      const std::uint8_t* rows = glyphRows(ch);
      for (int r = 0; r < 7; ++r)
        for (int col = 0; col < 5; ++col)
          if (rows[r] & (0x10 >> col)) fill(x + col * size, y + r * size, x + (col + 1) * size, y + (r + 1) * size, c);
      x += 6 * size;
    }
    return x;
  }
  static int textWidth(const std::string& s, int size) { return static_cast<int>(s.size()) * 6 * size; }
};

/// A short number for the legend: 3 significant digits, no trailing zeros.
std::string shortNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

/// Writes the canvas as PNG: MEM dataset with three Byte bands, then CreateCopy with the PNG driver.
void writePng(const Canvas& c, const std::string& path) {
  detail::ensureGdalRegistered();
  detail::GdalErrorScope errors;
  GDALDriverH mem = GDALGetDriverByName("MEM");
  GDALDriverH png = GDALGetDriverByName("PNG");
  if (mem == nullptr || png == nullptr)
    throw InputError("cannot write '" + path + "': GDAL has no " + (mem == nullptr ? "MEM" : "PNG") + " driver");
  GDALDatasetH ds = GDALCreate(mem, "", c.w, c.h, 3, GDT_Byte, nullptr);
  if (ds == nullptr) throw InputError("cannot write '" + path + "': " + errors.describe("GDAL MEM dataset"));
  std::vector<std::uint8_t> band(c.px.size());
  bool ok = true;
  for (int b = 0; b < 3 && ok; ++b) {
    for (std::size_t k = 0; k < c.px.size(); ++k) band[k] = b == 0 ? c.px[k].r : b == 1 ? c.px[k].g : c.px[k].b;
    ok = GDALRasterIO(GDALGetRasterBand(ds, b + 1), GF_Write, 0, 0, c.w, c.h, band.data(), c.w, c.h, GDT_Byte, 0,
                      0) == CE_None;
  }
  GDALDatasetH out = ok ? GDALCreateCopy(png, path.c_str(), ds, FALSE, nullptr, nullptr, nullptr) : nullptr;
  GDALClose(ds);
  if (out == nullptr)
    throw InputError("cannot write PNG '" + path + "': " + errors.describe("GDAL PNG driver failed"));
  GDALClose(out);
  // The PNG driver may leave a side-car with the (absent) georeference; the picture needs none.
  std::error_code ec;
  std::filesystem::remove(path + ".aux.xml", ec);
}

}  // namespace

Ramp parseRamp(const std::string& name) {
  if (name == "depth") return Ramp::Depth;
  if (name == "heat") return Ramp::Heat;
  if (name == "viridis") return Ramp::Viridis;
  if (name == "cohesion") return Ramp::Cohesion;
  throw InputError("unknown colour ramp '" + name + "' (depth, heat, viridis, cohesion)");
}

Rgb rampColour(Ramp ramp, double t) {
  const std::vector<Stop>& s = stops(ramp);
  if (!(t > 0.0)) return s.front().c;  // also NaN
  if (t >= 1.0) return s.back().c;
  std::size_t k = 1;
  while (k + 1 < s.size() && t > s[k].t) ++k;
  const double f = (t - s[k - 1].t) / (s[k].t - s[k - 1].t);
  auto mix = [f](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + f * (static_cast<double>(b) - a)));
  };
  return {mix(s[k - 1].c.r, s[k].c.r), mix(s[k - 1].c.g, s[k].c.g), mix(s[k - 1].c.b, s[k].c.b)};
}

std::vector<std::uint8_t> hillshade(const Raster& dem) {
  const Grid& g = dem.grid;
  std::vector<std::uint8_t> out(g.cells(), 255);
  const double az = 315.0 * kPi / 180.0, alt = 45.0 * kPi / 180.0;
  // Unit vector towards the sun in (east, north, up).
  const double sx = std::cos(alt) * std::sin(az), sy = std::cos(alt) * std::cos(az), sz = std::sin(alt);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      if (!dem.isValid(i, j)) continue;
      const double zc = dem.at(i, j);
      auto z = [&](int di, int dj) {
        const int ii = i + di, jj = j + dj;
        if (ii < 0 || jj < 0 || ii >= g.nx || jj >= g.ny || !dem.isValid(ii, jj)) return zc;
        return dem.at(ii, jj);
      };
      // Horn's 3 x 3 gradient; row j grows southwards, so dz/dnorth = -(dz/drow).
      const double dzdx = ((z(1, -1) + 2 * z(1, 0) + z(1, 1)) - (z(-1, -1) + 2 * z(-1, 0) + z(-1, 1))) / (8 * g.dx);
      const double dzdy = -((z(-1, 1) + 2 * z(0, 1) + z(1, 1)) - (z(-1, -1) + 2 * z(0, -1) + z(1, -1))) / (8 * g.dx);
      const double shade = (-dzdx * sx - dzdy * sy + sz) / std::sqrt(1 + dzdx * dzdx + dzdy * dzdy);
      out[g.index(i, j)] = static_cast<std::uint8_t>(std::lround(70.0 + 170.0 * std::max(0.0, shade)));
    }
  return out;
}

RenderLayout renderMap(const std::string& rasterPath, const std::string& pngPath, const RenderOptions& o) {
  const Raster map = readRaster(rasterPath);
  const Grid& g = map.grid;
  std::vector<std::uint8_t> shade(g.cells(), 210);
  if (!o.hillshadeDem.empty()) {
    const Raster dem = readRaster(o.hillshadeDem);
    requireSameGrid(dem, o.hillshadeDem, map, rasterPath);
    shade = hillshade(dem);
  }
  RenderLayout L;
  std::vector<std::uint8_t> shown(g.cells(), 0);
  double vmin = std::numeric_limits<double>::infinity(), vmax = -vmin;
  for (std::size_t k = 0; k < g.cells(); ++k)
    if (map.valid[k] && map.values[k] > o.threshold) {
      shown[k] = 1;
      ++L.shownCells;
      vmin = std::min(vmin, map.values[k]);
      vmax = std::max(vmax, map.values[k]);
    }
  if (o.fixedRange) {
    if (!(o.hi > o.lo)) throw InputError("talus render: --range needs lo < hi (got " + shortNumber(o.lo) + " " +
                                         shortNumber(o.hi) + ")");
    L.lo = o.lo, L.hi = o.hi;
  } else if (L.shownCells > 0) {
    L.lo = vmin >= 0.0 ? 0.0 : vmin;  // thicknesses and speeds: the ramp starts at zero
    L.hi = vmax > L.lo ? vmax : L.lo + 1.0;
  }

  // Layout: the map (scale pixels per cell) with a margin, and the legend band below it.
  const int maxSide = std::max(g.nx, g.ny);
  L.scale = o.scale > 0 ? o.scale : std::max(1, 800 / std::max(1, maxSide));
  const int margin = 10, textSize = 2, legendH = 70;
  L.mapX = margin, L.mapY = margin;
  const int mapW = g.nx * L.scale, mapH = g.ny * L.scale;
  L.width = std::max(mapW + 2 * margin, 520);
  L.height = mapH + 2 * margin + legendH;
  Canvas c(L.width, L.height, Rgb{255, 255, 255});
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const std::size_t k = g.index(i, j);
      const Rgb col = shown[k] ? rampColour(o.ramp, (map.values[k] - L.lo) / (L.hi - L.lo))
                               : Rgb{shade[k], shade[k], shade[k]};
      c.fill(L.mapX + i * L.scale, L.mapY + j * L.scale, L.mapX + (i + 1) * L.scale, L.mapY + (j + 1) * L.scale, col);
    }

  // Legend: label on the first line, then the colour bar with its range and a scale bar.
  const Rgb ink{20, 20, 20};
  const int y0 = L.mapY + mapH + 8;
  const std::string label =
      o.label.empty() ? std::filesystem::path(rasterPath).stem().string() : o.label;
  const std::string title = label + (L.shownCells == 0 ? "  (no cell above the threshold)" : "");
  // A long label is drawn at half size rather than cut at the picture's edge.
  c.text(margin, y0 + 4, title, Canvas::textWidth(title, textSize) <= L.width - 2 * margin ? textSize : 1, ink);
  const int barY = y0 + 22, barH = 14, barX = margin + Canvas::textWidth(shortNumber(L.lo), textSize) + 8;
  const int barW = std::min(220, L.width - barX - 2 * margin - Canvas::textWidth(shortNumber(L.hi), textSize) - 8);
  c.text(margin, barY, shortNumber(L.lo), textSize, ink);
  for (int x = 0; x < barW; ++x)
    c.fill(barX + x, barY, barX + x + 1, barY + barH, rampColour(o.ramp, (x + 0.5) / barW));
  const int afterBar = c.text(barX + barW + 8, barY, shortNumber(L.hi), textSize, ink);
  // Scale bar: a round length near a fifth of the map width.
  const double width = g.nx * g.dx, target = width / 5;
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  const double len = target >= 5 * p ? 5 * p : target >= 2 * p ? 2 * p : p;
  const int lenPx = static_cast<int>(std::lround(len / g.dx * L.scale));
  const int sbX = afterBar + 24;
  if (sbX + lenPx + 80 < L.width) {
    c.fill(sbX, barY + barH - 4, sbX + lenPx, barY + barH, ink);
    c.text(sbX + lenPx + 6, barY, shortNumber(len) + " m", textSize, ink);
  }
  writePng(c, pngPath);
  return L;
}

int renderCommand(const std::vector<std::string>& args) {
  RenderOptions o;
  std::string raster, png;
  for (std::size_t a = 0; a < args.size(); ++a) {
    const std::string& arg = args[a];
    auto value = [&](const char* flag) -> std::string {
      if (a + 1 >= args.size()) throw InputError(std::string("talus render: option ") + flag + " needs a value");
      return args[++a];
    };
    auto number = [&](const char* flag) {
      const std::string v = value(flag);
      char* end = nullptr;
      const double d = std::strtod(v.c_str(), &end);
      if (v.empty() || *end != '\0' || !std::isfinite(d))
        throw InputError(std::string("talus render: option ") + flag + ": '" + v + "' is not a number");
      return d;
    };
    if (arg == "-o" || arg == "--out") png = value("-o");
    else if (arg == "--hillshade") o.hillshadeDem = value("--hillshade");
    else if (arg == "--ramp") o.ramp = parseRamp(value("--ramp"));
    else if (arg == "--label") o.label = value("--label");
    else if (arg == "--threshold") o.threshold = number("--threshold");
    else if (arg == "--scale") o.scale = static_cast<int>(number("--scale"));
    else if (arg == "--range") {
      o.lo = number("--range");
      o.hi = number("--range");
      o.fixedRange = true;
    } else if (!arg.empty() && arg[0] == '-') throw InputError("talus render: unknown option '" + arg + "'");
    else if (raster.empty()) raster = arg;
    else throw InputError("talus render: more than one raster given ('" + raster + "' and '" + arg + "')");
  }
  if (raster.empty()) throw InputError("talus render: no raster given");
  if (png.empty()) throw InputError("talus render: no output file given (-o FILE.png)");
  const RenderLayout L = renderMap(raster, png, o);
  std::printf("talus render: %s -> %s (%dx%d pixels, %d cells shown, range %s..%s)\n", raster.c_str(), png.c_str(),
              L.width, L.height, L.shownCells, shortNumber(L.lo).c_str(), shortNumber(L.hi).c_str());
  return 0;
}

}  // namespace talus::io
