#include "sim/OutputWriter.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/Error.hpp"

namespace talus::sim {
namespace fs = std::filesystem;
namespace {

constexpr const char* kLock = ".talus-lock";
constexpr const char* kManifest = ".talus-outputs";
// The files every run writes under fixed names: removed by --overwrite also after a run whose
// version kept no manifest.
constexpr const char* kFixedOutputs[] = {"summary.json", "diagnostics.csv", "checkpoint.bin", "run.resolved.run",
                                         "series/index.csv"};

/// A manifest entry names a file inside the folder: relative, without "..".
bool insideFolder(const std::string& name) {
  if (name.empty() || name[0] == '/') return false;
  for (const auto& part : fs::path(name))
    if (part == "..") return false;
  return true;
}

std::string readSmallFile(const std::string& path, std::size_t limit) {
  std::ifstream in(path, std::ios::binary);
  std::string s(limit, '\0');
  in.read(&s[0], static_cast<std::streamsize>(limit));
  s.resize(static_cast<std::size_t>(in.gcount()));
  return s;
}

}  // namespace

OutputWriter::OutputWriter(const std::string& dir, const Raster& dem, io::RasterFormat format, bool overwrite,
                           bool resume)
    : dir_(fs::absolute(dir).lexically_normal().string()), dem_(dem), format_(format), resume_(resume) {
  std::error_code ec;
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
    throw InputError("output folder '" + dir_ + "' exists and is not a folder");
  if (resume && !fs::exists(dir_ + "/checkpoint.bin", ec))
    throw InputError("cannot resume: '" + dir_ + "' holds no checkpoint.bin");
  fs::create_directories(dir_, ec);
  if (ec) throw InputError("cannot create output folder '" + dir_ + "': " + ec.message());
  if (::access(dir_.c_str(), W_OK) != 0) throw InputError("output folder '" + dir_ + "' is not writable");
  // One run per folder. flock() belongs to the open file: it ends with the process however the
  // process ends (kill -9 included), so no stale lock can block the folder.
  const std::string lockPath = path(kLock);
  lockFd_ = ::open(lockPath.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lockFd_ < 0) throw InputError("cannot lock output folder '" + dir_ + "': " + std::strerror(errno));
  if (::flock(lockFd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    std::string holder = readSmallFile(lockPath, 32);
    while (!holder.empty() && (holder.back() == '\n' || holder.back() == ' ')) holder.pop_back();
    ::close(lockFd_);
    lockFd_ = -1;
    if (err == EWOULDBLOCK)
      throw InputError("output folder '" + dir_ + "' is in use by another Talus run" +
                       (holder.empty() ? std::string() : " (process " + holder + ")") +
                       "; wait for it to end or choose another folder");
    throw InputError("cannot lock output folder '" + dir_ + "': " + std::strerror(err));
  }
  try {
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(lockFd_, 0) != 0 || ::write(lockFd_, pid.data(), pid.size()) < 0) {
      // The pid is only for the message a second run prints; the lock itself holds.
    }
    const bool holdsRun = fs::exists(path("summary.json"), ec) || fs::exists(path("diagnostics.csv"), ec) ||
                          fs::exists(path(kManifest), ec);
    if (!overwrite && !resume && holdsRun)
      throw InputError("output folder '" + dir_ + "' already holds a run; choose another folder or pass --overwrite");
  } catch (...) {
    ::close(lockFd_);  // a constructor that throws runs no destructor: release the lock here
    lockFd_ = -1;
    throw;
  }
}

OutputWriter::~OutputWriter() {
  try {
    csv_.close();
    manifest_.close();
  } catch (const std::exception&) {
    // A failed close of the CSV or manifest at teardown was already reported by the write that
    // failed, or the run is being abandoned: nothing more to say.
  }
  if (lockFd_ >= 0) ::close(lockFd_);  // releases the lock
}

void OutputWriter::removePreviousRun() {
  std::error_code ec;
  std::istringstream manifest(readSmallFile(path(kManifest), std::size_t{64} << 20));
  std::string name;
  while (std::getline(manifest, name))
    if (insideFolder(name)) fs::remove(path(name), ec);
  for (const char* fixed : kFixedOutputs) fs::remove(path(fixed), ec);
  fs::remove(path(kManifest), ec);
  // Folders the previous run made, once empty (a user's own files in them stay).
  for (const char* sub : {"series", "particles"}) {
    if (fs::is_directory(path(sub), ec) && fs::is_empty(path(sub), ec)) fs::remove(path(sub), ec);
  }
}

void OutputWriter::prepare() {
  std::error_code ec;
  if (resume_) {
    fs::remove(path("summary.json"), ec);
    // Temporary files of writes a kill interrupted (the finished files they would have replaced
    // are intact: every write is a rename).
    for (const auto& e : fs::recursive_directory_iterator(dir_, ec))
      if (e.path().filename().string().find(".tmp-") != std::string::npos) fs::remove(e.path(), ec);
    std::istringstream manifest(readSmallFile(path(kManifest), std::size_t{64} << 20));
    std::string name;
    while (std::getline(manifest, name)) claimed_.insert(name);
    manifest_.open(path(kManifest), false);
    return;
  }
  removePreviousRun();
  fs::create_directories(path("series"), ec);
  if (ec) throw IoError("cannot create folder '" + path("series") + "': " + ec.message());
  manifest_.open(path(kManifest), true);
}

std::string OutputWriter::claim(const std::string& name) {
  if (claimed_.insert(name).second) manifest_.appendLine(name);
  return path(name);
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
  io::writeRaster(claim(name + ext), r, format_);
}

void OutputWriter::writeMapAs(const std::string& fileName, const std::vector<double>& values) {
  Raster r(dem_.grid, 0.0);
  r.values = values;
  r.valid = dem_.valid;
  r.nodata = -9999.0;
  io::writeRaster(claim(fileName), r, format_);
}

void OutputWriter::writeText(const std::string& name, const std::string& content) {
  writeFileAtomically(claim(name), content);
}

std::string OutputWriter::keptDiagnostics(const std::string& header, long long rows) const {
  std::ifstream in(path("diagnostics.csv"), std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  const std::string text = all.str();
  // Rows of other columns (a run started by another Talus version) would not continue this header.
  const std::string own = text.substr(0, text.find('\n'));
  if (own != header)
    throw InputError("cannot resume: '" + path("diagnostics.csv") + "' has other columns than this version of Talus " +
                     "writes (another version started the run); resume it with that version, or run it again");
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
  return kept;
}

void OutputWriter::checkDiagnostics(const std::string& header, long long rows) const { keptDiagnostics(header, rows); }

void OutputWriter::truncateDiagnostics(const std::string& header, long long rows) {
  writeText("diagnostics.csv", keptDiagnostics(header, rows));
  csv_.open(path("diagnostics.csv"), false);
}

void OutputWriter::appendDiagnostics(const std::string& header, const std::string& line) {
  if (!csv_.isOpen()) {
    csv_.open(claim("diagnostics.csv"), true);
    csv_.appendLine(header);
  }
  csv_.appendLine(line);
}

}  // namespace talus::sim
