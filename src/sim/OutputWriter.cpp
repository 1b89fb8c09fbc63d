#include "sim/OutputWriter.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "core/Error.hpp"

namespace talus::sim {
namespace fs = std::filesystem;

OutputWriter::OutputWriter(const std::string& dir, const Raster& dem, io::RasterFormat format, bool overwrite,
                           bool resume)
    : dir_(fs::absolute(dir).lexically_normal().string()), dem_(dem), format_(format) {
  std::error_code ec;
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
    throw InputError("output folder '" + dir_ + "' exists and is not a folder");
  if (resume) {
    if (!fs::exists(dir_ + "/checkpoint.bin", ec))
      throw InputError("cannot resume: '" + dir_ + "' holds no checkpoint.bin");
    fs::remove(dir_ + "/summary.json", ec);
    // Temporary files of writes a kill interrupted (the finished files they would have replaced
    // are intact: every write is a rename).
    for (const auto& e : fs::recursive_directory_iterator(dir_, ec))
      if (e.path().filename().string().find(".tmp-") != std::string::npos) fs::remove(e.path(), ec);
    return;
  }
  if (!overwrite && (fs::exists(dir_ + "/summary.json", ec) || fs::exists(dir_ + "/diagnostics.csv", ec)))
    throw InputError("output folder '" + dir_ + "' already holds a run; choose another folder or pass --overwrite");
  fs::create_directories(dir_ + "/series", ec);
  if (ec) throw InputError("cannot create output folder '" + dir_ + "': " + ec.message());
  if (::access(dir_.c_str(), W_OK) != 0) throw InputError("output folder '" + dir_ + "' is not writable");
  fs::remove(dir_ + "/diagnostics.csv", ec);
  fs::remove(dir_ + "/summary.json", ec);
  fs::remove(dir_ + "/checkpoint.bin", ec);
}

OutputWriter::~OutputWriter() {
  if (csv_) std::fclose(csv_);
}

void OutputWriter::writeMap(const std::string& name, const std::vector<double>& values, const double* nodataValue) {
  Raster r(dem_.grid, 0.0);
  r.values = values;
  r.valid = dem_.valid;
  r.nodata = -9999.0;
  if (nodataValue)
    for (std::size_t k = 0; k < values.size(); ++k)
      if (values[k] == *nodataValue) r.valid[k] = 0;
  const char* ext = format_ == io::RasterFormat::PCRaster ? ".map" : ".tif";
  io::writeRaster(path(name + ext), r, format_);
}

void OutputWriter::writeText(const std::string& name, const std::string& content) {
  const std::string target = path(name);
  const std::string tmp = target + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary);
    out << content;
    if (!out) throw InputError("cannot write '" + tmp + "'");
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError("cannot write '" + target + "'");
  }
}

void OutputWriter::truncateDiagnostics(const std::string& header, long long rows) {
  std::ifstream in(path("diagnostics.csv"), std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  const std::string text = all.str();
  // Complete lines end with '\n'; a row cut by a kill has none and is dropped.
  std::string kept = header + "\n";
  long long lines = 0;
  std::size_t pos = text.find('\n');  // skip the file's own header line
  while (pos != std::string::npos && lines < rows) {
    const std::size_t end = text.find('\n', pos + 1);
    if (end == std::string::npos) break;
    kept += text.substr(pos + 1, end - pos);
    ++lines;
    pos = end;
  }
  if (lines < rows)
    throw InputError("cannot resume: '" + path("diagnostics.csv") + "' has " + std::to_string(lines) +
                     " complete rows, the checkpoint needs " + std::to_string(rows));
  writeText("diagnostics.csv", kept);
  csv_ = std::fopen(path("diagnostics.csv").c_str(), "a");
  if (!csv_) throw InputError("cannot write '" + path("diagnostics.csv") + "'");
}

void OutputWriter::appendDiagnostics(const std::string& header, const std::string& line) {
  if (!csv_) {
    csv_ = std::fopen(path("diagnostics.csv").c_str(), "w");
    if (!csv_) throw InputError("cannot write '" + path("diagnostics.csv") + "'");
    std::fprintf(csv_, "%s\n", header.c_str());
  }
  std::fprintf(csv_, "%s\n", line.c_str());
  std::fflush(csv_);
}

}  // namespace talus::sim
