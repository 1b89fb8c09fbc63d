// Ensemble members run in this process (src/ensemble/EnsembleRun, EnsembleMerge, EnsembleCalibrate)
// on scenes whose answer is known: a lake at rest whose height is the parameter (so every merged
// probability and percentile follows from the parameter values alone), a wedge of water whose
// affected area and runout are known per member (calibration), and a restart after members were
// left incomplete.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "core/Error.hpp"
#include "ensemble/EnsembleCalibrate.hpp"
#include "ensemble/EnsembleFile.hpp"
#include "ensemble/EnsembleMerge.hpp"
#include "ensemble/EnsembleRun.hpp"
#include "ensemble/Sampling.hpp"
#include "io/RasterIO.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "support/CliRun.hpp"
#include "support/EnsembleScenes.hpp"
#include "support/ExpectInputError.hpp"

namespace fs = std::filesystem;
using namespace talus::ensemble;
using talus::Raster;

namespace {

class EnsembleRunTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("talus_ensrun_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Loads the ensemble and its base run-file, runs every member quietly and merges.
  RunOutcome runAll(const std::string& ensFile, bool merge = true) {
    spec_ = loadEnsembleFile(ensFile);
    base_ = std::make_unique<talus::io::RunConfig>(talus::io::RunConfig::load(spec_.runFile, talus::talusRunKeys()));
    std::vector<long long> all;
    for (long long m = 0; m < spec_.members; ++m) all.push_back(m);
    RunOptions opt;
    opt.quiet = true;
    const RunOutcome o = runMembers(spec_, *base_, all, opt);
    if (merge) mergeEnsemble(spec_, *base_);
    return o;
  }
  Raster merged(const std::string& name) const { return talus::io::readRaster(spec_.outputDir + "/merged/" + name + ".tif"); }

  /// Every value of a map's domain cells equals `expected` within `tol`; the maps are Float32, so
  /// `expected` is first rounded to float (tol 0: exactly that float).
  void expectUniform(const std::string& name, double expected, double tol) const {
    expected = static_cast<float>(expected);
    const Raster r = merged(name);
    for (std::size_t k = 0; k < r.values.size(); ++k) {
      ASSERT_TRUE(r.valid[k]) << name << " cell " << k;
      ASSERT_NEAR(r.values[k], expected, tol) << name << " cell " << k;
    }
  }

  fs::path dir_;
  EnsembleSpec spec_;
  std::unique_ptr<talus::io::RunConfig> base_;
};

}  // namespace

