// Ensemble descriptions, member sampling, the JSON reader and the percentile rule
// (src/ensemble/EnsembleFile, Sampling, Json, EnsembleMerge::percentile): host-only, no device.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "core/Error.hpp"
#include "ensemble/EnsembleFile.hpp"
#include "ensemble/EnsembleMerge.hpp"
#include "ensemble/Json.hpp"
#include "ensemble/Sampling.hpp"
#include "support/ExpectInputError.hpp"

namespace fs = std::filesystem;
using namespace talus::ensemble;

namespace {

/// A folder holding an empty base.run, so that Run File checks pass.
fs::path baseFolder() {
  const fs::path d = fs::temp_directory_path() / ("talus_ensfile_" + std::to_string(::getpid()));
  fs::create_directories(d);
  std::ofstream(d / "base.run") << "[Talus run file]\n";
  return d;
}

/// Removes the folder once all tests of the program have run.
class RemoveBaseFolder : public ::testing::Environment {
 public:
  void TearDown() override { fs::remove_all(baseFolder()); }
};
const ::testing::Environment* const kCleanUp = ::testing::AddGlobalTestEnvironment(new RemoveBaseFolder);

EnsembleSpec parse(const std::string& body) {
  return parseEnsembleText("[Ensemble]\nRun File=base.run\n" + body, baseFolder().string(), "test.ens");
}

}  // namespace

TEST(EnsembleFile, ParsesEveryKey) {
  const EnsembleSpec s = parse(
      "Members = 12\nSeed=5\nOutput Directory=out\n[Parameters]\nManning=uniform 0.02 0.08\n"
      "Initial Fluid Height=scale lognormal 0 0.2\nCFL=list 0.4 0.5\nFriction Angle=grid 20 30 3\n"
      "[Maps]\nThickness Thresholds=0.05 0.5\nSpeed Thresholds=2\nArrival Times=10 60\nPercentiles=5 95\n"
      "Affected Threshold=0.2\n[Calibration]\nObserved Runout=10 20\n");
  EXPECT_EQ(s.members, 12);
  EXPECT_EQ(s.seed, 5u);
  EXPECT_EQ(s.outputDir, (baseFolder() / "out").string());
  ASSERT_EQ(s.parameters.size(), 4u);
  EXPECT_EQ(s.parameters[1].mode, ApplyMode::Scale);
  EXPECT_EQ(s.parameters[1].distribution, Distribution::LogNormal);
  EXPECT_EQ(s.parameters[3].values, (std::vector<double>{20, 25, 30}));
  EXPECT_EQ(s.designSize(), 6);
  EXPECT_EQ(s.thicknessThresholds, (std::vector<double>{0.05, 0.5}));
  EXPECT_EQ(s.arrivalTimes, (std::vector<double>{10, 60}));
  EXPECT_EQ(s.rankBy, "runout");  // only a runout point is observed
  EXPECT_TRUE(s.hasObservedRunout);
}

TEST(EnsembleFile, DesignAloneSetsTheMembers) {
  EXPECT_EQ(parse("[Parameters]\nCFL=list 0.4 0.5\nManning=grid 0.01 0.05 5\n").members, 10);
}

