// Running the talus executable from tests: shell quoting, captured output and exit status.
#pragma once
#include <filesystem>
#include <ostream>
#include <string>

namespace talus::test {

/// The whole file as bytes ("" when it cannot be read).
std::string slurp(const std::filesystem::path& path);
/// Quotes an argument for /bin/sh.
std::string shellQuote(const std::string& s);

/// What one run of an executable did.
struct Outcome {
  int status = -1;  ///< exit status, -1 when it did not exit normally (a crash)
  std::string out, err;
};
std::ostream& operator<<(std::ostream& o, const Outcome& r);

/// Runs `binary ARGS` (ARGS already shell-quoted as needed) in `dir`, stdin from /dev/null, with
/// stdout and stderr captured through files in `dir`. `shellPrefix` (e.g. "ulimit -f 16;") runs
/// in the same shell first, so its limits apply to the binary.
Outcome runIn(const std::filesystem::path& dir, const std::string& binary, const std::string& args,
              const std::string& shellPrefix = "");

/// Writes a tiny water scene into `dir`: dem.tif and water.tif (20 x 16 cells of 2 m, a block of
/// 0.5 m of water on a gentle slope) and the run-file `name` ([Output] Output Directory=out,
/// End Time 0.05 min, Timestep 1 s), with `extra` appended; returns the run-file's path.
std::string writeCliScene(const std::filesystem::path& dir, const std::string& extra = "",
                          const std::string& name = "case.run");

}  // namespace talus::test
