// Declared run-file keys: registration, lookup, spelling suggestions and the Markdown key table.
#include "io/KeyRegistry.hpp"
#include "core/Text.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace talus::io {

namespace {

/// Lowercase copy of an ASCII string.
/// Levenshtein edit distance between two strings (insertions, deletions, substitutions).
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const std::size_t substitution = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({row[j - 1] + 1, above + 1, substitution});
      diagonal = above;
    }
  }
  return row[b.size()];
}

/// A table cell with '|' escaped.
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::string keyTypeName(KeyType type) {
  switch (type) {
    case KeyType::Flag: return "flag";
    case KeyType::Integer: return "integer";
    case KeyType::Real: return "real";
    case KeyType::Choice: return "choice";
    case KeyType::Text: return "text";
    case KeyType::Directory: return "directory";
    case KeyType::Map: return "map";
  }
  return "?";
}

std::string normalizeKeyName(const std::string& name) {
  std::string out;
  bool pendingSpace = false;
  for (char c : name) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      pendingSpace = !out.empty();
      continue;
    }
    if (pendingSpace) out += ' ';
    pendingSpace = false;
    out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

std::string formatNumber(double value) {
  std::ostringstream os;
  os.precision(15);
  os << value;
  return os.str();
}

std::string rangeText(const KeySpec& spec) {
  const bool hasMin = std::isfinite(spec.min), hasMax = std::isfinite(spec.max);
  if (hasMin && hasMax) return "[" + formatNumber(spec.min) + ", " + formatNumber(spec.max) + "]";
  if (hasMin) return ">= " + formatNumber(spec.min);
  if (hasMax) return "<= " + formatNumber(spec.max);
  return "";
}

KeyRegistry& KeyRegistry::add(KeySpec spec) {
  const std::string key = normalizeKeyName(spec.name);
  if (key.empty()) throw std::logic_error("KeyRegistry::add: a key needs a name");
  if (index_.count(key)) throw std::logic_error("KeyRegistry::add: key '" + spec.name + "' declared twice");
  if (spec.type == KeyType::Choice) {
    if (spec.choices.empty())
      throw std::logic_error("KeyRegistry::add: choice key '" + spec.name + "' has no choices");
    for (auto& c : spec.choices) c = lower(c);
    if (!spec.required &&
        std::find(spec.choices.begin(), spec.choices.end(), lower(spec.defaultValue)) == spec.choices.end())
      throw std::logic_error("KeyRegistry::add: default of choice key '" + spec.name + "' is not a choice");
  }
  for (const auto& alias : spec.aliases)
    if (index_.count(normalizeKeyName(alias)) || normalizeKeyName(alias) == key)
      throw std::logic_error("KeyRegistry::add: alias '" + alias + "' of '" + spec.name + "' is declared already");
  index_.emplace(key, keys_.size());
  for (const auto& alias : spec.aliases) index_.emplace(normalizeKeyName(alias), keys_.size());
  keys_.push_back(std::move(spec));
  return *this;
}

KeyRegistry& KeyRegistry::addRule(std::vector<std::string> keys, KeyCheck check) {
  for (const auto& k : keys)
    if (!find(k)) throw std::logic_error("KeyRegistry::addRule: undeclared key '" + k + "'");
  rules_.push_back({std::move(keys), std::move(check)});
  return *this;
}

const KeySpec* KeyRegistry::find(const std::string& name) const {
  const int i = indexOf(name);
  return i < 0 ? nullptr : &keys_[static_cast<std::size_t>(i)];
}

int KeyRegistry::indexOf(const std::string& name) const {
  const auto it = index_.find(normalizeKeyName(name));
  return it == index_.end() ? -1 : static_cast<int>(it->second);
}

