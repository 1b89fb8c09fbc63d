// OpenLISEM Hazard run-file -> Talus run-file (see RunFileConvert.hpp).
#include "io/RunFileConvert.hpp"

#include <map>
#include <sstream>

#include "io/RunConfig.hpp"

namespace talus::io {

Conversion convertRunFile(const std::string& inPath, const KeyRegistry& keys) {
  const RunConfig cfg = RunConfig::load(inPath, keys);
  Conversion out;
  std::ostringstream text;
  text << "# Talus run-file converted from " << inPath << " by `talus convert-runfile`.\n"
       << "# Only the keys Talus uses are kept; paths are absolute.\n";
  std::string section = "\x01";  // no section written yet
  std::map<KeyRole, int> droppedAtDefault;
  std::string offMaps;
  for (const KeySpec& spec : keys.keys()) {
    if (cfg.isDefault(spec.name)) continue;
    const std::string at = cfg.origin(spec.name);
    if (spec.role != KeyRole::Used) {
      const std::string given = cfg.valueText(spec.name);
      if (given == spec.lisemDefault) ++droppedAtDefault[spec.role];
      else out.report.push_back("dropped '" + spec.name + "=" + given + "' (" + at + "): " + keyRoleName(spec.role) + ", " +
                                (spec.process.empty() ? spec.help : spec.process));
      continue;
    }
    if (!spec.enabledBy.empty() && !cfg.flag(spec.enabledBy)) {  // a map of a process that is off: not read
      offMaps += (offMaps.empty() ? "" : ", ") + spec.name + " (" + spec.enabledBy + "=0)";
      continue;
    }
    if (spec.section != section) {
      section = spec.section;
      text << "\n[" << section << "]\n";
    }
    text << spec.name << "=" << cfg.valueText(spec.name) << "\n";
    if (!cfg.note(spec.name).empty()) out.report.push_back("changed '" + spec.name + "' (" + at + "): " + cfg.note(spec.name));
  }
  for (const auto& [role, n] : droppedAtDefault)
    out.report.push_back("dropped " + std::to_string(n) + " more key" + (n == 1 ? "" : "s") + " at OpenLISEM's defaults (" +
                         keyRoleName(role) + ")");
  if (!offMaps.empty()) out.report.push_back("dropped the maps of processes that are off: " + offMaps);
  out.text = text.str();
  return out;
}

}  // namespace talus::io
