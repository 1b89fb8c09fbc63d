// Declared run-file keys: each key is declared once with its type, default, unit, valid range,
// section and help text. The registry is what RunConfig validates a run-file against, what the
// "did you mean" suggestions search, and what the generated key table in docs/runfile.md lists.
#pragma once
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

namespace talus::io {

class RunConfig;

/// The kind of value a key takes.
enum class KeyType {
  Flag,       ///< 0/1 (also true/false, yes/no, on/off)
  Integer,    ///< an integral number, may carry a multiplier
  Real,       ///< a finite real number, may carry a multiplier
  Choice,     ///< one of KeySpec::choices, case-insensitive, stored lowercase
  Text,       ///< free text (trimmed)
  Directory,  ///< a folder path, resolved to an absolute path; need not exist
  Map,        ///< a raster file (must exist) or a number meaning a uniform map; may carry a multiplier
};

/// The name of a key type as written in the key table ("flag", "real", ...).
std::string keyTypeName(KeyType type);

/// What Talus does with a declared key. OpenLISEM Hazard's GUI writes every key of its parameter list
/// into each run-file, processes that are off included, so Talus knows keys it does not use.
enum class KeyRole {
  Used,          ///< read by Talus (its own keys, and OpenLISEM Hazard's with OpenLISEM's meaning)
  Unmodelled,    ///< a flag switching on a process Talus does not model: 0 accepted, 1 refused
  ProcessInput,  ///< an input of a process Talus does not model: accepted, never read
  NoEffect,      ///< an OpenLISEM Hazard setting without effect in Talus: accepted with a note
  OutputSwitch,  ///< an OpenLISEM Hazard output switch Talus does not honour yet: accepted with a note
};

/// The declaration of one run-file key.
struct KeySpec {
  std::string name;          ///< canonical name as written in run-files, e.g. "Map Directory"
  KeyType type = KeyType::Text;
  std::string defaultValue;  ///< run-file text of the default (ignored when required)
  std::string unit;          ///< unit of the value ("-" for dimensionless, "" when not a quantity)
  double min = -std::numeric_limits<double>::infinity();  ///< smallest valid value (numbers, maps)
  double max = std::numeric_limits<double>::infinity();   ///< largest valid value (numbers, maps)
  std::vector<std::string> choices;  ///< valid values of a Choice key (lowercase)
  std::string help;          ///< one-line description
  std::string section;       ///< section the key is listed under ("Input", "Time", ...)
  bool required = false;     ///< the run-file must give the key
  /// A Flag key that switches on the process this map belongs to ("Include Initial Water"): while
  /// it is 0 the map is not read, need not exist, and giving it earns a warning. Empty: always read.
  std::string enabledBy;
  KeyRole role = KeyRole::Used;
  /// Unmodelled: the process as the refusal names it ("slope failure"); ProcessInput and NoEffect:
  /// why Talus does not read the key. Shown in the OpenLISEM key table of docs/runfile.md.
  std::string process;
  /// Unmodelled: Talus is meant to model the process (refused as "not modelled by Talus yet").
  bool plannedProcess = false;
  /// The key is one OpenLISEM Hazard 2.x's GUI writes (lisem/model/parameters/parametermanager.h).
  bool fromLisem = false;
  /// OpenLISEM Hazard's default value text (when fromLisem); a switched-off map given with it is
  /// OpenLISEM's own boilerplate and earns no warning.
  std::string lisemDefault;
  /// Other names that mean this key (OpenLISEM 6's "Begin time" for Start Time).
  std::vector<std::string> aliases;
};

/// The name of a key role as written in the OpenLISEM key table ("used", "process off", ...).
std::string keyRoleName(KeyRole role);

/// A consistency rule over several keys, checked after every key parsed. Returns "" when the
/// configuration satisfies it, else the problem (the message should name the keys involved).
using KeyCheck = std::function<std::string(const RunConfig&)>;

/// A cross-key rule together with the keys it reads (the error is reported at the line of the last
/// of them given, and the rule is skipped when one of them already has an error).
struct KeyRule {
  std::vector<std::string> keys;
  KeyCheck check;
};

/// The set of declared keys, in declaration order.
class KeyRegistry {
 public:
  /// Declares a key. Throws std::logic_error for a duplicate name (after normalisation), an empty
  /// name, or a Choice key without choices / with a default outside them.
  KeyRegistry& add(KeySpec spec);
  /// Declares a rule relating several declared keys (e.g. End Time > Start Time).
  KeyRegistry& addRule(std::vector<std::string> keys, KeyCheck check);

  /// The key with this name (case-insensitive, whitespace-normalised), or nullptr.
  const KeySpec* find(const std::string& name) const;
  /// Position of the key in keys(), or -1 when not declared.
  int indexOf(const std::string& name) const;
  /// All keys in declaration order.
  const std::vector<KeySpec>& keys() const { return keys_; }
  /// All cross-key rules in declaration order.
  const std::vector<KeyRule>& rules() const { return rules_; }

  /// Declared names closest to a misspelt one (all at the smallest distance): case-insensitive Levenshtein distance
  /// on normalised names of at most max(1, length / 4) and at most a third of the name's length
  /// (so a short word is not "corrected" into an unrelated short key: 'coh' is not 'CFL').
  std::vector<std::string> suggestions(const std::string& misspelt) const;

  /// A Markdown table of every key grouped by section: name, type, default, unit, range, help.
  std::string markdownTable() const;
  /// A Markdown table of OpenLISEM Hazard's keys (KeySpec::fromLisem): OpenLISEM's default and
  /// what Talus does with each.
  std::string lisemMarkdownTable() const;

 private:
  std::vector<KeySpec> keys_;
  std::vector<KeyRule> rules_;
  std::unordered_map<std::string, std::size_t> index_;  // normalised name or alias -> position
};

/// The key table of a registry as Markdown (what `talus keys --markdown` prints).
std::string describeKeys(const KeyRegistry& keys);

/// A key name as matched: trimmed, internal whitespace runs collapsed to one space, lowercase.
std::string normalizeKeyName(const std::string& name);

/// The valid range of a number as text: "[0, 1]", ">= 0", "<= 5" or "" when unbounded.
std::string rangeText(const KeySpec& spec);

/// A number formatted briefly (up to 15 significant digits, no trailing zeros).
std::string formatNumber(double value);

}  // namespace talus::io
