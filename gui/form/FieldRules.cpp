#include "form/FieldRules.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>

#include "flow/Rheology.hpp"

namespace talus::gui {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  s.erase(0, s.find_first_not_of(" \t"));
  s.erase(s.find_last_not_of(" \t") + 1);
  return s;
}

/// The number a value text starts with (0 when none: an empty or unreadable value reads as off).
double number(const std::string& text) { return std::strtod(text.c_str(), nullptr); }

FieldRule whenOn(std::string key, std::string flag) {
  return {std::move(key), [flag](const ValueOf& v) { return isOn(v(flag)); }, "on with " + flag + "=1"};
}
FieldRule whenOff(std::string key, std::string flag) {
  return {std::move(key), [flag](const ValueOf& v) { return !isOn(v(flag)); }, "off with " + flag + "=1"};
}
FieldRule whenZero(std::string key, std::string other) {
  return {std::move(key), [other](const ValueOf& v) { return number(v(other)) == 0; }, "used while " + other + " is 0"};
}
FieldRule whenPositive(std::string key, std::string other) {
  return {std::move(key), [other](const ValueOf& v) { return number(v(other)) > 0; }, "needs " + other + " > 0"};
}

}  // namespace

bool isOn(const std::string& flagValue) {
  const std::string v = lower(flagValue);
  return v == "1" || v == "true" || v == "yes" || v == "on";
}

std::vector<FieldRule> fieldRules(const io::KeyRegistry& keys) {
  std::vector<FieldRule> rules;
  for (const io::KeySpec& k : keys.keys())
    if (!k.enabledBy.empty()) rules.push_back(whenOn(k.name, k.enabledBy));
  rules.push_back(whenOff("Bed Friction Angle", "Bed Friction Equals IFA"));
  rules.push_back({"Earth Pressure Coefficient", [](const ValueOf& v) { return lower(v("Earth Pressure")) == "constant"; },
                   "used with Earth Pressure=constant"});
  rules.push_back(whenZero("Young Modulus", "Elastic Modulus"));
  rules.push_back(whenZero("Poisson Ratio", "Shear Modulus"));
  rules.push_back(whenZero("Particle Volume", "Particle Fractional Dimension"));
  rules.push_back({"Particles Per Cell",
                   [](const ValueOf& v) { return number(v("Particle Fractional Dimension")) == 0 && number(v("Particle Volume")) == 0; },
                   "used while Particle Fractional Dimension and Particle Volume are 0"});
  rules.push_back(whenZero("Rainfall", "Rainfall Intensity"));
  rules.push_back(whenOn("Entrainment Growth Rate", "Include Entrainment"));
  for (const char* drag : {"Drag coefficient multiplier", "Drag P Exponent", "Drag M", "Drag Smoothing Velocity"})
    rules.push_back({drag, [](const ValueOf& v) { return lower(v("Drag Law")) != "off"; }, "off with Drag Law=off"});
  // The split time scheme is for water-only runs; solids (on the grid, as particles, or entrained)
  // make the run two-phase, which is unsplit.
  rules.push_back({"Time Scheme",
                   [](const ValueOf& v) {
                     return !isOn(v("Include Initial Solids")) && !isOn(v("Use Material Point Method")) &&
                            !isOn(v("Include Entrainment"));
                   },
                   "water-only runs (a run with solids is two-phase, which is unsplit)"});
  rules.push_back(whenPositive("Viscous Shear Factor", "Viscous Reynolds Number"));
  rules.push_back(whenPositive("Viscous Profile Factor", "Interfacial Reynolds Number"));
  // A basal law's parameters matter while Solid Rheology names a law that reads them.
  std::vector<std::string> lawKeys;
  for (const flow::RheologyLaw& law : flow::rheologyLaws())
    for (const flow::RheologyKey& key : law.keys)
      if (std::find(lawKeys.begin(), lawKeys.end(), key.name) == lawKeys.end()) lawKeys.push_back(key.name);
  for (const std::string& name : lawKeys)
    rules.push_back({name, [name](const ValueOf& v) {
                       const std::string chosen = lower(v("Solid Rheology"));
                       for (const flow::RheologyLaw& law : flow::rheologyLaws())
                         if (law.name == chosen)
                           for (const flow::RheologyKey& key : law.keys)
                             if (key.name == name) return true;
                       return false;
                     }, "used by another Solid Rheology"});
  // Rules name keys of this registry only (a registry without them gets none of their rules).
  rules.erase(std::remove_if(rules.begin(), rules.end(), [&](const FieldRule& r) { return !keys.find(r.key); }),
              rules.end());
  return rules;
}

std::vector<std::string> sectionProcesses(const io::KeyRegistry& keys, const std::string& section) {
  std::vector<const io::KeySpec*> inSection;
  for (const io::KeySpec& k : keys.keys())
    if (k.section == section) inSection.push_back(&k);
  auto switchesMaps = [&](const io::KeySpec& flag) {
    return flag.type == io::KeyType::Flag &&
           std::any_of(inSection.begin(), inSection.end(), [&](const io::KeySpec* k) {
             return io::normalizeKeyName(k->enabledBy) == io::normalizeKeyName(flag.name);
           });
  };
  std::vector<std::string> flags;
  if (inSection.empty() || !switchesMaps(*inSection.front())) return flags;
  for (const io::KeySpec* k : inSection)
    if (switchesMaps(*k)) flags.push_back(k->name);
  return flags;
}

bool sectionUnread(const io::KeyRegistry& keys, const std::string& section) {
  bool any = false;
  for (const io::KeySpec& k : keys.keys()) {
    if (k.section != section) continue;
    if (k.role == io::KeyRole::Used) return false;
    any = true;
  }
  return any;
}

}  // namespace talus::gui
