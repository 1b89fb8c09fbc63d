// Running ensemble members in this process, one after another. Each member is the base run-file
// with the member's parameters set on it (the base is parsed once), run by sim::Simulation into a
// private folder members/.mNNNN.partial-HOST-PID that is renamed to members/mNNNN once the run and
// its member.json are complete. A folder named mNNNN is therefore always a finished member: a kill
// at any moment leaves at most a .partial folder, which the next run removes and reruns.
#pragma once
#include <string>
#include <vector>

#include "ensemble/EnsembleFile.hpp"
#include "io/RunConfig.hpp"

namespace talus::ensemble {

/// "m0003" (at least four digits).
std::string memberName(long long member);
/// OUTPUT/members/mNNNN: the folder of a finished member.
std::string memberDir(const EnsembleSpec& spec, long long member);
/// True when the member's folder exists with its member.json.
bool memberComplete(const EnsembleSpec& spec, long long member);

/// The --set assignments that turn the base configuration into the member's ("Manning=0.035",
/// "Initial Fluid Height=\"/abs/water.tif\"=1.07"). Values are written with 17 significant digits,
/// so they read back as the exact double drawn.
std::vector<std::string> memberAssignments(const EnsembleSpec& spec, const io::RunConfig& base, long long member);

/// How members are run.
struct RunOptions {
  std::string device;  ///< device selector for every member ("" = the run-file's, else automatic)
  bool quiet = false;  ///< no per-member lines on stderr
  std::string label;   ///< prefix of the per-member lines ("rank 1: "), may be empty
};

/// What a call of runMembers did.
struct RunOutcome {
  int ran = 0;      ///< members run to completion by this call
  int skipped = 0;  ///< members found complete (or running in another process) and left alone
  std::vector<std::string> failures;  ///< "m0004: <reason>" for members whose simulation became unstable
};

/// Runs the given members that are not complete yet. A member whose simulation becomes unstable is
/// recorded in RunOutcome::failures (its .partial folder is kept for inspection) and the others go on;
/// a bad parameter value (InputError) stops with the member named. A finished member whose
/// member.json records other assignments than the ensemble file now gives is an InputError (the
/// file changed since: use a new Output Directory).
RunOutcome runMembers(const EnsembleSpec& spec, const io::RunConfig& base, const std::vector<long long>& members,
                      const RunOptions& options);

/// Throws InputError when finished member `member` was run with other assignments than `expected`.
void checkMemberRecord(const EnsembleSpec& spec, long long member, const std::vector<std::string>& expected);

}  // namespace talus::ensemble
