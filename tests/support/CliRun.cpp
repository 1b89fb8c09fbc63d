#include "support/CliRun.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/Grid.hpp"
#include "core/Raster.hpp"
#include "io/RasterIO.hpp"

namespace talus::test {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream o;
  o << in.rdbuf();
  return o.str();
}

std::string shellQuote(const std::string& s) {
  std::string o = "'";
  for (char c : s) o += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return o + "'";
}

std::ostream& operator<<(std::ostream& o, const Outcome& r) {
  return o << "exit " << r.status << "\n--- stdout ---\n" << r.out << "--- stderr ---\n" << r.err;
}

Outcome runIn(const std::filesystem::path& dir, const std::string& binary, const std::string& args,
              const std::string& shellPrefix) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = "cd " + shellQuote(dir.string()) + " && " + shellPrefix + " " + shellQuote(binary) + " " + args + " >" +
                          shellQuote(out.string()) + " 2>" + shellQuote(err.string()) + " </dev/null";
  const int raw = std::system(cmd.c_str());
  Outcome r;
  if (raw != -1 && WIFEXITED(raw)) r.status = WEXITSTATUS(raw);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

std::string writeCliScene(const std::filesystem::path& dir, const std::string& extra, const std::string& name) {
  Grid g = Grid::make(20, 16, 2.0, 300000.0, 4000000.0);
  Raster dem(g, 0.0), water(g, 0.0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      dem.at(i, j) = 10.0 + 0.05 * (g.nx - i);
      water.at(i, j) = (i >= 4 && i < 9 && j >= 4 && j < 10) ? 0.5 : 0.0;
    }
  io::writeRaster((dir / "dem.tif").string(), dem);
  io::writeRaster((dir / "water.tif").string(), water);
  const std::string text =
      "[openLISEM runfile version 6.0]\n"
      "[Input]\n"
      "DEM=dem.tif\n"
      "Include Initial Water=1\n"
      "Initial Fluid Height=water.tif\n"
      "[Time]\n"
      "End Time=0.05\n"
      "Timestep=1\n"
      "[Output]\n"
      "Output Directory=out\n" +
      extra;
  std::ofstream(dir / name, std::ios::binary) << text;
  return (dir / name).string();
}

}  // namespace talus::test