TEST_F(EnsembleRunTest, LakeProbabilitiesAndPercentilesAreKnownExactly) {
  // Two cycles of a four-value design: h0 in {0.05, 0.15, 0.25, 0.35} twice. A lake at rest keeps
  // its height (to float round-off, 1e-7 m), far from every threshold, so:
  //   P(hmax > 0.1) = 6/8, P(hmax > 0.3) = 2/8, P(vmax > 0.5) = 0, P(arrival <= 1 s) = 1
  //   (every h0 exceeds the 0.01 m Arrival Threshold at t = 0);
  //   type-7 percentiles of (0.05, 0.05, 0.15, 0.15, 0.25, 0.25, 0.35, 0.35): p0 = 0.05,
  //   p50 = 0.15 + 0.5 (0.25 - 0.15) = 0.2, p25 at h = 1.75: 0.05 + 0.75 (0.15 - 0.05) = 0.125, p100 = 0.35.
  const std::string ens = talus::test::writeLakeEnsemble(
      dir_, "Initial Fluid Height=list 0.05 0.15 0.25 0.35", 8,
      "[Maps]\nThickness Thresholds=0.1 0.3\nSpeed Thresholds=0.5\nArrival Times=1\nPercentiles=0 25 50 100\n");
  const RunOutcome o = runAll(ens);
  EXPECT_EQ(o.ran, 8);
  EXPECT_TRUE(o.failures.empty());
  const double exact = 0.0, hTol = 1e-6;  // probabilities are counts / 8: exact in float
  expectUniform("p_hmax_gt_0.1", 0.75, exact);
  expectUniform("p_hmax_gt_0.3", 0.25, exact);
  expectUniform("p_vmax_gt_0.5", 0.0, exact);
  expectUniform("p_arrival_le_1", 1.0, exact);
  expectUniform("hmax_p0", 0.05, hTol);
  expectUniform("hmax_p25", 0.125, hTol);
  expectUniform("hmax_p50", 0.2, hTol);
  expectUniform("hmax_p100", 0.35, hTol);
  // The merged maps carry the DEM's georeference.
  const Raster dem = talus::io::readRaster((dir_ / "dem.tif").string());
  EXPECT_TRUE(talus::sameGrid(dem.grid, merged("p_hmax_gt_0.1").grid));
  // The member table: area = the 120 m^2 domain where h0 > Affected Threshold (0.1 m), volume = 120 h0.
  std::istringstream csv(talus::test::slurp(spec_.outputDir + "/merged/members.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "member,name,Initial Fluid Height,status,area_m2,runout_m,runout_x,runout_y,volume_initial_m3,volume_final_m3");
  for (int m = 0; m < 8; ++m) {
    ASSERT_TRUE(std::getline(csv, line));
    const double h0 = 0.05 + 0.1 * (m % 4);
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    ASSERT_EQ(f.size(), 10u) << line;
    EXPECT_NEAR(std::stod(f[2]), h0, 1e-15) << line;
    EXPECT_EQ(f[3], "completed");
    EXPECT_EQ(std::stod(f[4]), h0 > 0.1 ? 120.0 : 0.0) << line;
    EXPECT_NEAR(std::stod(f[8]), 120 * h0, 1e-5) << line;  // float fields summed: 1e-7 relative
  }
}

TEST_F(EnsembleRunTest, RandomDrawsGiveTheFractionOfDrawsAboveTheThreshold) {
  // Independent reference: the fraction of the sampler's own draws above 0.2 m.
  const std::string ens = talus::test::writeLakeEnsemble(dir_, "Initial Fluid Height=uniform 0.02 0.4", 5,
                                                         "[Maps]\nThickness Thresholds=0.2\n");
  runAll(ens);
  int above = 0;
  for (long long m = 0; m < 5; ++m) above += memberValues(spec_, m)[0] > 0.2 ? 1 : 0;
  expectUniform("p_hmax_gt_0.2", above / 5.0, 0.0);
}

TEST_F(EnsembleRunTest, WedgeCalibrationRanksTheMemberThatMatches) {
  const std::string ens = talus::test::writeWedgeEnsemble(dir_);
  runAll(ens);
  // Member s affects columns i with (20 - i) s > 10.5: s = 1: i <= 9, 2: i <= 14, 3: i <= 16,
  // 4: i <= 17 (all 6 rows). Observed: i <= 16. By hand (cells = columns x 6):
  //   s = 1: TP 60, FN 42            J = 10/17, TPR = 10/17, FPR = 0
  //   s = 2: TP 90, FN 12            J = 15/17
  //   s = 3: TP 102                  J = 1, D2PC = 0, runout point = observed point
  //   s = 4: TP 102, FP 6, TN 12     J = 17/18, FPR = 1/3, D2PC = 1/3
  std::ifstream csv(spec_.outputDir + "/merged/calibration.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "rank,member,name,Initial Fluid Height,tp,fp,fn,tn,jaccard,tpr,fpr,d2pc,auroc,foc,runout_distance_m");
  std::map<int, std::vector<std::string>> byMember;
  std::vector<int> order;
  while (std::getline(csv, line)) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    order.push_back(std::stoi(f[1]));
    byMember[std::stoi(f[1])] = f;
  }
  EXPECT_EQ(order, (std::vector<int>{2, 3, 1, 0}));  // Jaccard 1 > 17/18 > 15/17 > 10/17
  const double j[4] = {10.0 / 17, 15.0 / 17, 1.0, 17.0 / 18};
  const long long tp[4] = {60, 90, 102, 102}, fp[4] = {0, 0, 0, 6}, fn[4] = {42, 12, 0, 0}, tn[4] = {18, 18, 18, 12};
  for (int m = 0; m < 4; ++m) {
    const auto& f = byMember[m];
    EXPECT_EQ(std::stoll(f[4]), tp[m]) << m;
    EXPECT_EQ(std::stoll(f[5]), fp[m]) << m;
    EXPECT_EQ(std::stoll(f[6]), fn[m]) << m;
    EXPECT_EQ(std::stoll(f[7]), tn[m]) << m;
    EXPECT_NEAR(std::stod(f[8]), j[m], 1e-9) << m;  // 10 significant digits written
  }
  EXPECT_NEAR(std::stod(byMember[3][11]), 1.0 / 3, 1e-9);      // D2PC of s = 4
  EXPECT_NEAR(std::stod(byMember[3][13]), 108.0 / 102, 1e-9);  // FoC of s = 4: over-predicts
  EXPECT_NEAR(std::stod(byMember[0][13]), 60.0 / 102, 1e-9);   // FoC of s = 1: under-predicts
  // Runout points: the highest release cell is column 0 (row 0); the farthest affected cell is
  // (i_max, 5), so the distance to the observed point (16, 5) is 2 m x (16 - i_max).
  EXPECT_NEAR(std::stod(byMember[2][14]), 0.0, 1e-9);
  EXPECT_NEAR(std::stod(byMember[0][14]), 14.0, 1e-9);
  EXPECT_NEAR(std::stod(byMember[3][14]), 2.0, 1e-9);
  // Agreement map of the best member (s = 3): 3 (both) on i <= 16, 0 (neither) beyond.
  const Raster a = merged("agreement");
  for (int jy = 0; jy < a.grid.ny; ++jy)
    for (int i = 0; i < a.grid.nx; ++i) ASSERT_EQ(a.at(i, jy), i <= 16 ? 3.0 : 0.0) << i << "," << jy;
  const std::string best = talus::test::slurp(spec_.outputDir + "/merged/calibration.json");
  EXPECT_NE(best.find("\"best_member\": 2"), std::string::npos) << best;
  EXPECT_NE(best.find("\"Initial Fluid Height\": 3"), std::string::npos) << best;
  // members.csv: runout of s = 3 is hypot(32, 10) m from cell (0, 0) to (16, 5).
  const std::string table = talus::test::slurp(spec_.outputDir + "/merged/members.csv");
  EXPECT_NE(table.find("," + std::to_string(std::hypot(32.0, 10.0)).substr(0, 8)), std::string::npos) << table;
}

TEST(EnsembleCalibrateMask, ConfusionCountsByHand) {
  // modelled 1100, observed 1010, domain 1111 + one outside cell: TP 1, FP 1, FN 1, TN 1.
  const std::vector<unsigned char> m{1, 1, 0, 0, 1}, o{1, 0, 1, 0, 1}, d{1, 1, 1, 1, 0};
  const MemberFit f = fitMask(m, o, d);
  EXPECT_EQ(f.tp, 1);
  EXPECT_EQ(f.fp, 1);
  EXPECT_EQ(f.fn, 1);
  EXPECT_EQ(f.tn, 1);
  EXPECT_DOUBLE_EQ(f.jaccard, 1.0 / 3);
  EXPECT_DOUBLE_EQ(f.tpr, 0.5);
  EXPECT_DOUBLE_EQ(f.fpr, 0.5);
  EXPECT_DOUBLE_EQ(f.d2pc, std::sqrt(0.5));
  EXPECT_DOUBLE_EQ(f.auroc, 0.5);
  EXPECT_DOUBLE_EQ(f.foc, 1.0);
  EXPECT_EQ(agreementMap(m, o, d), (std::vector<unsigned char>{3, 1, 2, 0, 255}));
}

TEST_F(EnsembleRunTest, RestartRerunsIncompleteMembersAndSkipsFinishedOnes) {
  const std::string ens = talus::test::writeLakeEnsemble(dir_, "Initial Fluid Height=list 0.05 0.15 0.25 0.35", 4,
                                                         "[Maps]\nPercentiles=50\n");
  runAll(ens);
  const fs::path members = fs::path(spec_.outputDir) / "members", mergedDir = fs::path(spec_.outputDir) / "merged";
  std::map<std::string, std::string> before;
  for (const auto& e : fs::directory_iterator(mergedDir)) before[e.path().filename().string()] = talus::test::slurp(e.path());
  // What a kill can leave: m0001 still in its partial folder (no process holds its lock), and a
  // stale partial folder beside the finished m0003. m0002 loses its record (not a state Talus
  // writes, but a folder without member.json must not count as finished either).
  fs::rename(members / "m0001", members / ".m0001.partial-deadhost-1");
  fs::create_directories(members / ".m0003.partial-deadhost-2");
  std::ofstream(members / ".m0003.partial-deadhost-2" / "hfmax.tif") << "cut short";
  fs::remove(members / "m0002" / "member.json");
  talus::test::expectInputError([&] { mergeEnsemble(spec_, *base_); }, {"2 of 4 members are not complete", "m0001, m0002"});

  const RunOutcome again = runAll(ens);
  EXPECT_EQ(again.ran, 2);
  EXPECT_EQ(again.skipped, 2);
  for (const auto& e : fs::directory_iterator(members))
    EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos) << e.path();
  for (const auto& [name, bytes] : before)
    EXPECT_TRUE(talus::test::slurp(mergedDir / name) == bytes) << name << " differs after the restart";

  // A changed ensemble file does not silently mix members of two designs.
  const std::string changed = talus::test::writeLakeEnsemble(dir_, "Initial Fluid Height=list 0.05 0.15 0.25 0.45", 4,
                                                             "", "lake.ens");
  talus::test::expectInputError([&] { runAll(changed); }, {"m0003", "the file changed since"});
}
