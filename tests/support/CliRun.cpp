#include "support/CliRun.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

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

Outcome runIn(const std::filesystem::path& dir, const std::string& binary, const std::string& args) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = "cd " + shellQuote(dir.string()) + " && " + shellQuote(binary) + " " + args + " >" +
                          shellQuote(out.string()) + " 2>" + shellQuote(err.string()) + " </dev/null";
  const int raw = std::system(cmd.c_str());
  Outcome r;
  if (raw != -1 && WIFEXITED(raw)) r.status = WEXITSTATUS(raw);
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

}  // namespace talus::test
