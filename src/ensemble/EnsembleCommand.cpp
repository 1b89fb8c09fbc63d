// The `talus ensemble` command (see EnsembleCommand.hpp).
#include "ensemble/EnsembleCommand.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>

#include "compute/Device.hpp"
#include "core/Error.hpp"
#include "ensemble/EnsembleFile.hpp"
#include "ensemble/EnsembleMerge.hpp"
#include "ensemble/EnsembleMpi.hpp"
#include "ensemble/EnsembleRun.hpp"
#include "ensemble/Sampling.hpp"
#include "ensemble/SlurmScript.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"

namespace talus::ensemble {
namespace {

struct Options {
  std::string file, device;
  bool merge = false, list = false, slurm = false, quiet = false;
  bool range = false;
  long long first = 0, last = -1;
};

long long wholeNumber(const std::string& s, const std::string& what) {
  char* end = nullptr;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || v < 0) throw InputError("--members: '" + what + "' is not a range A-B of member numbers (0-based)");
  return v;
}

Options parse(const std::vector<std::string>& args) {
  Options o;
  for (std::size_t a = 0; a < args.size(); ++a) {
    const std::string& arg = args[a];
    auto value = [&](const char* flag) -> std::string {
      if (a + 1 >= args.size()) throw InputError(std::string("option ") + flag + " needs a value");
      return args[++a];
    };
    if (arg == "--merge") o.merge = true;
    else if (arg == "--list") o.list = true;
    else if (arg == "--slurm") o.slurm = true;
    else if (arg == "--quiet") o.quiet = true;
    else if (arg == "--device") o.device = value("--device");
    else if (arg == "--members") {
      const std::string r = value("--members");
      const std::size_t dash = r.find('-');
      o.range = true;
      o.first = wholeNumber(r.substr(0, dash), r);
      o.last = dash == std::string::npos ? o.first : wholeNumber(r.substr(dash + 1), r);
      if (o.last < o.first) throw InputError("--members " + r + ": the last member comes before the first");
    } else if (!arg.empty() && arg[0] == '-') throw InputError("talus ensemble: unknown option '" + arg + "'");
    else if (o.file.empty()) o.file = arg;
    else throw InputError("talus ensemble: more than one ensemble file given ('" + o.file + "' and '" + arg + "')");
  }
  if (o.file.empty()) throw InputError(std::string("talus ensemble: no ensemble file given\n") + ensembleUsage());
  if (o.merge + o.list + o.slurm + o.range > 1)
    throw InputError("talus ensemble: give at most one of --merge, --list, --slurm and --members");
  return o;
}

std::string selfPath() {
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? "talus" : p.string();
}

int list(const EnsembleSpec& spec) {
  std::printf("member");
  for (const Parameter& p : spec.parameters) std::printf("\t%s", p.key.c_str());
  std::printf("\tstate\n");
  for (long long m = 0; m < spec.members; ++m) {
    std::printf("%s", memberName(m).c_str());
    for (double v : memberValues(spec, m)) std::printf("\t%.10g", v);
    std::printf("\t%s\n", memberComplete(spec, m) ? "done" : "to run");
  }
  return 0;
}

/// The device of this rank when several ranks share a machine and nothing was chosen: rank mod
/// the number of GPUs (else of all devices).
std::string rankDevice(const io::RunConfig& base, int rank, int size) {
  if (size <= 1 || !base.text("Device").empty() || std::getenv("TALUS_DEVICE")) return "";
  const auto devices = compute::listDevices();
  std::vector<int> gpus, all;
  for (const auto& d : devices) {
    all.push_back(d.index);
    if (d.isGpu) gpus.push_back(d.index);
  }
  const std::vector<int>& pool = gpus.empty() ? all : gpus;
  if (pool.empty()) return "";
  return std::to_string(pool[static_cast<std::size_t>(rank) % pool.size()]);
}

int merge(const EnsembleSpec& spec, const io::RunConfig& base, bool quiet) {
  const MergeReport r = mergeEnsemble(spec, base);
  if (!quiet)
    std::fprintf(stderr, "talus: merged %d members into %s/merged (%zu files)\n", r.members, spec.outputDir.c_str(),
                 r.files.size());
  if (!r.best.empty()) std::printf("talus: %s\n", r.best.c_str());
  return 0;
}

}  // namespace

