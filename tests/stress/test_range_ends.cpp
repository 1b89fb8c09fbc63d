// Every number a run-file may legally hold, at both ends of its declared range, on a plain scene:
// the run either refuses the value with a clear message (a rule between keys: InputError) or runs
// its first steps without the health check stopping it (issue 14: Initial Solid IFA = 1.4, Earth
// Pressure Coefficient = 100 and Viscous Reynolds Number = 1 stopped at step 1 as "runaway
// velocity" or "CFL violation", the check judging a wave speed against a flow-speed bound and a
// viscous rate against the CFL condition).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "core/Error.hpp"
#include "io/KeyRegistry.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"
#include "support/CliRun.hpp"

namespace fs = std::filesystem;

namespace {

// Keys that define the scene itself rather than a parameter of the model: a uniform DEM or
// initial thickness at a range end is another scene, not a parameter's limit.
bool definesTheScene(const std::string& name) {
  return name == "DEM" || name == "Initial Fluid Height" || name == "Initial Solid Height";
}

struct SweepCount {
  int tried = 0, refused = 0, ran = 0;
  std::string failures;
};

/// Sets each numeric key accepted by `select` to both ends of its range on the scene of `runFile`
/// (with End Time `endTime` minutes unless the key is End Time) and runs `steps` steps.
template <class Select>
SweepCount sweepRangeEnds(const std::string& runFile, const std::string& endTime, const fs::path& out, int steps,
                          Select select) {
  const talus::io::KeyRegistry& keys = talus::talusRunKeys();
  SweepCount c;
  std::ostringstream failures;
  for (const talus::io::KeySpec& k : keys.keys()) {
    const bool numeric = k.type == talus::io::KeyType::Real || k.type == talus::io::KeyType::Integer ||
                         k.type == talus::io::KeyType::Map;
    if (!numeric || definesTheScene(k.name) || !select(k)) continue;
    for (double end : {k.min, k.max}) {
      if (!std::isfinite(end)) continue;
      const std::string assignment = k.name + "=" + talus::io::formatNumber(end);
      ++c.tried;
      const auto start = std::chrono::steady_clock::now();
      try {
        talus::io::RunConfig cfg = talus::io::RunConfig::load(runFile, keys);
        cfg.set("End Time=" + endTime);
        cfg.set(assignment);
        const talus::sim::Scene scene = talus::sim::loadScene(cfg);
        talus::sim::Simulation sim(scene, cfg, out.string(), talus::sim::OutputMode::Overwrite);
        sim.begin();
        for (int s = 0; s < steps && !sim.atEnd(); ++s) sim.stepOnce();
        sim.finish();
        ++c.ran;
      } catch (const talus::InputError&) {
        ++c.refused;  // a clear refusal (a rule between keys, a derived quantity out of range)
      } catch (const std::exception& e) {
        failures << assignment << ": " << e.what() << "\n";
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (seconds > 5) {
        std::printf("  %s took %.1f s\n", assignment.c_str(), seconds);
        std::fflush(stdout);
      }
    }
  }
  c.failures = failures.str();
  return c;
}

class RangeEnds : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("talus_range_ends_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

}  // namespace

TEST_F(RangeEnds, NoLegalValueStopsAPlainTwoPhaseRunInItsFirstSteps) {
  // Solids (1 m everywhere) under a block of 0.5 m of water on a gentle slope.
  const std::string runFile =
      talus::test::writeCliScene(dir_, "[Solids]\nInclude Initial Solids=1\nInitial Solid Height=1\n");
  const SweepCount c = sweepRangeEnds(runFile, "0.05", dir_ / "out", 5, [](const talus::io::KeySpec&) { return true; });
  std::printf("range ends (two-phase grid): %d tried, %d ran, %d refused with a message\n", c.tried, c.ran, c.refused);
  EXPECT_EQ(c.failures, "");
  EXPECT_GT(c.ran, c.tried / 2);  // a scene that every value refuses would test nothing
}

// The particles' keys on a hybrid scene (MPM particles seeded from 1 m of cohesive solids), over
// 6 ms: legal ends such as 400 particles per cell (5000 neighbours each within the smoothing
// length of one cell) or a sound speed of 1e6 m/s (sub-steps of 0.4 us) are slow by nature (the
// run shows their cost before it starts, sim::Simulation::particleCost), not unstable.
TEST_F(RangeEnds, NoLegalParticleValueStopsAPlainHybridRunInItsFirstSteps) {
  const std::string runFile = talus::test::writeCliScene(
      dir_, "[Solids]\nInclude Initial Solids=1\nInitial Solid Height=1\nInitial Cohesion=100\n"
            "[Particles]\nUse Material Point Method=1\nYoung Modulus=1e7\n");
  const SweepCount c =
      sweepRangeEnds(runFile, "0.0001", dir_ / "out", 2, [](const talus::io::KeySpec& k) { return k.section == "Particles"; });
  std::printf("range ends (particles): %d tried, %d ran, %d refused with a message\n", c.tried, c.ran, c.refused);
  EXPECT_EQ(c.failures, "");
  EXPECT_GT(c.ran, c.tried / 2);
}
