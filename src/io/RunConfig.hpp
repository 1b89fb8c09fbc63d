// A parsed and validated run-file (OpenLISEM Hazard syntax) against a registry of declared keys.
// Every key of the registry has a value afterwards (given or default); every error a user can make
// is reported as a talus::InputError naming the file, line and key.
#pragma once
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "io/KeyRegistry.hpp"

namespace talus::io {

/// The value of a Map key: a raster file or a uniform number, times a multiplier.
struct MapValue {
  bool isFile = false;
  std::string file;       ///< absolute path of the raster (when isFile)
  double constant = 0;    ///< the uniform value (when !isFile), before the multiplier
  double multiplier = 1;  ///< applies to every cell
};

/// A run configuration: the declared keys with their values, where each value came from, and the
/// folder relative paths are resolved against.
class RunConfig {
 public:
  /// Reads, parses and validates a run-file. Throws talus::InputError (all problems, one per line).
  static RunConfig load(const std::string& runFilePath, const KeyRegistry& keys);
  /// Parses and validates run-file text whose relative paths resolve against baseDir. Error
  /// messages name the text displayName.
  static RunConfig fromText(const std::string& text, const std::string& baseDir, const KeyRegistry& keys,
                            const std::string& displayName = "<text>");

  /// Overrides one key, "Key=Value[=Multiplier]" (the --set option), validated like a run-file line;
  /// errors name "command line --set". The configuration is unchanged when it throws.
  void set(const std::string& assignment);

  /// Value times multiplier of a Real or Integer key.
  double real(const std::string& key) const;
  /// Value times multiplier of an Integer key.
  int integer(const std::string& key) const;
  bool flag(const std::string& key) const;
  /// The chosen alternative of a Choice key, lowercase.
  std::string choice(const std::string& key) const;
  std::string text(const std::string& key) const;
  /// Absolute, normalised folder of a Directory key.
  std::string directory(const std::string& key) const;
  MapValue map(const std::string& key) const;

  /// True when the key was given neither in the run-file nor by set().
  bool isDefault(const std::string& key) const;
  /// Where the value came from: "file.run:12", "command line" or "default".
  std::string origin(const std::string& key) const;

  /// The fully resolved configuration in run-file syntax: every key Talus uses grouped by section,
  /// paths absolute, each preceded by a comment with its help, unit and origin. fromText parses it
  /// back to the same values.
  std::string echo() const;

  /// The value of a key in run-file syntax as echo() writes it (paths absolute, numbers read from
  /// a decimal comma or day:minute time written plainly, quoted where needed, "=multiplier" kept).
  std::string valueText(const std::string& key) const;
  /// How the value was read when it needed reading OpenLISEM-style (decimal comma, day:minute,
  /// Windows path, file name in another case), else "".
  std::string note(const std::string& key) const { return entry(key, {}).note; }

  /// Warnings about the configuration that do not stop a run (RunConfigNotes.cpp): maps given for
  /// a process that is switched off (KeySpec::enabledBy) with a value other than the default or
  /// OpenLISEM's, values read OpenLISEM-style (note()), one line for the OpenLISEM settings given
  /// that have no effect in Talus and one for OpenLISEM's output switches.
  std::vector<std::string> warnings() const;

  /// Name of the run-file (or display name of the text) as used in messages.
  const std::string& sourceName() const { return source_; }
  /// Absolute folder relative paths in the run-file resolve against.
  std::string baseDir() const { return baseDir_; }
  /// The registry the configuration was validated against.
  const KeyRegistry& registry() const { return registry_; }

 private:
  /// One key's value: the text as given and what it was parsed to.
  struct Entry {
    std::string raw;         // value text, trimmed
    std::string rawMult;     // multiplier text, "" when none
    bool hasMult = false;
    bool quoted = false;     // the value was written in quotes (backslashes are not separators)
    std::string origin = "default";
    int line = 0;            // run-file line, 0 for defaults and the command line
    // parsed
    double number = 0;       // Real/Integer value before the multiplier
    double multiplier = 1;
    bool flagValue = false;
    std::string textValue;   // Choice (lowercase), Text, Directory (absolute)
    MapValue mapValue;
    std::string note;        // how an OpenLISEM-style value was read ("" when plainly)
  };

  RunConfig(const KeyRegistry& keys, std::string source, std::string baseDir);

  /// Parses every value, checks required keys and rules; returns the problems, each with the rank
  /// of its location (run-file line; command line and defaults after the file).
  std::vector<std::pair<long, std::string>> validate();
  /// Parses one entry of the key at position i; returns "" or the problem (without location).
  std::string parseEntry(std::size_t i, Entry& e, const std::string& mapDir) const;
  /// False when the key belongs to a process whose switch (KeySpec::enabledBy) is off.
  bool switchedOn(const KeySpec& spec) const;
  /// Location prefix of messages about an entry ("file:12", "command line --set", or the file).
  std::string where(const Entry& e) const;
  /// The one-line notes about OpenLISEM keys Talus accepts but does not act on (RunConfigNotes.cpp).
  std::vector<std::string> lisemNotes() const;
  /// The entry of a declared key of the given type; std::logic_error otherwise.
  const Entry& entry(const std::string& key, std::initializer_list<KeyType> types) const;

  KeyRegistry registry_;
  std::string source_;
  std::string baseDir_;
  std::string header_;  // first header line of the run-file, kept for echo
  std::vector<Entry> entries_;  // parallel to registry_.keys()
};

/// Text with control bytes escaped (\0, \xNN), as messages that quote a run-file show it.
std::string printableText(const std::string& text);

}  // namespace talus::io
