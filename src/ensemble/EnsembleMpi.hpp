// The MPI side of `talus ensemble`: when the program was started by mpirun and built with MPI
// (TALUS_HAVE_MPI, CMake's find_package(MPI)), ranks share the members round-robin and meet in a
// reduction before rank 0 merges. Without mpirun (or without MPI) there is one rank. MPI is only
// initialised by `talus ensemble`; `talus run` never touches it.
#pragma once
#include <vector>

namespace talus::ensemble {

/// True when this build of Talus has MPI.
bool builtWithMpi();

/// The number of processes the launcher announced (OMPI_COMM_WORLD_SIZE, PMI_SIZE), 1 without one.
int launcherSize();

/// The ranks of this run. Without MPI (or without a launcher) rank 0 of 1.
class RankSession {
 public:
  /// Initialises MPI when built with it and started by a launcher. Throws InputError when a
  /// launcher started several processes but this build has no MPI (each would run every member).
  RankSession();
  ~RankSession();
  RankSession(const RankSession&) = delete;
  RankSession& operator=(const RankSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// The largest `value` over all ranks; every rank must call it (it is also a barrier).
  int maxOverRanks(int value) const;
  /// Ends MPI (the destructor does it otherwise).
  void finish();

 private:
  int rank_ = 0, size_ = 1;
  bool active_ = false;
};

/// The members rank `rank` of `size` runs: every size-th of `members`, starting at `rank`.
std::vector<long long> membersOfRank(const std::vector<long long>& members, int rank, int size);

}  // namespace talus::ensemble
