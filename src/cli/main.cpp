// talus: the headless command line.
//   talus run SCENE.run [--out DIR] [--device SEL] [--precision float|double] [--set "Key=Value"]...
//             [--overwrite] [--quiet]
//   talus run --resume DIR [--device SEL] [--set "Key=Value"]... [--quiet]
//   talus ensemble FILE [--members A-B | --merge | --list | --slurm] [--device SEL] [--quiet]
//   talus devices
//   talus keys [--markdown]
//   talus convert-runfile OPENLISEM.run TALUS.run
//   talus render MAP.tif -o MAP.png [--hillshade DEM] [--ramp NAME] [--range LO HI] [--label TEXT]
//                [--threshold T] [--scale N]
// Exit status: 0 success, 1 usage or unexpected error, 2 bad input, 3 compute device error,
// 4 simulation became unstable (outputs so far are kept), 5 outputs could not be written (full disk,
// permissions, quota: the system's reason is printed, summary.json says "failed" where it could be
// written).
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "compute/Device.hpp"
#include "core/Error.hpp"
#include "core/FileWrite.hpp"
#include "ensemble/EnsembleCommand.hpp"
#include "io/MapRender.hpp"
#include "io/RunConfig.hpp"
#include "io/RunFileConvert.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

namespace {

void usage(std::FILE* f) {
  std::fprintf(f,
               "usage: talus run SCENE.run [--out DIR] [--device SEL] [--precision float|double]\n"
               "                 [--set \"Key=Value\"]... [--overwrite] [--quiet]\n"
               "       talus run --resume DIR [--device SEL] [--set \"Key=Value\"]... [--quiet]\n"
               "%s"
               "       talus devices\n"
               "       talus keys [--markdown]\n"
               "       talus convert-runfile OPENLISEM.run TALUS.run\n"
               "         (writes a Talus run-file from an OpenLISEM Hazard one; lists what it dropped or changed)\n"
               "       talus render MAP.tif -o MAP.png [--hillshade DEM.tif] [--ramp depth|heat|viridis|cohesion]\n"
               "                    [--range LO HI] [--label TEXT] [--threshold T] [--scale PIXELS_PER_CELL]\n"
               "         (renders an output map over the DEM's hillshade with a legend; cells <= T, default 0,\n"
               "          and nodata show only the hillshade)\n"
               "The device can also be chosen with the environment variable TALUS_DEVICE (index or name).\n",
               talus::ensemble::ensembleUsage());
}

int listDevices() {
  const auto devices = talus::compute::listDevices();
  if (devices.empty()) {
    std::fprintf(stderr, "talus: no OpenCL device found (on Debian: apt-get install pocl-opencl-icd)\n");
    return 3;
  }
  for (const auto& d : devices) std::printf("%s\n", d.describe().c_str());
  return 0;
}

int listKeys(bool markdown) {
  const auto& keys = talus::talusRunKeys();
  if (markdown) {
    std::printf("%s", talus::io::describeKeys(keys).c_str());
    return 0;
  }
  for (const auto& k : keys.keys())
    std::printf("%-24s %-10s default %-10s %s\n", k.name.c_str(), talus::io::keyTypeName(k.type).c_str(),
                k.defaultValue.empty() ? "\"\"" : k.defaultValue.c_str(), k.unit.c_str());
  return 0;
}

/// `talus convert-runfile IN OUT`: OUT must not exist yet (a converted file never replaces one).
int convertRunFile(int argc, char** argv) {
  if (argc != 4) throw talus::InputError("usage: talus convert-runfile OPENLISEM.run TALUS.run");
  const std::string in = argv[2], out = argv[3];
  std::error_code ec;
  if (std::filesystem::exists(out, ec)) throw talus::InputError("'" + out + "' exists already; give a new file name");
  const talus::io::Conversion c = talus::io::convertRunFile(in, talus::talusRunKeys());
  talus::writeFileAtomically(out, c.text);
  for (const std::string& line : c.report) std::printf("talus: %s\n", line.c_str());
  std::printf("talus: wrote %s\n", out.c_str());
  return 0;
}

/// One progress line on the terminal (rewritten in place on a TTY, every ~5% otherwise).
class ProgressPrinter {
 public:
  explicit ProgressPrinter(bool quiet) : quiet_(quiet), tty_(::isatty(STDERR_FILENO)) {}
  void operator()(const talus::sim::Progress& p) {
    if (quiet_) return;
    const double span = p.endTime - p.startTime;
    const double frac = span > 0 ? (p.time - p.startTime) / span : 1.0;
    const bool due = tty_ ? p.wallSeconds - lastWall_ >= 0.25 : frac - lastFrac_ >= 0.05;
    if (!due && frac < 1.0) return;
    lastWall_ = p.wallSeconds;
    lastFrac_ = frac;
    const double stepsPerSecond = p.wallSeconds > 0 ? p.steps / p.wallSeconds : 0.0;
    const double eta = frac > 0 ? p.wallSeconds * (1.0 - frac) / frac : 0.0;
    std::fprintf(stderr, "%st = %9.2f / %.2f s  %5.1f%%  step %lld  %.1f steps/s  ETA %.0f s   %s", tty_ ? "\r" : "",
                 p.time, p.endTime, 100.0 * frac, p.steps, stepsPerSecond, eta, tty_ ? "" : "\n");
    if (tty_ && frac >= 1.0) std::fprintf(stderr, "\n");
  }

