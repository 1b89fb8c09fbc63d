// `talus ensemble FILE --slurm`: a Slurm job array with one member per array task (each task runs
// `talus ensemble FILE --members i-i`, a single `talus run` of that member with the ensemble's
// completion marking), a merge job that runs once the whole array succeeded, and submit.sh, which
// submits both with the dependency. Slurm does the distribution; Talus only writes the scripts.
#pragma once
#include <string>
#include <vector>

#include "ensemble/EnsembleFile.hpp"

namespace talus::ensemble {

/// The three files' contents: members.sbatch, merge.sbatch, submit.sh.
struct SlurmScripts {
  std::string members, merge, submit;
};

/// The scripts for `spec`, calling the talus executable `binary` (absolute).
SlurmScripts slurmScripts(const EnsembleSpec& spec, const std::string& binary);

/// Writes the scripts into OUTPUT/slurm (created) and returns their paths.
std::vector<std::string> writeSlurmScripts(const EnsembleSpec& spec, const std::string& binary);

}  // namespace talus::ensemble
