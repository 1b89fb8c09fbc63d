// RunConfig's warnings: what a run-file asks for that Talus reads differently or not at all. The
// OpenLISEM Hazard keys Talus accepts without acting on them are summarised in one line per kind
// (lisemNotes), so that a run-file written by OpenLISEM's GUI, which carries every key, earns two
// lines rather than forty. The output switches have their own line here: when Talus honours them,
// this is the one place to change.
#include <string>
#include <vector>

#include "io/RunConfig.hpp"

namespace talus::io {

namespace {

/// "a, b and c".
std::string joinNames(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) out += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return out;
}

/// The note on keys of one role that were given: those given with a value other than OpenLISEM's
/// default by name and value, the others counted.
std::string summarise(const std::vector<std::string>& changed, std::size_t atDefault, const std::string& lead) {
  if (changed.empty() && atDefault == 0) return "";
  std::string out = lead;
  if (!changed.empty()) out += ": " + joinNames(changed);
  if (atDefault > 0)
    out += (changed.empty() ? ": " : " (and ") + std::to_string(atDefault) + " more at OpenLISEM's defaults" +
           (changed.empty() ? "" : ")");
  return out;
}

}  // namespace

std::vector<std::string> RunConfig::lisemNotes() const {
  std::vector<std::string> noEffect, outputs;
  std::size_t noEffectDefault = 0, outputsDefault = 0;
  const auto& specs = registry_.keys();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const KeySpec& spec = specs[i];
    const Entry& e = entries_[i];
    if (e.origin == "default") continue;
    const bool atDefault = e.raw == spec.lisemDefault;
    if (spec.role == KeyRole::NoEffect) {
      if (atDefault) ++noEffectDefault;
      else noEffect.push_back(spec.name + "=" + e.raw);
    } else if (spec.role == KeyRole::OutputSwitch) {
      if (atDefault) ++outputsDefault;
      else outputs.push_back(spec.name + "=" + e.raw);
    }
  }
  std::vector<std::string> out;
  const std::size_t nNoEffect = noEffect.size() + noEffectDefault, nOutputs = outputs.size() + outputsDefault;
  const std::string a = summarise(noEffect, noEffectDefault,
                                  std::to_string(nNoEffect) + " OpenLISEM Hazard setting" + (nNoEffect == 1 ? " has" : "s have") +
                                      " no effect in Talus (it chooses its own steps and device)");
  if (!a.empty()) out.push_back(source_ + ": " + a);
  const std::string b = summarise(outputs, outputsDefault,
                                  std::to_string(nOutputs) + " OpenLISEM Hazard output switch" + (nOutputs == 1 ? " is" : "es are") +
                                      " not honoured yet (Talus writes its own outputs, docs/outputs.md)");
  if (!b.empty()) out.push_back(source_ + ": " + b);
  return out;
}

std::vector<std::string> RunConfig::warnings() const {
  std::vector<std::string> out;
  const auto& specs = registry_.keys();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const Entry& e = entries_[i];
    if (!e.note.empty()) out.push_back(printableText(where(e) + ": key '" + specs[i].name + "': " + e.note));
    // A value equal to the default says nothing (run.resolved.run writes every key, defaults too),
    // nor does OpenLISEM's default file name (its GUI writes every map, with the multiplier 1).
    const bool plainMult = !e.hasMult || e.rawMult == "1";
    if (e.origin == "default" || switchedOn(specs[i]) || specs[i].role != KeyRole::Used) continue;
    // A text key (the Rainfall file) keeps OpenLISEM's "=1" multiplier inside its value.
    const bool lisemDefault = specs[i].fromLisem && (e.raw == specs[i].lisemDefault || e.raw == specs[i].lisemDefault + "=1");
    if (plainMult && (e.raw == specs[i].defaultValue || lisemDefault)) continue;
    out.push_back(printableText(where(e) + ": key '" + specs[i].name + "' is given, but '" + specs[i].enabledBy +
                                "' is 0: the map is not read (set '" + specs[i].enabledBy + "=1' to use it)"));
  }
  for (const auto& n : lisemNotes()) out.push_back(printableText(n));
  return out;
}

}  // namespace talus::io