const char* ensembleUsage() {
  return "       talus ensemble FILE [--device SEL] [--quiet]   (run the members not finished yet, then merge;\n"
         "                                                    under mpirun -np N the ranks share the members)\n"
         "       talus ensemble FILE --members A-B | --merge | --list | --slurm\n";
}

int ensembleCommand(const std::vector<std::string>& args) {
  const Options opt = parse(args);
  const EnsembleSpec spec = loadEnsembleFile(opt.file);
  if (opt.list) return list(spec);
  if (opt.slurm) {
    for (const std::string& p : writeSlurmScripts(spec, selfPath())) std::printf("talus: wrote %s\n", p.c_str());
    std::printf("talus: submit with  bash %s/slurm/submit.sh\n", spec.outputDir.c_str());
    return 0;
  }
  // The base run-file is parsed once; every member is a copy with its parameters set.
  const io::RunConfig base = io::RunConfig::load(spec.runFile, talusRunKeys());
  if (opt.merge) return merge(spec, base, opt.quiet);
  std::vector<long long> members;
  if (opt.range && opt.last >= spec.members)
    throw InputError("--members " + std::to_string(opt.first) + "-" + std::to_string(opt.last) + ": the ensemble has members 0-" +
                     std::to_string(spec.members - 1));
  for (long long m = opt.range ? opt.first : 0; m <= (opt.range ? opt.last : spec.members - 1); ++m) members.push_back(m);

  RankSession ranks;
  RunOptions run;
  run.quiet = opt.quiet;
  run.device = opt.device.empty() ? rankDevice(base, ranks.rank(), ranks.size()) : opt.device;
  if (ranks.size() > 1) run.label = "rank " + std::to_string(ranks.rank()) + ": ";
  std::exception_ptr error;
  RunOutcome outcome;
  int local = 0;
  try {
    outcome = runMembers(spec, base, membersOfRank(members, ranks.rank(), ranks.size()), run);
    local = outcome.failures.empty() ? 0 : 4;
  } catch (const InputError&) {
    error = std::current_exception();
    local = 2;
  } catch (const ComputeError&) {
    error = std::current_exception();
    local = 3;
  } catch (const IoError&) {
    error = std::current_exception();
    local = 5;
  } catch (...) {
    error = std::current_exception();
    local = 1;
  }
  // Every rank reaches this reduction, whatever happened to it, so no rank waits for ever.
  const int status = ranks.maxOverRanks(local);
  if (!opt.quiet && ranks.rank() == 0 && status == 0)
    std::fprintf(stderr, "talus: %d members run, %d already finished\n", outcome.ran, outcome.skipped);
  if (status == 0 && !opt.range && ranks.rank() == 0) {
    try {
      merge(spec, base, opt.quiet);
    } catch (...) {
      error = std::current_exception();
    }
  }
  ranks.finish();
  if (error) std::rethrow_exception(error);
  if (!outcome.failures.empty()) {
    std::fprintf(stderr, "talus: %zu member(s) became unstable (their .partial folders are kept; the merge waits for them):\n",
                 outcome.failures.size());
    for (const std::string& f : outcome.failures) std::fprintf(stderr, "talus:   %s\n", f.c_str());
    return 4;
  }
  if (status != 0) {
    std::fprintf(stderr, "talus: %sanother rank failed (see its messages); no merge\n", run.label.c_str());
    return status;
  }
  return 0;
}

}  // namespace talus::ensemble
