#include "compute/KernelSources.hpp"

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "core/Error.hpp"

namespace talus::compute {
namespace {

std::string readOne(const std::string& path) {
  if (const char* dir = std::getenv("TALUS_KERNEL_DIR")) {
    std::ifstream in(std::string(dir) + "/" + path);
    if (!in) throw ComputeError("kernel source '" + path + "' not found in TALUS_KERNEL_DIR=" + dir);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  for (const EmbeddedKernel& k : embeddedKernelSources())
    if (path == k.path) return k.source;
  throw ComputeError("kernel source '" + path + "' is not embedded in this binary");
}

void expand(const std::string& path, std::set<std::string>& seen, std::ostringstream& out) {
  if (!seen.insert(path).second) return;
  std::istringstream in(readOne(path));
  std::string line;
  int number = 0;
  out << "#line 1 \"" << path << "\"\n";
  while (std::getline(in, line)) {
    ++number;
    const auto pos = line.find("#include \"");
    if (pos != std::string::npos && line.find_first_not_of(" \t") == pos) {
      const auto start = pos + 10;
      const auto end = line.find('"', start);
      expand(line.substr(start, end - start), seen, out);
      out << "#line " << number + 1 << " \"" << path << "\"\n";
      continue;
    }
    out << line << "\n";
  }
}

}  // namespace

std::string loadKernelSource(const std::string& path) {
  std::set<std::string> seen;
  std::ostringstream out;
  expand(path, seen, out);
  return out.str();
}

}  // namespace talus::compute
