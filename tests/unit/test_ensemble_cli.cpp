// `talus ensemble` end to end (src/ensemble/EnsembleCommand): the executable named by TALUS_BINARY
// on tiny lake ensembles (tests/support/EnsembleScenes.hpp): bad files exit with status 2 naming the
// line, --list and --slurm run nothing, a kill -9 in the middle loses no finished member and leaves
// none that looks finished, and `mpirun -np 2` merges bitwise the same maps as the serial run.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <thread>

#include "ensemble/EnsembleMpi.hpp"
#include "support/CliRun.hpp"
#include "support/EnsembleScenes.hpp"

#ifndef TALUS_BINARY
#define TALUS_BINARY ""
#endif

namespace fs = std::filesystem;
using talus::test::Outcome;
using talus::test::shellQuote;
using talus::test::slurp;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

class EnsembleCli : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(TALUS_BINARY)) << "talus executable not found at '" << TALUS_BINARY << "'";
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("talus_enscli_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  Outcome talus(const std::string& args, const std::string& prefix = "") {
    return talus::test::runIn(dir_, TALUS_BINARY, args, prefix);
  }
  /// The files of OUTPUT/merged, name -> bytes.
  std::map<std::string, std::string> mergedFiles(const std::string& outputDir) const {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::directory_iterator(dir_ / outputDir / "merged")) files[e.path().filename().string()] = slurp(e.path());
    return files;
  }
  /// A copy of lake.ens writing into another output folder (same members, same seed).
  std::string copyWithOutput(const std::string& ens, const std::string& outputDir) {
    std::string text = slurp(ens);
    const std::size_t at = text.find("Output Directory=ens");
    text.replace(at, std::string("Output Directory=ens").size(), "Output Directory=" + outputDir);
    const std::string path = (dir_ / (outputDir + ".ens")).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  fs::path dir_;
};

const char* kRandomLake = "Initial Fluid Height=uniform 0.02 0.4";
const char* kMaps = "[Maps]\nThickness Thresholds=0.1 0.2\nArrival Times=1\nPercentiles=10 50 90\n";

}  // namespace

TEST_F(EnsembleCli, BadFileExitsWithStatusTwoNamingTheLine) {
  talus::test::writeLakeEnsemble(dir_, "Manning=uniform 0.1", 4);
  const Outcome r = talus("ensemble lake.ens");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "lake.ens:7: key 'Manning': uniform takes two numbers")) << r;
  // A run-file key that does not exist is named with the ensemble file's line.
  talus::test::writeLakeEnsemble(dir_, "Manning Coefficient=uniform 0.01 0.1", 4);
  const Outcome k = talus("ensemble lake.ens");
  EXPECT_EQ(k.status, 2) << k;
  EXPECT_TRUE(contains(k.err, "lake.ens:7: key 'Manning Coefficient': not a key")) << k;
  const Outcome u = talus("ensemble lake.ens --frobnicate");
  EXPECT_EQ(u.status, 2) << u;
  EXPECT_TRUE(contains(u.err, "unknown option '--frobnicate'")) << u;
}

TEST_F(EnsembleCli, ListAndSlurmRunNothing) {
  talus::test::writeLakeEnsemble(dir_, "Initial Fluid Height=list 0.1 0.2 0.3", 3);
  const Outcome l = talus("ensemble lake.ens --list");
  ASSERT_EQ(l.status, 0) << l;
  EXPECT_TRUE(contains(l.out, "m0002\t0.3\tto run")) << l;
  const Outcome s = talus("ensemble lake.ens --slurm");
  ASSERT_EQ(s.status, 0) << s;
  const std::string members = slurp(dir_ / "ens/slurm/members.sbatch");
  EXPECT_TRUE(contains(members, "#SBATCH --array=0-2")) << members;
  EXPECT_TRUE(contains(members, "ensemble '" + (dir_ / "lake.ens").string() + "' --members \"$i-$i\"")) << members;
  EXPECT_TRUE(contains(slurp(dir_ / "ens/slurm/merge.sbatch"), "--merge"));
  EXPECT_TRUE(contains(slurp(dir_ / "ens/slurm/submit.sh"), "--dependency=afterok:"));
  EXPECT_FALSE(fs::exists(dir_ / "ens/members"));
  // One array task's work: one member, no merge.
  const Outcome one = talus("ensemble lake.ens --members 1-1 --quiet");
  ASSERT_EQ(one.status, 0) << one;
  EXPECT_TRUE(fs::exists(dir_ / "ens/members/m0001/member.json"));
  EXPECT_FALSE(fs::exists(dir_ / "ens/members/m0000"));
  EXPECT_FALSE(fs::exists(dir_ / "ens/merged"));
  const Outcome early = talus("ensemble lake.ens --merge");
  EXPECT_EQ(early.status, 2) << early;
  EXPECT_TRUE(contains(early.err, "2 of 3 members are not complete (m0000, m0002)")) << early;
}

