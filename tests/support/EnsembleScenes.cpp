#include "support/EnsembleScenes.hpp"

#include <fstream>

#include "core/Grid.hpp"
#include "core/Raster.hpp"
#include "io/RasterIO.hpp"

namespace talus::test {

std::string writeLakeEnsemble(const std::filesystem::path& dir, const std::string& parameter, int members,
                              const std::string& extra, const std::string& name) {
  const Grid g = Grid::make(12, 10, 1.0, 2000.0, 3000.0);
  io::writeRaster((dir / "dem.tif").string(), Raster(g, 5.0));
  std::ofstream(dir / "lake.run", std::ios::binary) << "[Talus run file]\n[Input]\nDEM=dem.tif\nInclude Initial Water=1\n"
                                                       "Initial Fluid Height=0.1\n[Time]\nEnd Time=0.0001\nTimestep=1\n"
                                                       "[Numerics]\nBoundary Type=wall\n[Output]\nOutput Directory=out\n";
  std::ofstream(dir / name, std::ios::binary) << "[Ensemble]\nRun File=lake.run\nMembers=" << members
                                              << "\nSeed=11\nOutput Directory=ens\n[Parameters]\n"
                                              << parameter << "\n" << extra;
  return (dir / name).string();
}

std::string writeWedgeEnsemble(const std::filesystem::path& dir) {
  const Grid g = Grid::make(kWedgeNx, kWedgeNy, kWedgeDx, kWedgeX0, kWedgeY0);
  Raster dem(g, 0.0), water(g, 0.0), observed(g, 0.0);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      dem.at(i, j) = 10.0 - 0.05 * i;
      water.at(i, j) = 0.01 * (g.nx - i);
      observed.at(i, j) = i <= 16 ? 1.0 : 0.0;
    }
  io::writeRaster((dir / "dem.tif").string(), dem);
  io::writeRaster((dir / "wedge.tif").string(), water);
  io::writeRaster((dir / "observed.tif").string(), observed);
  std::ofstream(dir / "wedge.run", std::ios::binary) << "[Talus run file]\n[Input]\nDEM=dem.tif\nInclude Initial Water=1\n"
                                                        "Initial Fluid Height=wedge.tif\n[Time]\nEnd Time=0.0001\n"
                                                        "Timestep=1\n[Output]\nOutput Directory=out\n";
  std::ofstream(dir / "wedge.ens", std::ios::binary)
      << "[Ensemble]\nRun File=wedge.run\nOutput Directory=ens\n[Parameters]\nInitial Fluid Height=scale list 1 2 3 4\n"
         "[Maps]\nAffected Threshold=0.105\n[Calibration]\nObserved Map=observed.tif\nObserved Threshold=0.5\n"
         "Observed Runout="
      << g.cellX(16) << " " << g.cellY(g.ny - 1) << "\n";
  return (dir / "wedge.ens").string();
}

}  // namespace talus::test
