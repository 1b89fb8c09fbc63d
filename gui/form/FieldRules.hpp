// Which fields of the run-file form matter for the values the form holds now: a map of a process
// that is off (KeySpec::enabledBy), Bed Friction Angle while it equals the IFA, the parameters of
// the basal laws not chosen, ... Such fields are disabled, not hidden. And which sections belong to
// a process (Solids, Particles, ...), so that the form expands only those of processes that are on.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "io/KeyRegistry.hpp"

namespace talus::gui {

/// The value text of a key as the form holds it now (the file's, or the default).
using ValueOf = std::function<std::string(const std::string& key)>;

/// A dependent field: `key` matters only while `applies` holds; `reason` says on what.
struct FieldRule {
  std::string key;
  std::function<bool(const ValueOf&)> applies;
  std::string reason;
};

/// The rules of a registry: one per map read only with its process on, and the pairs the key
/// declarations describe in words (Bed Friction Equals IFA, Earth Pressure, Elastic and Shear
/// Modulus, the particle volume, Drag Law, the Reynolds numbers, Solid Rheology, the rainfall).
std::vector<FieldRule> fieldRules(const io::KeyRegistry& keys);

/// Whether a flag's value text means on (1, true, yes, on).
bool isOn(const std::string& flagValue);

/// The flags whose process a section's keys belong to: for a section that starts with a flag that
/// switches on maps of the same section (Solids: Include Initial Solids; Rain and infiltration:
/// Include Rainfall and Include Infiltration), every such flag of the section; else none.
std::vector<std::string> sectionProcesses(const io::KeyRegistry& keys, const std::string& section);

/// Whether Talus reads none of a section's keys (OpenLISEM Hazard's keys of processes it does not
/// model): such a section starts collapsed.
bool sectionUnread(const io::KeyRegistry& keys, const std::string& section);

}  // namespace talus::gui
