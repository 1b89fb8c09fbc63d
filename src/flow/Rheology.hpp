// The basal rheologies of the solids (kernels/flow/basal_rheology.cl) as a table: each law's
// run-file name, its keys with defaults and ranges, and how their values become the kernels'
// parameters. The run-file keys (sim/RunKeys.cpp) and the scene (sim/Scene.cpp) read this table, so
// a new law is one entry here plus its function in basal_rheology.cl (docs/rheology.md).
#pragma once
#include <array>
#include <string>
#include <vector>

namespace talus::flow {

/// Kernel ids (RHEOLOGY_* of basal_rheology.cl).
enum class Rheology { Coulomb = 0, Voellmy = 1, MuI = 2, HerschelBulkley = 3 };

/// One run-file key of a law (a real number).
struct RheologyKey {
  std::string name, defaultValue, unit;
  double min, max;
  std::string help;
};

struct RheologyLaw {
  std::string name;   ///< value of the key "Solid Rheology"
  Rheology id;
  std::string help;   ///< one line for the key's documentation
  std::vector<RheologyKey> keys;
  /// The kernel parameters rheo[0..3] from the keys' values (in the order of `keys`).
  std::array<double, 4> (*params)(const std::vector<double>& values);
  /// "" when the values are consistent, else why not (names the keys).
  std::string (*check)(const std::vector<double>& values);
};

/// Every law, Coulomb first (the default).
const std::vector<RheologyLaw>& rheologyLaws();
/// The law named `name`; throws InputError listing the names when there is none.
const RheologyLaw& rheologyLaw(const std::string& name);

}  // namespace talus::flow
