// Rank session of `talus ensemble` (see EnsembleMpi.hpp). The MPI calls are compiled only with
// TALUS_HAVE_MPI.
#include "ensemble/EnsembleMpi.hpp"

#include <cstdlib>
#include <string>

#include "core/Error.hpp"

#ifdef TALUS_HAVE_MPI
#include <mpi.h>
#endif

namespace talus::ensemble {

bool builtWithMpi() {
#ifdef TALUS_HAVE_MPI
  return true;
#else
  return false;
#endif
}

int launcherSize() {
  for (const char* var : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"}) {
    const char* v = std::getenv(var);
    if (v && *v) {
      const int n = std::atoi(v);
      if (n > 0) return n;
    }
  }
  return 1;
}

RankSession::RankSession() {
  const int announced = launcherSize();
  if (!builtWithMpi()) {
    if (announced > 1)
      throw InputError("started by mpirun with " + std::to_string(announced) +
                       " processes, but this talus was built without MPI (each process would run every "
                       "member); install libopenmpi-dev and rebuild, or run without mpirun");
    return;
  }
#ifdef TALUS_HAVE_MPI
  if (announced <= 1 && !std::getenv("OMPI_COMM_WORLD_RANK")) return;  // no launcher: plain serial run
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  active_ = true;
#endif
}

RankSession::~RankSession() { finish(); }

void RankSession::finish() {
#ifdef TALUS_HAVE_MPI
  if (active_) MPI_Finalize();
#endif
  active_ = false;
}

int RankSession::maxOverRanks(int value) const {
#ifdef TALUS_HAVE_MPI
  if (active_) {
    int out = value;
    MPI_Allreduce(&value, &out, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return out;
  }
#endif
  return value;
}

std::vector<long long> membersOfRank(const std::vector<long long>& members, int rank, int size) {
  std::vector<long long> mine;
  for (std::size_t k = static_cast<std::size_t>(rank); k < members.size(); k += static_cast<std::size_t>(size))
    mine.push_back(members[k]);
  return mine;
}

}  // namespace talus::ensemble