TEST_F(EnsembleCli, KillNineLosesNoFinishedMember) {
  const std::string ens = talus::test::writeLakeEnsemble(dir_, kRandomLake, 10, kMaps);
  // Start the ensemble in the background and kill it hard once two members have finished.
  const std::string cmd = "cd " + shellQuote(dir_.string()) + " && " + shellQuote(TALUS_BINARY) +
                          " ensemble lake.ens --quiet >/dev/null 2>&1 & echo $! > " + shellQuote((dir_ / "pid").string());
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(dir_ / "ens/members/m0001") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const std::string pid = slurp(dir_ / "pid");
  ASSERT_EQ(std::system(("kill -9 " + pid + " 2>/dev/null; sleep 0.2").c_str()), 0);
  ASSERT_TRUE(fs::exists(dir_ / "ens/members/m0001")) << "no member finished within 120 s";
  // Every folder named like a member is complete; anything else is a .partial folder.
  int finished = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "ens/members")) {
    const std::string name = e.path().filename().string();
    if (name[0] == '.') continue;
    ++finished;
    EXPECT_TRUE(fs::exists(e.path() / "member.json")) << name;
    EXPECT_TRUE(contains(slurp(e.path() / "summary.json"), "\"status\": \"completed\"")) << name;
  }
  ASSERT_LT(finished, 10) << "the kill came too late to test anything";
  const Outcome again = talus("ensemble lake.ens");
  ASSERT_EQ(again.status, 0) << again;
  EXPECT_TRUE(contains(again.err, std::to_string(10 - finished) + " members run, " + std::to_string(finished) +
                                      " already finished")) << again;
  // The resumed ensemble merges bitwise the same as one that was never interrupted.
  ASSERT_EQ(talus("ensemble " + shellQuote(copyWithOutput(ens, "clean")) + " --quiet").status, 0);
  const auto resumed = mergedFiles("ens"), clean = mergedFiles("clean");
  ASSERT_EQ(resumed.size(), clean.size());
  for (const auto& [name, bytes] : clean) EXPECT_TRUE(resumed.at(name) == bytes) << name;
}

TEST_F(EnsembleCli, MpiTwoRanksMergeBitwiseAsTheSerialRun) {
  if (std::system("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun is not installed (openmpi-bin)";
  if (!talus::ensemble::builtWithMpi()) GTEST_SKIP() << "this build has no MPI (libopenmpi-dev was not found)";
  const std::string ens = talus::test::writeLakeEnsemble(dir_, kRandomLake, 6, kMaps);
  const Outcome serial = talus("ensemble lake.ens --quiet");
  ASSERT_EQ(serial.status, 0) << serial;
  const std::string mpiEns = copyWithOutput(ens, "mpi");
  // Open MPI refuses root without these; --oversubscribe allows 2 ranks on fewer cores.
  const std::string prefix =
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 mpirun -np 2 --oversubscribe";
  const Outcome mpi = talus("ensemble " + shellQuote(mpiEns), prefix);
  ASSERT_EQ(mpi.status, 0) << mpi;
  EXPECT_TRUE(contains(mpi.err, "rank 0: m0000")) << mpi;
  EXPECT_TRUE(contains(mpi.err, "rank 1: m0001")) << mpi;
  const auto a = mergedFiles("ens"), b = mergedFiles("mpi");
  ASSERT_EQ(a.size(), b.size());
  ASSERT_GE(a.size(), 8u);
  for (const auto& [name, bytes] : a) EXPECT_TRUE(b.at(name) == bytes) << name << " differs between serial and MPI";
}
