// Output integrity under faults (issue 14): every write checked through close and rename, one run
// per output folder, --overwrite that leaves nothing of the previous run, a failed resume that
// changes nothing, and particle layers defined at the start time. The faults are real: a file-size
// limit set with `ulimit -f` (the kernel refuses writes past it with EFBIG, as a full disk refuses
// them with ENOSPC), /dev/full, and a lock held by this process.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/Error.hpp"
#include "core/FileWrite.hpp"
#include "io/ParticleLayerIO.hpp"
#include "io/RasterIO.hpp"
#include "support/CliRun.hpp"

#ifndef TALUS_BINARY
#define TALUS_BINARY ""
#endif

namespace fs = std::filesystem;
using talus::test::Outcome;
using talus::test::slurp;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// Files under `dir` whose name holds ".tmp-" (what an interrupted atomic write leaves).
int temporaryFiles(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp-") != std::string::npos) ++n;
  return n;
}

class OutputIntegrity : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(TALUS_BINARY)) << "talus executable not found at " << TALUS_BINARY;
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("talus_io_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (!std::getenv("TALUS_KEEP_TEST_DIRS")) fs::remove_all(dir_);
  }
  Outcome talus(const std::string& args, const std::string& prefix = "") {
    return talus::test::runIn(dir_, TALUS_BINARY, args, prefix);
  }
  fs::path dir_;
};

}  // namespace

// /dev/full refuses every write with ENOSPC, the error of a full disk: the append must say so.
TEST(FileWrite, AFullDiskIsAnIoErrorWithTheSystemsReason) {
  talus::AppendFile f;
  f.open("/dev/full", false);
  try {
    f.appendLine("step,time_s");
    FAIL() << "a write to /dev/full was accepted";
  } catch (const talus::IoError& e) {
    EXPECT_TRUE(contains(e.what(), "/dev/full")) << e.what();
    EXPECT_TRUE(contains(e.what(), "No space left on device")) << e.what();
  }
  // An atomic write into a folder that does not exist: the target is named, nothing is left.
  EXPECT_THROW(talus::writeFileAtomically("/nonexistent-talus-folder/summary.json", "{}"), talus::IoError);
}

// A file-size limit above every file a short run writes (measured by a first run) but below what
// diagnostics.csv reaches in a longer one (a row per step): the run starts and stops mid-run when
// the CSV hits the limit. It must end with exit status 5 and the system's reason, leave no
// temporary file, and still write the maxima and a summary that says "failed" and why (they are
// small enough to fit).
TEST_F(OutputIntegrity, AWriteRefusedMidRunEndsTheRunAsAnIoFailure) {
  talus::test::writeCliScene(dir_, "Report Series=0\n");
  ASSERT_EQ(talus("run case.run --set \"End Time=0.01\"").status, 0);
  std::uintmax_t largest = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "out"))
    if (e.is_regular_file() && e.path().filename() != "diagnostics.csv")
      largest = std::max<std::uintmax_t>(largest, fs::file_size(e.path()));
  const std::uintmax_t blocks = (largest + 4096) / 512 + 1;  // ulimit -f counts 512-byte blocks
  fs::remove_all(dir_ / "out");
  const Outcome r = talus("run case.run --set \"End Time=0.5\"",
                          "ulimit -f " + std::to_string(blocks) + "; trap '' XFSZ;");
  EXPECT_EQ(r.status, 5) << r;
  EXPECT_TRUE(contains(r.err, "I/O error")) << r;
  EXPECT_TRUE(contains(r.err, "File too large")) << r;
  EXPECT_TRUE(contains(r.err, "diagnostics.csv")) << r;
  EXPECT_EQ(temporaryFiles(dir_ / "out"), 0);
  const std::string summary = slurp(dir_ / "out/summary.json");
  EXPECT_TRUE(contains(summary, "\"status\": \"failed\"")) << summary;
  EXPECT_TRUE(contains(summary, "File too large")) << summary;
  EXPECT_NO_THROW(talus::io::readRaster((dir_ / "out/hfmax.tif").string()));
}

// A limit below the size of the first file the run writes: it cannot start, says why with exit
// status 5 (not 2: the input is fine), and leaves no temporary file.
TEST_F(OutputIntegrity, AnOutputThatCannotBeWrittenAtTheStartIsAnIoError) {
  talus::test::writeCliScene(dir_);
  const Outcome r = talus("run case.run", "ulimit -f 1; trap '' XFSZ;");
  EXPECT_EQ(r.status, 5) << r;
  EXPECT_TRUE(contains(r.err, "File too large")) << r;
  EXPECT_EQ(temporaryFiles(dir_ / "out"), 0);
  EXPECT_FALSE(fs::exists(dir_ / "out/summary.json"));
}

