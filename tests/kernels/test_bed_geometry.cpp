// The bed's slope fields recomputed on the device (kernels/flow/bed_geometry.cl, after entrainment
// changed the bed) against the host computation they replace (flow/SlopeGravity.cpp, which every
// run uses at setInput): g_n, g_p, the slope speed and the limited bed slope, on a
// rough random DEM with nodata holes and a nodata column, for the slope correction on (cos^4 depth
// pressure, so g_p differs from g_n) and off. In double the two evaluate the same expressions in the
// same order (hypot and sqrt correctly rounded or within an ulp on PoCL): we allow 1e-13 relative to
// the field's scale. In float the device rounds each operation (~10 per field) to 6e-8: 2e-6. A wrong
// stencil, sign or missing cos^2 changes a field by O(1) of its scale.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "flow/FlowSolver.hpp"
#include "flow/SlopeGravity.hpp"
#include "support/DebrisScene.hpp"
#include "support/TestDevice.hpp"

namespace {

using namespace talus;
using compute::Precision;

/// max |a - b| / max(|b|) over the mask (and a size check).
double relativeDiff(const std::vector<double>& a, const std::vector<double>& b, const std::vector<uint8_t>& mask,
                    std::size_t components) {
  EXPECT_EQ(a.size(), b.size());
  double scale = 0, worst = 0;
  const std::size_t n = mask.size();
  for (std::size_t c = 0; c < components; ++c)
    for (std::size_t k = 0; k < n; ++k)
      if (mask[k]) scale = std::max(scale, std::fabs(b[c * n + k]));
  for (std::size_t c = 0; c < components; ++c)
    for (std::size_t k = 0; k < n; ++k)
      if (mask[k]) worst = std::max(worst, std::fabs(a[c * n + k] - b[c * n + k]));
  return scale > 0 ? worst / scale : worst;
}

class BedGeometryTest : public ::testing::TestWithParam<Precision> {};

TEST_P(BedGeometryTest, DeviceMatchesHost) {
  const bool dbl = GetParam() == Precision::Double;
  const double tol = dbl ? 1e-13 : 2e-6;
  const Grid grid = Grid::make(37, 29, 2.5);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  flow::FlowInput in = test::debrisInput(grid);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const std::size_t k = grid.index(i, j);
      // A valley with 2 m roughness: slopes up to ~60 degrees between neighbours.
      in.bed[k] = 0.02 * (i - 18) * (i - 18) + 0.5 * j + 2.0 * uni(rng);
      if (i == 11 || (i > 25 && j > 20 && uni(rng) > 0.3)) in.mask[k] = 0;
      if (!dbl) in.bed[k] = static_cast<float>(in.bed[k]);
    }
  for (int variant = 0; variant < 2; ++variant) {  // each builds the solver's programs anew (~6 s on PoCL)
    flow::FlowSettings s;
    s.twoPhase = true;
    s.entrainment.enabled = true;
    s.slopeCorrection = variant == 0;
    s.depthPressure = flow::DepthPressure::Cos4;  // g_p differs from g_n
    SCOPED_TRACE("variant " + std::to_string(variant));
    std::vector<double> bed = in.bed;
    for (std::size_t k = 0; k < bed.size(); ++k)
      if (!in.mask[k]) bed[k] = 0.0;  // as setInput stores it
    const flow::SlopeGravity host = flow::computeSlopeGravity(grid, bed, in.mask, s);
    flow::FlowSolver solver(test::testContext(GetParam()), grid, s);
    solver.setInput(in);
    solver.recomputeBedGeometry();
    std::vector<double> slope = host.slopeX;
    slope.insert(slope.end(), host.slopeY.begin(), host.slopeY.end());
    EXPECT_LE(relativeDiff(solver.gn(), host.gn, in.mask, 1), tol);
    EXPECT_LE(relativeDiff(solver.gp(), host.gp, in.mask, 1), tol);
    EXPECT_LE(relativeDiff(solver.slopeSpeed(), host.slopeSpeed, in.mask, 1), tol);
    EXPECT_LE(relativeDiff(solver.bedSlope(), slope, in.mask, 2), tol);
    // The host's fields are not trivially zero here.
    EXPECT_GT(*std::max_element(host.slopeSpeed.begin(), host.slopeSpeed.end()), 5.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Precisions, BedGeometryTest, ::testing::Values(Precision::Double, Precision::Float),
                         [](const ::testing::TestParamInfo<Precision>& i) {
                           return std::string(i.param == Precision::Double ? "Double" : "Float");
                         });

}  // namespace