TEST(EnsembleFile, ErrorsNameFileLineAndKey) {
  using talus::test::expectInputError;
  expectInputError([] { parse("Members=4\n[Parameters]\nManning=triangular 0 1\n"); },
                   {"test.ens:5", "key 'Manning'", "unknown distribution 'triangular'"});
  expectInputError([] { parse("Members=4\n[Parameters]\nManning=uniform 0.08 0.02\n"); },
                   {"test.ens:5", "lower < upper"});
  expectInputError([] { parse("Members=x\n[Parameters]\nManning=uniform 0 1\n"); }, {"test.ens:3", "key 'Members'", "'x'"});
  expectInputError([] { parse("Members=3\n[Parameters]\nCFL=list 0.4 0.5\n"); },
                   {"test.ens:3", "not a multiple of the 2 combinations"});
  expectInputError([] { parse("[Parameters]\nManning=uniform 0 1\n"); }, {"key 'Members'", "required"});
  expectInputError([] { parse("Members=2\nColour=red\n[Parameters]\nManning=uniform 0 1\n"); },
                   {"test.ens:4", "key 'Colour'", "unknown key"});
  expectInputError([] { parse("Members=2\n[Parameters]\nManning=normal 0.05 0\n"); }, {"standard deviation > 0"});
  expectInputError([] { parse("Members=2\n[Parameters]\nManning=uniform 0 1\n[Calibration]\nRank By=jaccard\n"); },
                   {"test.ens:7", "Rank By", "needs an Observed Map"});
  expectInputError([] { parseEnsembleText("[Ensemble]\nMembers=1\n[Parameters]\nManning=uniform 0 1\n", "/", "x.ens"); },
                   {"x.ens", "Run File", "required"});
  // Every problem is listed, not only the first.
  const std::string all = expectInputError(
      [] { parse("Members=0\n[Parameters]\nManning=uniform 1\nCFL=grid 0 1 2.5\n"); }, {"problem(s)"});
  EXPECT_NE(all.find("test.ens:5"), std::string::npos) << all;
  EXPECT_NE(all.find("test.ens:6"), std::string::npos) << all;
}

TEST(EnsembleSampling, ReproducibleAndIndependentOfMemberCount) {
  const EnsembleSpec a = parse("Members=10\nSeed=3\n[Parameters]\nManning=uniform 0 1\nCFL=normal 0 1\n");
  const EnsembleSpec b = parse("Members=500\nSeed=3\n[Parameters]\nManning=uniform 0 1\nCFL=normal 0 1\n");
  const EnsembleSpec c = parse("Members=10\nSeed=4\n[Parameters]\nManning=uniform 0 1\nCFL=normal 0 1\n");
  for (long long m = 0; m < 10; ++m) {
    EXPECT_EQ(memberValues(a, m), memberValues(b, m)) << "member " << m;  // bitwise
    EXPECT_NE(memberValues(a, m)[0], memberValues(c, m)[0]) << "another seed, another draw";
    EXPECT_NE(memberValues(a, m)[0], memberValues(a, m + 1)[0]);
  }
  // The two parameters of one member are different draws.
  EXPECT_NE(uniform01(3, 0, 0, 0), uniform01(3, 0, 1, 0));
}

TEST(EnsembleSampling, MomentsOfTheDistributions) {
  // n draws: the sample mean has standard error sigma / sqrt(n); 5 standard errors are exceeded
  // with probability 6e-7, so these bounds fail only for a wrong sampler. The sample variance's
  // standard error is about sigma^2 sqrt(2 / n) for the normal (sqrt((mu4 - sigma^4) / n) in general).
  const int n = 40000;
  const EnsembleSpec s = parse("Members=" + std::to_string(n) +
                               "\n[Parameters]\nManning=uniform 2 5\nCFL=normal 1.5 0.5\nCohesion=lognormal 0.3 0.4\n");
  double sum[3] = {0, 0, 0}, sq[3] = {0, 0, 0};
  double minU = 1e9, maxU = -1e9;
  for (long long m = 0; m < n; ++m) {
    const std::vector<double> v = memberValues(s, m);
    const double x[3] = {v[0], v[1], std::log(v[2])};
    for (int k = 0; k < 3; ++k) {
      sum[k] += x[k];
      sq[k] += x[k] * x[k];
    }
    minU = std::min(minU, v[0]);
    maxU = std::max(maxU, v[0]);
  }
  auto mean = [&](int k) { return sum[k] / n; };
  auto var = [&](int k) { return sq[k] / n - mean(k) * mean(k); };
  // Uniform on [2, 5): mean 3.5, variance 9/12 = 0.75; SE(mean) = sqrt(0.75 / n) = 0.0043;
  // SE(var) = sqrt((81/80 - 0.5625) / n) = 0.0034.
  EXPECT_NEAR(mean(0), 3.5, 5 * 0.0043);
  EXPECT_NEAR(var(0), 0.75, 5 * 0.0034);
  EXPECT_GE(minU, 2.0);
  EXPECT_LT(maxU, 5.0);
  // Normal(1.5, 0.5): SE(mean) = 0.5 / 200 = 0.0025, SE(var) = 0.25 sqrt(2 / n) = 0.0018.
  EXPECT_NEAR(mean(1), 1.5, 5 * 0.0025);
  EXPECT_NEAR(var(1), 0.25, 5 * 0.0018);
  // Lognormal: ln X ~ Normal(0.3, 0.4): SE(mean) = 0.002, SE(var) = 0.16 sqrt(2 / n) = 0.0011.
  EXPECT_NEAR(mean(2), 0.3, 5 * 0.002);
  EXPECT_NEAR(var(2), 0.16, 5 * 0.0011);
}

