// libFuzzer target: file bytes -> talus::io::readRaster. The first input byte picks the file name
// extension (.tif, .asc or .map, which also steers GDAL's driver probing); the rest is the file.
// Contract checked: readRaster returns a raster whose grid, values and mask agree, or throws
// talus::InputError naming the file. Anything else (another exception, a sanitizer report, a crash)
// is a finding.
//
// GDAL is not instrumented. To keep the search on Talus's code and on the formats Talus documents,
// only the GTiff, AAIGrid and PCRaster drivers stay registered (TALUS_FUZZ_ALL_DRIVERS=1 keeps all),
// and rasters whose header claims more than kMaxFuzzCells cells are skipped before readRaster
// allocates them (readRaster's own cap, 2^31 cells, is far above the fuzzer's memory limit; see
// tests/unit/test_hostile_input.cpp for the headers beyond that cap).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <typeinfo>

#include <stdlib.h>  // mkdtemp

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>

#include "core/Error.hpp"
#include "io/RasterIO.hpp"

namespace fs = std::filesystem;

namespace {

constexpr long long kMaxFuzzCells = 1ll << 20;  // 1 Mi cells: 9 MB as values and mask
const char* const kExtensions[] = {".tif", ".asc", ".map"};
std::string g_dir;

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_raster: %s: %s\n", what, detail.c_str());
  std::abort();
}

/// Cells the file's header claims (0 when GDAL does not open it).
long long claimedCells(const std::string& path) {
  GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) return 0;
  return static_cast<long long>(ds->GetRasterXSize()) * ds->GetRasterYSize();
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // No side-car (.aux.xml) writes, quiet GDAL.
  CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");
  CPLSetConfigOption("GDAL_DISABLE_READDIR_ON_OPEN", "EMPTY_DIR");
  CPLSetConfigOption("CPL_DEBUG", "OFF");
  CPLSetConfigOption("GDAL_CACHEMAX", "32");  // MB of block cache (the default, 5% of RAM, can reach 1 GB+)
  CPLSetErrorHandler(CPLQuietErrorHandler);
  // readRaster registers GDAL's drivers on its first call (a missing file, so it throws at once);
  // afterwards drop the drivers outside the documented formats.
  try {
    talus::io::readRaster("/nonexistent/talus_fuzz_init.tif");
  } catch (const talus::InputError&) {
  }
  const char* all = std::getenv("TALUS_FUZZ_ALL_DRIVERS");
  if (all == nullptr || std::string(all) != "1") {
    GDALDriverManager* manager = GetGDALDriverManager();
    for (int i = manager->GetDriverCount() - 1; i >= 0; --i) {
      GDALDriver* driver = manager->GetDriver(i);
      const std::string name = driver->GetDescription();
      if (name == "GTiff" || name == "AAIGrid" || name == "PCRaster") continue;
      manager->DeregisterDriver(driver);
      GDALDestroyDriver(driver);
    }
  }
  const char* base = fs::is_directory("/dev/shm") ? "/dev/shm/talus_fuzz_raster_XXXXXX" : "/tmp/talus_fuzz_raster_XXXXXX";
  std::string pattern = base;
  if (::mkdtemp(pattern.data()) == nullptr) {
    std::perror("fuzz_raster: mkdtemp");
    std::exit(1);
  }
  g_dir = pattern;
  std::atexit([] {
    std::error_code ec;
    fs::remove_all(g_dir, ec);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 256 * 1024) return 0;
  const std::string path = g_dir + "/input" + kExtensions[data[0] % 3];
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) fail("cannot write the input file", path);
    if (size > 1 && std::fwrite(data + 1, 1, size - 1, f) != size - 1) fail("short write", path);
    std::fclose(f);
  }
  if (claimedCells(path) <= kMaxFuzzCells) {
    try {
      const talus::Raster r = talus::io::readRaster(path);
      const talus::Grid& g = r.grid;
      if (g.nx <= 0 || g.ny <= 0 || r.values.size() != g.cells() || r.valid.size() != g.cells())
        fail("inconsistent raster", path);
      if (!(g.dx > 0)) fail("non-positive cell size accepted", path);
    } catch (const talus::InputError& e) {
      if (std::string(e.what()).find(path) == std::string::npos) fail("InputError does not name the file", e.what());
    } catch (const std::exception& e) {
      fail("unexpected exception", std::string(typeid(e).name()) + ": " + e.what());
    }
  }
  std::remove(path.c_str());
  return 0;
}
