// Particle seeding of the hybrid mode (src/particles/ParticleSeeding, spec §5, OpenLISEM Hazard
// P.88), checked against its definition: the count per cell, exact mass per cell, positions inside
// the seeding cell, the R2 sequence running on across cells, low discrepancy inside a cell, and
// clear errors for bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/Error.hpp"
#include "particles/ParticleSeeding.hpp"

using namespace talus;
using namespace talus::particles;

namespace {

/// Material in cells i = 2..5, j = 1..3 (the grid must be at least 6 x 4), thicker towards +x.
SeedInput block(const Grid& g, double h, double rho) {
  SeedInput in;
  in.mask.assign(g.cells(), 1);
  in.bed.assign(g.cells(), 0.0);
  in.thickness.assign(g.cells(), 0.0);
  in.density.assign(g.cells(), rho);
  for (int j = 1; j < 4; ++j)
    for (int i = 2; i < 6; ++i) in.thickness[g.index(i, j)] = h * (1.0 + 0.1 * i);
  return in;
}

}  // namespace

// Counts round(H dx^2 / V_I) (at least one), masses summing to rho H dx^2 per cell (relative 1e-14:
// n equal shares of a double, a few roundings), volumes to H dx^2, positions inside the cell.
TEST(ParticleSeeding, CountsMassesAndPositionsFollowTheDefinition) {
  const Grid g = Grid::make(8, 6, 2.0);
  SeedInput in = block(g, 1.0, 2400.0);
  in.thickness[g.index(0, 0)] = 1e-4;  // a thin deposit: one particle, not truncated
  in.mask[g.index(7, 5)] = 0;
  in.thickness[g.index(7, 5)] = 5.0;  // outside the domain: never seeded
  const SeedSpacing spacing{0.5, 0};
  const SeededParticles p = seedParticles(g, in, spacing);
  EXPECT_DOUBLE_EQ(p.particleVolume, 0.5);
  std::map<uint32_t, int> count;
  std::map<uint32_t, double> mass, volume;
  for (std::size_t q = 0; q < p.size(); ++q) {
    const uint32_t c = p.cell[q];
    ++count[c];
    mass[c] += p.mass[q];
    volume[c] += p.volume[q];
    const int i = static_cast<int>(c % g.nx), j = static_cast<int>(c / g.nx);
    EXPECT_GE(p.x[q], i * g.dx);
    EXPECT_LT(p.x[q], (i + 1) * g.dx);
    EXPECT_GE(p.y[q], j * g.dx);
    EXPECT_LT(p.y[q], (j + 1) * g.dx);
  }
  for (std::size_t k = 0; k < g.cells(); ++k) {
    const double h = in.mask[k] ? in.thickness[k] : 0.0;
    const int want = h > 0 ? std::max(1, static_cast<int>(std::round(h * 4.0 / 0.5))) : 0;
    EXPECT_EQ(count[static_cast<uint32_t>(k)], want) << "cell " << k;
    if (want == 0) continue;
    EXPECT_NEAR(mass[static_cast<uint32_t>(k)], 2400.0 * h * 4.0, 1e-14 * 2400.0 * h * 4.0 * want);
    EXPECT_NEAR(volume[static_cast<uint32_t>(k)], h * 4.0, 1e-14 * h * 4.0 * want);
  }
}

// perCell: the thickest cell gets exactly that many particles.
TEST(ParticleSeeding, ParticlesPerCellSetsTheVolumeFromTheThickestCell) {
  const Grid g = Grid::make(8, 6, 1.0);
  const SeedInput in = block(g, 2.0, 2000.0);
  const SeededParticles p = seedParticles(g, in, SeedSpacing{0, 9});
  const double hMax = 2.0 * 1.5;  // i = 5
  EXPECT_DOUBLE_EQ(p.particleVolume, hMax / 9.0);
  int thickest = 0;
  for (uint32_t c : p.cell) thickest += c == g.index(5, 2);
  EXPECT_EQ(thickest, 9);
}

// The R2 sequence runs on across cells: cell-relative positions of consecutive cells differ (the
// offset continues), and inside one cell of 256 particles each of 4 x 4 sub-squares holds 16 +- 4
// points (R2's discrepancy is O(log N / N); independent uniform points would have a standard
// deviation of 3.9 per sub-square and break +-4 in about 30 % of the squares).
TEST(ParticleSeeding, R2PointsContinueAcrossCellsAndCoverTheCell) {
  const Grid g = Grid::make(3, 1, 1.0);
  SeedInput in;
  in.mask.assign(3, 1);
  in.bed.assign(3, 0.0);
  in.thickness = {256.0, 256.0, 0.0};
  in.density.assign(3, 1000.0);
  const SeededParticles p = seedParticles(g, in, SeedSpacing{1.0, 0});
  ASSERT_EQ(p.size(), 512u);
  int same = 0;
  for (int q = 0; q < 256; ++q) same += std::fabs(p.x[q] - (p.x[256 + q] - 1.0)) < 1e-12 && std::fabs(p.y[q] - p.y[256 + q]) < 1e-12;
  EXPECT_EQ(same, 0);
  int bins[4][4] = {};
  for (int q = 0; q < 256; ++q) ++bins[static_cast<int>(p.x[q] * 4)][static_cast<int>(p.y[q] * 4)];
  for (auto& row : bins)
    for (int b : row) EXPECT_NEAR(b, 16, 4);
  // The sequence itself: point n is (frac(s + n / p), frac(s + n / p^2)).
  double u, v;
  r2Point(1000, 0.5, u, v);
  EXPECT_NEAR(u, std::fmod(0.5 + 1000 / kPlasticNumber, 1.0), 1e-12);
  EXPECT_NEAR(v, std::fmod(0.5 + 1000 / (kPlasticNumber * kPlasticNumber), 1.0), 1e-12);
}

TEST(ParticleSeeding, BadInputGivesAClearError) {
  const Grid g = Grid::make(8, 6, 1.0);
  SeedInput in = block(g, 1.0, 2000.0);
  in.thickness[g.index(2, 3)] = -1.0;
  try {
    seedParticles(g, in, SeedSpacing{0.1, 0});
    FAIL() << "negative thickness accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cell 2, 3"), std::string::npos) << e.what();
  }
  in = block(g, 1.0, 2000.0);
  in.density[g.index(3, 2)] = 0.0;
  EXPECT_THROW(seedParticles(g, in, SeedSpacing{0.1, 0}), InputError);
  in = block(g, 1.0, 2000.0);
  EXPECT_THROW(seedParticles(g, in, SeedSpacing{1e-12, 0}), InputError);  // far too many particles
  EXPECT_THROW(seedParticles(g, in, SeedSpacing{0, 0.5}), InputError);
  in.thickness.pop_back();
  EXPECT_THROW(seedParticles(g, in, SeedSpacing{0.1, 0}), InputError);
}