// While a run holds the folder (here: this process holds its lock), no second run may write into
// it, with or without --overwrite or --resume; once the lock is gone the folder is free again.
TEST_F(OutputIntegrity, OneRunPerOutputFolder) {
  talus::test::writeCliScene(dir_, "Checkpoint Interval=0.01\n");
  ASSERT_EQ(talus("run case.run").status, 0);
  const std::string summary = slurp(dir_ / "out/summary.json");
  const int fd = ::open((dir_ / "out/.talus-lock").c_str(), O_RDWR);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  for (const char* args : {"run case.run --overwrite", "run --resume out --set \"End Time=0.1\""}) {
    const Outcome r = talus(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r;
    EXPECT_TRUE(contains(r.err, "in use by another Talus run")) << r;
  }
  EXPECT_EQ(slurp(dir_ / "out/summary.json"), summary);
  ::close(fd);
  EXPECT_EQ(talus("run case.run --overwrite").status, 0);
}

// --overwrite removes every file the previous run wrote (here a two-phase run's solid maps and
// series beside a water run), and nothing else (a user's notes in the folder stay).
TEST_F(OutputIntegrity, OverwriteLeavesNoFileOfThePreviousRun) {
  talus::test::writeCliScene(dir_, "[Solids]\nInclude Initial Solids=1\nInitial Solid Height=0.5\n", "solids.run");
  talus::test::writeCliScene(dir_);
  ASSERT_EQ(talus("run solids.run").status, 0);
  ASSERT_TRUE(fs::exists(dir_ / "out/hsmax.tif"));
  ASSERT_TRUE(fs::exists(dir_ / "out/series/hs_0000.tif"));
  std::ofstream(dir_ / "out/notes.txt") << "field notes";
  ASSERT_EQ(talus("run case.run --overwrite").status, 0);
  for (const char* gone : {"hsmax.tif", "vsmax.tif", "deposit.tif", "hsfinal.tif", "series/hs_0000.tif"})
    EXPECT_FALSE(fs::exists(dir_ / "out" / gone)) << gone;
  EXPECT_TRUE(fs::exists(dir_ / "out/hfmax.tif"));
  EXPECT_EQ(slurp(dir_ / "out/notes.txt"), "field notes");
}

// A resume that fails changes nothing in the folder: an End Time before the checkpoint, another
// precision. Before, the summary of the completed run was deleted first, and an End Time before the
// checkpoint reported "completed" with the checkpoint's maps.
TEST_F(OutputIntegrity, AFailedResumeChangesNothing) {
  talus::test::writeCliScene(dir_, "Checkpoint Interval=0.01\n");
  ASSERT_EQ(talus("run case.run").status, 0);
  const std::string summary = slurp(dir_ / "out/summary.json"), csv = slurp(dir_ / "out/diagnostics.csv");
  ASSERT_TRUE(contains(summary, "\"status\": \"completed\""));
  Outcome r = talus("run --resume out --set \"End Time=0.001\"");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "lies before the time of checkpoint")) << r;
  r = talus("run --resume out --set \"Precision=double\"");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_EQ(slurp(dir_ / "out/summary.json"), summary);
  EXPECT_EQ(slurp(dir_ / "out/diagnostics.csv"), csv);
}

// A run whose diagnostics.csv has other columns (started by another version of Talus: e.g. before
// friction_drag_work_J) is not resumed: its rows would not continue the header. The refusal names
// the file, and nothing in the folder changes.
TEST_F(OutputIntegrity, ResumingDiagnosticsOfOtherColumnsIsRefused) {
  talus::test::writeCliScene(dir_, "Checkpoint Interval=0.01\n");
  ASSERT_EQ(talus("run case.run").status, 0);
  std::string csv = slurp(dir_ / "out/diagnostics.csv");
  const std::string column = "friction_drag_work_J,";
  ASSERT_NE(csv.find(column), std::string::npos);
  csv.erase(csv.find(column), column.size());  // the header of the version before
  { std::ofstream(dir_ / "out/diagnostics.csv", std::ios::binary | std::ios::trunc) << csv; }
  const std::string summary = slurp(dir_ / "out/summary.json");
  const Outcome r = talus("run --resume out --set \"End Time=0.1\"");
  EXPECT_EQ(r.status, 2) << r;
  EXPECT_TRUE(contains(r.err, "diagnostics.csv")) << r;
  EXPECT_TRUE(contains(r.err, "other columns")) << r;
  EXPECT_EQ(slurp(dir_ / "out/summary.json"), summary);
  EXPECT_EQ(slurp(dir_ / "out/diagnostics.csv"), csv);
}

// The particle layer written at the start time holds the particles' state, not uninitialised device
// memory (before: thickness -1e6 .. 3e13 m, sqrt(J2) up to 1e48 Pa, different every run): two runs
// write the same layer, with thickness between 0 and the release's 2.5 m column (solids and
// confined water) and no stress (the particles start stress-free).
TEST_F(OutputIntegrity, TheParticleLayerAtTheStartTimeIsDefined) {
  talus::test::writeCliScene(dir_,
                             "[Solids]\nInclude Initial Solids=1\nInitial Solid Height=2\nInitial Cohesion=100\n"
                             "[Particles]\nUse Material Point Method=1\nYoung Modulus=1e7\n");
  ASSERT_EQ(talus("run case.run").status, 0);
  const talus::io::ParticleLayer first = talus::io::readParticleLayer((dir_ / "out/particles/particles_0000.gpkg").string());
  ASSERT_EQ(talus("run case.run --overwrite").status, 0);
  const talus::io::ParticleLayer second = talus::io::readParticleLayer((dir_ / "out/particles/particles_0000.gpkg").string());
  ASSERT_GT(first.size(), 0u);
  ASSERT_EQ(first.size(), second.size());
  const std::vector<double>* h1 = first.find("thickness");
  const std::vector<double>* h2 = second.find("thickness");
  const std::vector<double>* j2 = first.find("sqrtJ2");
  ASSERT_TRUE(h1 && h2 && j2);
  for (std::size_t q = 0; q < first.size(); ++q) {
    EXPECT_EQ((*h1)[q], (*h2)[q]) << q;
    EXPECT_GT((*h1)[q], 0.0) << q;
    EXPECT_LE((*h1)[q], 2.5 * 1.5) << q;  // the SPH thickness estimate smooths, never triples
    // The only stress at rest is the overburden's deviator, rho g H / 2 over 3 (P.41): < 1e5 Pa.
    EXPECT_TRUE(std::isfinite((*j2)[q])) << q;
    EXPECT_LT((*j2)[q], 1e5) << q;
  }
}
