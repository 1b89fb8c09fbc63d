#include "flow/Rheology.hpp"

#include <cmath>

#include "core/Constants.hpp"
#include "core/Error.hpp"

namespace talus::flow {
namespace {

std::array<double, 4> noParams(const std::vector<double>&) { return {0, 0, 0, 0}; }
std::string noCheck(const std::vector<double>&) { return ""; }

/// Voellmy: {mu, g / xi}.
std::array<double, 4> voellmyParams(const std::vector<double>& v) { return {v[0], kGravity / v[1], 0, 0}; }

/// Pouliquen-Forterre: {tan z1, tan z2, beta, L}.
std::array<double, 4> muIParams(const std::vector<double>& v) {
  return {std::tan(v[0]), std::tan(v[1]), v[2], v[3]};
}
std::string muICheck(const std::vector<double>& v) {
  if (v[1] > v[0]) return "";
  return "Pouliquen Angle 2 (" + std::to_string(v[1]) + " rad) must exceed Pouliquen Angle 1 (" +
         std::to_string(v[0]) + " rad): h_stop = L (tan z2 - tan theta) / (tan theta - tan z1)";
}

/// Bingham: {tau_y, mu_B, 1}; Herschel-Bulkley: {tau_y, K, n}.
std::array<double, 4> binghamParams(const std::vector<double>& v) { return {v[0], v[1], 1, 0}; }
std::array<double, 4> hbParams(const std::vector<double>& v) { return {v[0], v[1], v[2], 0}; }

std::vector<RheologyLaw> buildLaws() {
  const RheologyKey yield{"Yield Stress", "1000", "Pa", 0, 1e7, "yield stress tau_y of a Bingham or Herschel-Bulkley solid phase"};
  return {
      {"coulomb", Rheology::Coulomb, "Coulomb friction tan(delta) sigma_n (Bed Friction Angle)", {}, noParams, noCheck},
      {"voellmy", Rheology::Voellmy, "Voellmy: mu sigma_n + rho g |U|^2 / xi (RAMMS, com1DFA)",
       {{"Voellmy Mu", "0.155", "-", 0, 5, "Coulomb coefficient mu of the Voellmy law (com1DFA's standard 0.155)"},
        {"Voellmy Xi", "4000", "m/s^2", 1, 1e7, "turbulence coefficient xi of the Voellmy law (com1DFA's standard 4000)"}},
       voellmyParams, noCheck},
      {"mu-i", Rheology::MuI, "Pouliquen & Forterre (2002) mu(H, Fr), depth-averaged mu(I)",
       {{"Pouliquen Angle 1", "0.36652", "rad", 0, 1.5, "zeta_1: friction angle where h_stop grows without bound (glass beads: 21 deg)"},
        {"Pouliquen Angle 2", "0.53582", "rad", 0, 1.5, "zeta_2: friction angle where h_stop vanishes (glass beads: 30.7 deg)"},
        {"Pouliquen Beta", "0.136", "-", 1e-3, 10, "beta of Fr = beta H / h_stop(theta) in steady flow"},
        {"Pouliquen L", "0.00065", "m", 1e-7, 1e3, "length L of h_stop = L (tan z2 - tan theta) / (tan theta - tan z1)"}},
       muIParams, muICheck},
      {"bingham", Rheology::HerschelBulkley, "Bingham plastic: yield stress and viscosity (plug flow)",
       {yield, {"Bingham Viscosity", "100", "Pa s", 1e-6, 1e9, "plastic viscosity mu_B of a Bingham solid phase"}},
       binghamParams, noCheck},
      {"herschel-bulkley", Rheology::HerschelBulkley, "Herschel-Bulkley: tau_y + K (du/dz)^n (plug flow)",
       {yield,
        {"Consistency Index", "100", "Pa s^n", 1e-6, 1e9, "consistency K of a Herschel-Bulkley solid phase"},
        {"Flow Index", "0.33", "-", 0.05, 5, "flow index n of a Herschel-Bulkley solid phase (mud: about 1/3)"}},
       hbParams, noCheck},
  };
}

}  // namespace

const std::vector<RheologyLaw>& rheologyLaws() {
  static const std::vector<RheologyLaw> laws = buildLaws();
  return laws;
}

const RheologyLaw& rheologyLaw(const std::string& name) {
  std::string names;
  for (const RheologyLaw& law : rheologyLaws()) {
    if (law.name == name) return law;
    names += (names.empty() ? "" : ", ") + law.name;
  }
  throw InputError("solid rheology '" + name + "' is not one of: " + names);
}

}  // namespace talus::flow
