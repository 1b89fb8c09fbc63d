#include "flow/DebrisParams.hpp"

namespace talus::flow {
namespace {

template <class Real>
void fill(compute::RawBuffer& buf, const DebrisSettings& d) {
  DebrisParamsT<Real> p{};
  p.earthPressure = static_cast<int32_t>(d.earthPressure);
  p.dragLaw = static_cast<int32_t>(d.drag);
  p.virtualMass = d.virtualMass ? 1 : 0;
  p.deltaFromPhi = d.deltaFromPhi ? 1 : 0;
  p.kConst = static_cast<Real>(d.kConst);
  p.rhoF = static_cast<Real>(d.fluidDensity);
  p.poreB = static_cast<Real>(d.poreB);
  p.dragMult = static_cast<Real>(d.dragMultiplier);
  p.dragM = static_cast<Real>(d.dragPExponent);
  p.dragBigM = static_cast<Real>(d.dragM);
  p.dragKappa = static_cast<Real>(d.dragKappa);
  p.viscA = static_cast<Real>(d.viscA);
  p.viscB = static_cast<Real>(d.viscB);
  p.phiDefault = static_cast<Real>(kDebrisDefaultPhi);
  p.rhoSDefault = static_cast<Real>(kDebrisDefaultRhoS);
  p.dDefault = static_cast<Real>(kDebrisDefaultGrain);
  p.filmH = static_cast<Real>(d.filmThickness);
  p.invNR = static_cast<Real>(d.reynolds > 0 ? 1.0 / d.reynolds : 0.0);
  p.invNRA = static_cast<Real>(d.reynoldsInterfacial > 0 ? 1.0 / d.reynoldsInterfacial : 0.0);
  p.chi = static_cast<Real>(d.chi);
  p.xi = static_cast<Real>(d.xi);
  p.packing = static_cast<Real>(d.packing);
  p.rheology = static_cast<int32_t>(d.rheology);
  for (int c = 0; c < 4; ++c) p.rheo[c] = static_cast<Real>(d.rheologyParams[c]);
  buf.writeBytes(&p, sizeof p);
}

}  // namespace

void writeDebrisParams(compute::RawBuffer& buf, const DebrisSettings& d, compute::Precision precision) {
  if (precision == compute::Precision::Double)
    fill<double>(buf, d);
  else
    fill<float>(buf, d);
}

}  // namespace talus::flow