std::vector<std::string> KeyRegistry::suggestions(const std::string& misspelt) const {
  const std::string wanted = normalizeKeyName(misspelt);
  // A quarter of the letters (at least one) may differ, but never more than a third: 'coh' (3
  // letters) two edits from 'CFL' is no misspelling of it, 'Maning' one edit from 'Manning' is.
  const std::size_t limit = std::max<std::size_t>(1, wanted.size() / 4);
  std::vector<std::pair<std::size_t, std::size_t>> hits;  // (distance, key position)
  // The edit distance is at least the difference in length, so only names of about the same
  // length need the quadratic comparison: an 8 MiB misspelt key costs one pass, not minutes.
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const std::string name = normalizeKeyName(keys_[i].name);
    const std::size_t gap = wanted.size() > name.size() ? wanted.size() - name.size() : name.size() - wanted.size();
    if (gap > limit) continue;
    const std::size_t d = editDistance(wanted, name);
    if (d <= limit && 3 * d <= wanted.size()) hits.emplace_back(d, i);
  }
  std::stable_sort(hits.begin(), hits.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  // Only the closest names: 'Include Initial Stabilty' is one edit from 'Include Initial Stability'
  // and should not also be offered 'Include Initial Solids', five edits away.
  std::vector<std::string> names;
  for (const auto& h : hits)
    if (h.first == hits.front().first) names.push_back(keys_[h.second].name);
  return names;
}

std::string KeyRegistry::markdownTable() const {
  std::vector<std::string> sections;
  for (const auto& k : keys_)
    if (k.role == KeyRole::Used && std::find(sections.begin(), sections.end(), k.section) == sections.end())
      sections.push_back(k.section);
  std::ostringstream os;
  for (const auto& section : sections) {
    os << "### " << (section.empty() ? "Other" : section) << "\n\n"
       << "| Key | Type | Default | Unit | Range | Description |\n"
       << "|---|---|---|---|---|---|\n";
    for (const auto& k : keys_) {
      if (k.section != section || k.role != KeyRole::Used) continue;
      std::string type = keyTypeName(k.type);
      if (k.type == KeyType::Choice) {
        type += ": ";
        for (std::size_t i = 0; i < k.choices.size(); ++i) type += (i ? ", " : "") + k.choices[i];
      }
      std::string def = k.required ? "(required)" : k.defaultValue;
      if (!k.required && k.defaultValue.empty()) def = "(empty)";
      const std::string help = k.enabledBy.empty() ? k.help : k.help + "; read only with " + k.enabledBy + "=1";
      os << "| `" << k.name << "` | " << cell(type) << " | " << cell(def) << " | " << cell(k.unit)
         << " | " << cell(rangeText(k)) << " | " << cell(help) << " |\n";
    }
    os << "\n";
  }
  return os.str();
}

std::string keyRoleName(KeyRole role) {
  switch (role) {
    case KeyRole::Used: return "used";
    case KeyRole::Unmodelled: return "process switch";
    case KeyRole::ProcessInput: return "input of a process Talus lacks";
    case KeyRole::NoEffect: return "no effect";
    case KeyRole::OutputSwitch: return "output switch";
  }
  return "?";
}

std::string KeyRegistry::lisemMarkdownTable() const {
  std::ostringstream os;
  os << "| OpenLISEM key | OpenLISEM default | In Talus |\n|---|---|---|\n";
  for (const auto& k : keys_) {
    if (!k.fromLisem) continue;
    std::string what;
    switch (k.role) {
      case KeyRole::Used: what = "same key and meaning: " + k.help + (k.unit.empty() || k.unit == "-" ? "" : " [" + k.unit + "]"); break;
      case KeyRole::Unmodelled:
        what = "0 accepted; 1 refused: " + k.process + " is not modelled by Talus" + (k.plannedProcess ? " yet" : "");
        break;
      case KeyRole::ProcessInput: what = "accepted, not read: " + k.process; break;
      case KeyRole::NoEffect: what = "accepted with a note, no effect: " + k.process; break;
      case KeyRole::OutputSwitch: what = "accepted with a note: OpenLISEM output switch, not honoured yet"; break;
    }
    os << "| `" << k.name << "` | " << cell(k.lisemDefault.empty() ? "(empty)" : k.lisemDefault) << " | " << cell(what)
       << " |\n";
  }
  return os.str();
}

std::string describeKeys(const KeyRegistry& keys) {
  return keys.markdownTable() + "### OpenLISEM Hazard 2.x keys\n\n" +
         "Every key of OpenLISEM Hazard 2.x's parameter list (those Talus uses first), with its default\n" +
         "there and what Talus does with it (see \"OpenLISEM Hazard run-files\" above).\n\n" +
         keys.lisemMarkdownTable();
}

}  // namespace talus::io
