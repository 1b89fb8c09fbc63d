#include "form/RunFilePaths.hpp"

#include <algorithm>
#include <filesystem>

#include "io/LisemValues.hpp"

namespace talus::gui {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMapDirectory = "Map Directory";
constexpr const char* kOutputDirectory = "Output Directory";

/// `target` (absolute) as a value written in a run-file of folder `dir`: relative when a relative
/// path leads there (on another drive or root none does: then absolute).
std::string pathFrom(const fs::path& dir, const fs::path& target) {
  const fs::path rel = target.lexically_normal().lexically_relative(dir);
  return (rel.empty() ? target.lexically_normal() : rel).generic_string();
}

/// Where a path value written in a run-file of folder `base` points, as RunConfig reads it; false
/// for values that do not depend on the folder (absolute or quoted: quotes are kept as written).
/// A Windows drive path names its last component under `base` (OpenLISEM's site layout).
bool resolveAgainst(const fs::path& base, std::string value, bool isMapDirectory, fs::path& out) {
  if (!value.empty() && value.front() == '"') return false;
  if (io::isWindowsDrivePath(value)) {
    out = base / io::lastPathComponent(value);
    std::error_code ec;
    if (isMapDirectory && !fs::is_directory(out, ec)) out = base;  // RunConfig's fallback for it
    return true;
  }
  std::replace(value.begin(), value.end(), '\\', '/');
  if (fs::path(value).is_absolute()) return false;
  out = (base / value).lexically_normal();
  return true;
}

}  // namespace

void rebaseInputPaths(RunFileDocument& doc, const std::string& newDir) {
  const fs::path oldBase = fs::path(doc.baseDir()).lexically_normal();
  const fs::path newBase = fs::absolute(newDir).lexically_normal();
  if (oldBase == newBase) return;
  for (const auto& spec : doc.keys().keys()) {
    if (spec.type != io::KeyType::Directory || spec.name == kOutputDirectory || !doc.isGiven(spec.name)) continue;
    fs::path folder;
    if (resolveAgainst(oldBase, doc.value(spec.name), spec.name == kMapDirectory, folder))
      doc.setValue(spec.name, pathFrom(newBase, folder));
  }
  if (doc.isGiven(kMapDirectory)) return;  // the map files resolve against it, wherever it now is
  for (const auto& spec : doc.keys().keys()) {
    if (spec.type != io::KeyType::Map || !doc.isGiven(spec.name)) continue;
    const std::string value = doc.value(spec.name);
    const std::size_t eq = !value.empty() && value.front() == '"' ? std::string::npos : value.find('=');
    const std::string suffix = eq == std::string::npos ? "" : value.substr(eq);  // "=multiplier"
    fs::path file;
    std::error_code ec;
    // A uniform value is a number, not a file: only names of existing files are rewritten.
    if (resolveAgainst(oldBase, value.substr(0, eq), false, file) && fs::is_regular_file(file, ec))
      doc.setValue(spec.name, pathFrom(newBase, file) + suffix);
  }
}

}  // namespace talus::gui
