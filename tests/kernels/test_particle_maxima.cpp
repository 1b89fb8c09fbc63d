// The particle phase's peak maps (kernels/particles/particle_maxima.cl, particle_track_maxima) against
// a host reference written here: over several P2G states of random cells, each cell keeps the largest
// thickness H_c and the largest speed |P_c| / M_c among the states where it holds mass (M_c > 0), and
// keeps what it had where it holds none. The maxima are exact (fmax of the same values; the speed
// is one sqrt and one division, so the tolerance is 1e-15 relative in double, 1e-6 in float).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "compute/Buffer.hpp"
#include "compute/Context.hpp"
#include "compute/Kernel.hpp"
#include "support/TestDevice.hpp"

using talus::compute::Precision;

class ParticleMaxima : public ::testing::TestWithParam<Precision> {};

TEST_P(ParticleMaxima, EachCellKeepsItsLargestThicknessAndMeanSpeed) {
  talus::compute::Context& ctx = talus::test::testContext(GetParam());
  const double tol = GetParam() == Precision::Double ? 1e-15 : 1e-6;
  const int cells = 1000;
  std::mt19937 rng(20261205u);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto buffer = [&](const char* label) { return talus::compute::RealBuffer(ctx, cells, label); };
  talus::compute::RealBuffer H = buffer("H"), M = buffer("M"), Px = buffer("Px"), Py = buffer("Py");
  talus::compute::RealBuffer hmax = buffer("hmax"), vmax = buffer("vmax");
  hmax.fill(0.0);
  vmax.fill(0.0);
  std::vector<double> hostH(cells, 0.0), hostV(cells, 0.0);
  talus::compute::Kernel k(ctx.program("particles/particle_maxima.cl"), "particle_track_maxima");
  for (int state = 0; state < 5; ++state) {
    std::vector<double> h(cells), m(cells), px(cells), py(cells);
    for (int c = 0; c < cells; ++c) {
      const bool empty = u(rng) < 0.3;  // cells no particle reaches
      m[c] = empty ? 0.0 : 1e3 * u(rng);
      h[c] = empty ? 0.0 : 5 * u(rng);
      px[c] = empty ? 0.0 : m[c] * (60 * u(rng) - 30);
      py[c] = empty ? 0.0 : m[c] * (60 * u(rng) - 30);
      hostH[c] = std::max(hostH[c], h[c]);
      if (m[c] > 0) hostV[c] = std::max(hostV[c], std::hypot(px[c], py[c]) / m[c]);
    }
    H.upload(h), M.upload(m), Px.upload(px), Py.upload(py);
    k.bind(cells, H, M, Px, Py, hmax, vmax);
    k.launch(talus::compute::Range{static_cast<std::size_t>(cells)});
  }
  const std::vector<double> dh = hmax.download(), dv = vmax.download();
  for (int c = 0; c < cells; ++c) {
    // (float: the inputs themselves round to float first)
    EXPECT_NEAR(dh[c], hostH[c], tol * std::max(1.0, hostH[c])) << c;
    EXPECT_NEAR(dv[c], hostV[c], tol * std::max(1.0, hostV[c]) * 4) << c;
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, ParticleMaxima, ::testing::Values(Precision::Double, Precision::Float));
