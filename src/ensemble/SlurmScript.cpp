// Slurm job-array scripts of an ensemble (see SlurmScript.hpp).
#include "ensemble/SlurmScript.hpp"

#include <sys/stat.h>

#include <filesystem>

#include "core/FileWrite.hpp"

namespace talus::ensemble {
namespace fs = std::filesystem;

namespace {

/// Single-quoted for sh: ' becomes '\''.
std::string sh(const std::string& s) {
  std::string o = "'";
  for (char c : s) {
    if (c == '\'') o += "'\\''";
    else o += c;
  }
  return o + "'";
}

}  // namespace

SlurmScripts slurmScripts(const EnsembleSpec& spec, const std::string& binary) {
  const std::string logs = (fs::path(spec.outputDir) / "slurm").string();
  SlurmScripts s;
  s.members = "#!/bin/bash\n"
              "# One ensemble member per array task; written by `talus ensemble --slurm`.\n"
              "# Resources: edit to your cluster (one GPU per task; the member picks the GPU Slurm gives it).\n"
              "#SBATCH --job-name=talus-members\n"
              "#SBATCH --array=0-" + std::to_string(spec.members - 1) + "\n"
              "#SBATCH --ntasks=1\n"
              "#SBATCH --gres=gpu:1\n"
              "#SBATCH --time=01:00:00\n"
              "#SBATCH --output=" + logs + "/member_%a.log\n"
              "set -euo pipefail\n"
              "i=${SLURM_ARRAY_TASK_ID}\n"
              "# A finished member is skipped, so a requeued or resubmitted task costs nothing.\n"
              "exec " + sh(binary) + " ensemble " + sh(spec.file) + " --members \"$i-$i\" --quiet\n";
  s.merge = "#!/bin/bash\n"
            "# Merges the members once the whole array has succeeded; written by `talus ensemble --slurm`.\n"
            "#SBATCH --job-name=talus-merge\n"
            "#SBATCH --ntasks=1\n"
            "#SBATCH --time=00:30:00\n"
            "#SBATCH --output=" + logs + "/merge.log\n"
            "set -euo pipefail\n"
            "exec " + sh(binary) + " ensemble " + sh(spec.file) + " --merge\n";
  s.submit = "#!/bin/bash\n"
             "# Submits the member array and the merge that waits for it (afterok: every task succeeded).\n"
             "set -euo pipefail\n"
             "cd " + sh(logs) + "\n"
             "array=$(sbatch --parsable members.sbatch)\n"
             "sbatch --dependency=afterok:${array%%;*} merge.sbatch\n"
             "echo \"submitted member array ${array} and its merge\"\n";
  return s;
}

std::vector<std::string> writeSlurmScripts(const EnsembleSpec& spec, const std::string& binary) {
  const fs::path dir = fs::path(spec.outputDir) / "slurm";
  fs::create_directories(dir);
  const SlurmScripts s = slurmScripts(spec, binary);
  std::vector<std::string> paths;
  for (const auto& [name, text] : {std::pair<const char*, const std::string*>{"members.sbatch", &s.members},
                                   {"merge.sbatch", &s.merge}, {"submit.sh", &s.submit}}) {
    const std::string p = (dir / name).string();
    writeFileAtomically(p, *text);
    ::chmod(p.c_str(), 0755);
    paths.push_back(p);
  }
  return paths;
}

}  // namespace talus::ensemble