 private:
  bool quiet_, tty_;
  double lastWall_ = -1.0, lastFrac_ = -1.0;
};

int runScene(int argc, char** argv) {
  std::string runFile, outDir, device, precision, resumeDir;
  std::vector<std::string> sets;
  bool overwrite = false, quiet = false;
  for (int a = 2; a < argc; ++a) {
    const std::string arg = argv[a];
    auto value = [&](const char* flag) -> std::string {
      if (a + 1 >= argc) throw talus::InputError(std::string("option ") + flag + " needs a value");
      return argv[++a];
    };
    if (arg == "--out") outDir = value("--out");
    else if (arg == "--device") device = value("--device");
    else if (arg == "--precision") precision = value("--precision");
    else if (arg == "--set") sets.push_back(value("--set"));
    else if (arg == "--overwrite") overwrite = true;
    else if (arg == "--resume") resumeDir = value("--resume");
    else if (arg == "--quiet") quiet = true;
    else if (!arg.empty() && arg[0] == '-') throw talus::InputError("unknown option '" + arg + "'");
    else if (runFile.empty()) runFile = arg;
    else throw talus::InputError("more than one run-file given ('" + runFile + "' and '" + arg + "')");
  }
  if (!resumeDir.empty()) {
    // A resumed run reads the resolved configuration its first part echoed into the folder.
    if (!runFile.empty() || !outDir.empty() || overwrite || !precision.empty())
      throw talus::InputError("--resume DIR takes the run-file, output folder and precision from DIR; "
                              "do not give them again");
    runFile = resumeDir + "/run.resolved.run";
    outDir = resumeDir;
  }
  if (runFile.empty()) throw talus::InputError("talus run: no run-file given");
  talus::io::RunConfig config = talus::io::RunConfig::load(runFile, talus::talusRunKeys());
  for (const std::string& s : sets) config.set(s);
  if (!device.empty()) config.set("Device=" + device);
  if (!precision.empty()) config.set("Precision=" + precision);
  const talus::sim::Scene scene = talus::sim::loadScene(config);
  // Warnings are shown even with --quiet: they say that the run is not quite what the run-file reads as.
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "talus: warning: %s\n", w.c_str());
  talus::sim::requireMaterial(scene, config);
  using talus::sim::OutputMode;
  const OutputMode mode = !resumeDir.empty() ? OutputMode::Resume : overwrite ? OutputMode::Overwrite : OutputMode::New;
  talus::sim::Simulation sim(scene, config, outDir, mode);
  if (!quiet)
    std::fprintf(stderr, "talus: %s on %s (%s), grid %dx%d of %g m%s\n", runFile.c_str(),
                 sim.context().device().name.c_str(), scene.precision.c_str(), scene.dem.grid.nx, scene.dem.grid.ny,
                 scene.dem.grid.dx,
                 mode == OutputMode::Resume ? (", resuming at t = " + std::to_string(sim.resumeTime()) + " s").c_str()
                                            : "");
  const std::string particleCost = sim.particleCost();
  if (!quiet && !particleCost.empty()) std::fprintf(stderr, "talus: particles: %s\n", particleCost.c_str());
  ProgressPrinter printer(quiet);
  const talus::sim::RunSummary s = sim.run([&](const talus::sim::Progress& p) { printer(p); });
  if (!quiet)
    std::fprintf(stderr,
                 "talus: done: %lld steps, %.2f s simulated in %.2f s wall, %.3g cell-updates/s, volume balance "
                 "error %.2e\n",
                 s.steps, s.simulatedSeconds, s.wallSeconds, s.cellUpdatesPerSecond, s.volumeBalanceError);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    usage(argc < 2 ? stderr : stdout);
    return argc < 2 ? 1 : 0;
  }
  const std::string cmd = argv[1];
  try {
    if (cmd == "run") return runScene(argc, argv);
    if (cmd == "ensemble") return talus::ensemble::ensembleCommand(std::vector<std::string>(argv + 2, argv + argc));
    if (cmd == "devices") return listDevices();
    if (cmd == "render") return talus::io::renderCommand(std::vector<std::string>(argv + 2, argv + argc));
    if (cmd == "convert-runfile") return convertRunFile(argc, argv);
    if (cmd == "keys") return listKeys(argc > 2 && !std::strcmp(argv[2], "--markdown"));
    std::fprintf(stderr, "talus: unknown command '%s'\n", cmd.c_str());
    usage(stderr);
    return 1;
  } catch (const talus::InputError& e) {
    std::fprintf(stderr, "\ntalus: error: %s\n", e.what());
    return 2;
  } catch (const talus::ComputeError& e) {
    std::fprintf(stderr, "\ntalus: device error: %s\n", e.what());
    return 3;
  } catch (const talus::IoError& e) {
    std::fprintf(stderr, "\ntalus: I/O error: %s\n", e.what());
    return 5;
  } catch (const talus::SimulationError& e) {
    std::fprintf(stderr,
                 "\ntalus: %s\ntalus: the maps and diagnostics written so far are kept; with a checkpoint the run "
                 "can be continued by `talus run --resume DIR` (e.g. with --set \"CFL=...\")\n",
                 e.what());
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "\ntalus: unexpected error: %s\n", e.what());
    return 1;
  }
}