TEST(EnsembleSampling, DesignRunsThroughEveryCombination) {
  const EnsembleSpec s = parse("Members=12\n[Parameters]\nCFL=list 0.4 0.5\nManning=uniform 0 1\nFriction Angle=grid 20 30 3\n");
  std::set<std::pair<double, double>> seen;
  for (long long m = 0; m < 6; ++m) {
    const std::vector<double> v = memberValues(s, m);
    seen.insert({v[0], v[2]});
    // The second cycle repeats the design with fresh random draws.
    const std::vector<double> w = memberValues(s, m + 6);
    EXPECT_EQ(v[0], w[0]);
    EXPECT_EQ(v[2], w[2]);
    EXPECT_NE(v[1], w[1]);
  }
  EXPECT_EQ(seen.size(), 6u);
  // The first design parameter varies fastest.
  EXPECT_EQ(memberValues(s, 0)[0], 0.4);
  EXPECT_EQ(memberValues(s, 1)[0], 0.5);
  EXPECT_EQ(memberValues(s, 1)[2], 20.0);
  EXPECT_EQ(memberValues(s, 2)[2], 25.0);
}

TEST(EnsemblePercentile, LinearInterpolationOfOrderStatistics) {
  // Hyndman-Fan type 7 by hand: for {1, 2, 4, 8}, h = 3q/100: q = 50 -> h = 1.5 -> 2 + 0.5 * 2 = 3;
  // q = 10 -> h = 0.3 -> 1 + 0.3 = 1.3; q = 0 and 100 are the extremes.
  const std::vector<float> x{1, 2, 4, 8};
  EXPECT_DOUBLE_EQ(percentile(x, 50), 3.0);
  EXPECT_DOUBLE_EQ(percentile(x, 10), 1.3);
  EXPECT_DOUBLE_EQ(percentile(x, 0), 1.0);
  EXPECT_DOUBLE_EQ(percentile(x, 100), 8.0);
  EXPECT_DOUBLE_EQ(percentile({7}, 90), 7.0);
}

TEST(EnsembleJson, ReadsWhatTalusWritesAndRefusesBrokenText) {
  const JsonValue v = JsonValue::parse(
      "{\"status\": \"completed\", \"volume\": {\"initial_m3\": 1.5e2, \"final_m3\": -0.25},"
      " \"list\": [true, false, null, \"a\\\"b\\u00e9\"], \"n\": 0}",
      "x.json");
  EXPECT_EQ(v.find("status")->string(), "completed");
  EXPECT_DOUBLE_EQ(v.at({"volume", "initial_m3"})->number(), 150.0);
  EXPECT_DOUBLE_EQ(v.at({"volume", "final_m3"})->number(), -0.25);
  ASSERT_EQ(v.find("list")->array().size(), 4u);
  EXPECT_EQ(v.find("list")->array()[3].string(), "a\"b\xc3\xa9");
  EXPECT_EQ(v.at({"volume", "missing"}), nullptr);
  const std::string quoted = jsonQuote("tab\there \"q\"");
  EXPECT_EQ(JsonValue::parse(quoted, "q").string(), "tab\there \"q\"");
  using talus::test::expectInputError;
  expectInputError([] { JsonValue::parse("{\"a\": 1,}", "s.json"); }, {"s.json", "byte 8"});
  expectInputError([] { JsonValue::parse("{\"a\": 01}", "s.json"); }, {"s.json"});
  expectInputError([] { JsonValue::parse(std::string(100, '['), "s.json"); }, {"deeper than 64"});
  expectInputError([] { JsonValue::parse("", "s.json"); }, {"unexpected end"});
}
