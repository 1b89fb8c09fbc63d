// `talus ensemble FILE [--members A-B] [--merge] [--list] [--slurm] [--device SEL] [--quiet]`
// (docs/ensembles.md):
//   (no option)   run every member not finished yet, then merge (under mpirun: ranks share the members)
//   --members A-B run members A..B only (0-based, inclusive; no merge): one Slurm array task
//   --merge       merge the finished members only
//   --list        print each member's parameters, run nothing
//   --slurm       write OUTPUT/slurm/{members.sbatch, merge.sbatch, submit.sh}, run nothing
#pragma once
#include <string>
#include <vector>

namespace talus::ensemble {

/// Runs the command with the arguments after "ensemble". Returns the exit status (0, or 4 when a
/// member's simulation became unstable); throws the engine's errors for main() to report.
int ensembleCommand(const std::vector<std::string>& args);

/// The usage lines of the command.
const char* ensembleUsage();

}  // namespace talus::ensemble
