// Run-file parsing and validation: OpenLISEM Hazard syntax checked against declared keys, relative
// paths resolved, every problem reported with file, line and key; echo() writes the resolved setup.
#include "io/RunConfig.hpp"

#include <cstdio>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/Error.hpp"
#include "io/LisemValues.hpp"
#include "core/Text.hpp"

namespace talus::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMapDirectoryKey = "Map Directory";
constexpr long kRankCommandLine = LONG_MAX - 1;  // command-line problems come after the file's
constexpr long kRankDefault = LONG_MAX;          // then missing keys and rules over defaults
/// Largest run-file read. Real run-files are a few kilobytes (OpenLISEM Hazard's ~30 kB); the cap
/// keeps `talus run /dev/urandom`-like mistakes from reading until memory runs out.
constexpr std::uintmax_t kMaxRunFileBytes = 4u << 20;
/// User text longer than this is cut in messages (an 8 MiB key must not become an 8 MiB message).
constexpr std::size_t kMaxShown = 120;

/// Outcome of reading a number from text.
enum class Number { Ok, NotANumber, NotFinite };

/// Reads a whole string as a finite real number (C locale, optional leading '+').
Number parseNumber(const std::string& text, double& value) {
  std::string s = text;
  if (s.size() > 1 && s[0] == '+' && s[1] != '-' && s[1] != '+') s.erase(0, 1);
  if (s.empty()) return Number::NotANumber;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (end != s.data() + s.size()) return Number::NotANumber;
  if (ec == std::errc::result_out_of_range) return Number::NotFinite;
  if (ec != std::errc()) return Number::NotANumber;
  return std::isfinite(value) ? Number::Ok : Number::NotFinite;
}

/// An absolute, normalised path: value resolved against base (absolute values kept; backslashes
/// read as folder separators unless the value was quoted; an empty value is base itself).
std::string resolvePath(const std::string& base, std::string value, bool quoted = false) {
  if (!quoted) std::replace(value.begin(), value.end(), '\\', '/');
  fs::path p = value.empty() ? fs::path(base) : fs::path(value);
  if (p.is_relative()) p = fs::path(base) / p;
  std::string s = p.lexically_normal().string();
  while (s.size() > 1 && s.back() == '/') s.pop_back();
  return s;
}

/// The unit of a key for messages: " m", " (dimensionless)" or "".
std::string unitSuffix(const KeySpec& spec) {
  if (spec.unit == "-") return " (dimensionless)";
  return spec.unit.empty() ? "" : " " + spec.unit;
}

/// "" when v lies in the key's range, else the complaint.
std::string checkRange(const KeySpec& spec, double v, double raw, double mult) {
  if (v >= spec.min && v <= spec.max) return "";
  std::string what = "value " + formatNumber(v);
  if (mult != 1) what += " (" + formatNumber(raw) + " x multiplier " + formatNumber(mult) + ")";
  return what + " is outside the valid range " + rangeText(spec) + unitSuffix(spec);
}

/// User text for a message: cut after kMaxShown characters, saying how long it was.
std::string clip(const std::string& text) {
  if (text.size() <= kMaxShown) return text;
  return text.substr(0, kMaxShown) + "... (" + std::to_string(text.size()) + " bytes)";
}

/// Reads a number as OpenLISEM Hazard users write it: plain, or with a decimal comma (noted), or
/// for a key in minutes as OpenLISEM's day:minute time (noted). Returns "" or the problem.
std::string readUserNumber(const KeySpec& spec, const std::string& text, double& value, std::string& note) {
  const Number n = parseNumber(text, value);
  if (n == Number::Ok) return "";
  if (n == Number::NotFinite) return "bad number '" + clip(text) + "': not finite";
  std::string dotted;
  const DecimalComma comma = readDecimalComma(text, dotted);
  if (comma == DecimalComma::Ambiguous)
    return "bad number '" + clip(text) + "': a decimal comma or a thousands separator? write it with a decimal "
           "point (" + text.substr(0, text.find(',')) + "." + text.substr(text.find(',') + 1) + ") or without the comma";
  if (comma == DecimalComma::Read && parseNumber(dotted, value) == Number::Ok) {
    note = "'" + text + "' has a decimal comma: read as " + dotted;
    return "";
  }
  if (spec.unit == "min" && readDayMinute(text, value)) {
    note = "'" + text + "' read as OpenLISEM's day:minute time, " + formatNumber(value) + " min (day x 1440 + minute)";
    return "";
  }
  std::string hint;
  if (text.find(',') != std::string::npos) hint = ": expected one number with a decimal point (e.g. 0.05)";
  else if (text.find(':') != std::string::npos && spec.unit == "min")
    hint = ": expected minutes (e.g. 90) or OpenLISEM's day:minute (ddd:mmmm, e.g. 001:0030)";
  return "bad number '" + clip(text) + "'" + hint;
}

/// Reads a quoted value starting at rest[0] == '"': up to the next unescaped '"', with \\, \" and
/// \xHH (two hex digits) as escapes and every other character literal. Sets end to the position
/// after the closing quote; returns false when there is none.
bool unquote(const std::string& rest, std::string& value, std::size_t& end) {
  value.clear();
  for (std::size_t i = 1; i < rest.size(); ++i) {
    const char c = rest[i];
    if (c == '"') {
      end = i + 1;
      return true;
    }
    if (c == '\\' && i + 1 < rest.size() && (rest[i + 1] == '\\' || rest[i + 1] == '"')) {
      value += rest[++i];
    } else if (c == '\\' && i + 3 < rest.size() && rest[i + 1] == 'x' && std::isxdigit(static_cast<unsigned char>(rest[i + 2])) &&
               std::isxdigit(static_cast<unsigned char>(rest[i + 3]))) {
      value += static_cast<char>(std::stoi(rest.substr(i + 2, 2), nullptr, 16));
      i += 3;
    } else {
      value += c;
    }
  }
  return false;
}

/// Splits "Value[=Multiplier]"; Text and Directory values take everything after the first '='. A
/// value starting with '"' is quoted (see unquote): it may hold '=', spaces at its ends and
/// backslashes that are not folder separators. Returns "" or the problem.
std::string splitValue(const KeySpec& spec, const std::string& rest, std::string& value, std::string& mult,
                       bool& hasMult, bool& quoted) {
  const std::string t = trim(rest);
  quoted = !t.empty() && t[0] == '"';
  if (quoted) {
    std::size_t end = 0;
    if (!unquote(t, value, end)) return "quoted value " + clip(t) + " has no closing '\"'";
    const std::string after = trim(t.substr(end));
    hasMult = !after.empty();
    if (hasMult && after[0] != '=') return "unexpected text '" + clip(after) + "' after the quoted value";
    mult = hasMult ? trim(after.substr(1)) : "";
    return "";
  }
  const std::size_t eq = t.find('=');
  hasMult = eq != std::string::npos && spec.type != KeyType::Text && spec.type != KeyType::Directory;
  value = trim(hasMult ? t.substr(0, eq) : t);
  mult = hasMult ? trim(t.substr(eq + 1)) : "";
  return "";
}

/// True when echo() must quote a value for it to read back as it is: text a plain value cannot
/// carry ('=' would start a multiplier, spaces at the ends are trimmed, backslashes become folder
/// separators, a leading '"' starts a quote, control characters would break the line).
bool needsQuotes(const std::string& v) {
  if (v.empty()) return false;
  if (std::isspace(static_cast<unsigned char>(v.front())) || std::isspace(static_cast<unsigned char>(v.back())) ||
      v.front() == '"')
    return true;
  for (unsigned char c : v)
    if (c == '=' || c == '\\' || c < 0x20 || c == 0x7f) return true;
  return false;
}

/// The value as echo() writes it: as is, or quoted with \\, \" and \xHH escapes.
std::string quoteForEcho(const std::string& v) {
  if (!needsQuotes(v)) return v;
  std::string out = "\"";
  for (unsigned char c : v) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

/// The "did you mean" part of an unknown-key message ("" without suggestions).
std::string didYouMean(const KeyRegistry& keys, const std::string& name) {
  const auto names = keys.suggestions(name);
  if (names.empty()) return "";
  const std::size_t shown = std::min<std::size_t>(names.size(), 3);
  std::string s = "; did you mean ";
  for (std::size_t i = 0; i < shown; ++i) {
    if (i > 0) s += i + 1 == shown ? " or " : ", ";
    s += "'" + names[i] + "'";
  }
  return s + "?";
}

/// The message with control bytes of the run-file escaped (\0, \xNN): an embedded NUL would cut
/// the C string of what() short, and terminal escape sequences must not reach the terminal.
std::string printable(const std::string& text) {
  std::string out;
  for (unsigned char c : text) {
    if (c == 0) {
      out += "\\0";
    } else if ((c < 0x20 && c != '\t') || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string joinLines(std::vector<std::pair<long, std::string>> errors) {
  std::stable_sort(errors.begin(), errors.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::string out;
  for (const auto& e : errors) out += (out.empty() ? "" : "\n") + printable(e.second);
  return out;
}

}  // namespace

std::string printableText(const std::string& text) { return printable(text); }

RunConfig::RunConfig(const KeyRegistry& keys, std::string source, std::string baseDir)
    : registry_(keys), source_(std::move(source)), entries_(keys.keys().size()) {
  baseDir_ = resolvePath(fs::current_path().string(), std::move(baseDir));
  for (std::size_t i = 0; i < entries_.size(); ++i) entries_[i].raw = keys.keys()[i].defaultValue;
}

RunConfig RunConfig::load(const std::string& runFilePath, const KeyRegistry& keys) {
  std::error_code ec;
  if (fs::is_directory(runFilePath, ec))
    throw InputError("cannot read run-file '" + runFilePath + "': it is a folder");
  // Only regular files: a device (/dev/zero) or a pipe has no end to wait for.
  const fs::file_status st = fs::status(runFilePath, ec);
  if (!ec && fs::exists(st) && !fs::is_regular_file(st))
    throw InputError("cannot read run-file '" + runFilePath + "': not a regular file (a device, pipe or socket)");
  const std::uintmax_t size = fs::file_size(runFilePath, ec);
  if (!ec && size > kMaxRunFileBytes)
    throw InputError("cannot read run-file '" + runFilePath + "': it has " + std::to_string(size) +
                     " bytes, more than the " + std::to_string(kMaxRunFileBytes >> 20) +
                     " MiB a run-file may have (is it a run-file?)");
  std::ifstream in(runFilePath, std::ios::binary);
  if (!in) throw InputError("cannot read run-file '" + runFilePath + "': " + std::strerror(errno));
  // Read at most one byte more than the cap: a file that grows while being read is still bounded.
  std::string content(kMaxRunFileBytes + 1, '\0');
  in.read(content.data(), static_cast<std::streamsize>(content.size()));
  if (in.bad()) throw InputError("cannot read run-file '" + runFilePath + "': read error");
  content.resize(static_cast<std::size_t>(in.gcount()));
  if (content.size() > kMaxRunFileBytes)
    throw InputError("cannot read run-file '" + runFilePath + "': more than " +
                     std::to_string(kMaxRunFileBytes >> 20) + " MiB");
  const std::string folder = fs::absolute(fs::path(runFilePath)).parent_path().string();
  return fromText(content, folder, keys, runFilePath);
}

RunConfig RunConfig::fromText(const std::string& text, const std::string& baseDir, const KeyRegistry& keys,
                              const std::string& displayName) {
  RunConfig cfg(keys, displayName, baseDir);
  std::vector<std::pair<long, std::string>> errors;
  std::istringstream in(text);
  std::string raw;
  bool seenContent = false;
  for (int n = 1; std::getline(in, raw); ++n) {
    if (n == 1 && raw.rfind("\xEF\xBB\xBF", 0) == 0) raw.erase(0, 3);  // UTF-8 byte order mark
    const std::string t = trim(raw);
    if (t.empty() || t[0] == '#' || t[0] == ';') continue;
    const std::string at = displayName + ":" + std::to_string(n);
    if (t[0] == '[') {  // header or [Section]: ignored for lookup
      bool isSection = false;
      for (const auto& k : keys.keys())
        isSection = isSection || normalizeKeyName("[" + k.section + "]") == normalizeKeyName(t);
      if (!seenContent && !isSection) cfg.header_ = t;
      seenContent = true;
      continue;
    }
    seenContent = true;
    const std::size_t eq = t.find('=');
    if (eq == std::string::npos) {
      errors.emplace_back(n, at + ": key '" + clip(t) + "': no '=' in the line; expected Name=Value");
      continue;
    }
    const std::string name = trim(t.substr(0, eq));
    if (name.empty()) {
      errors.emplace_back(n, at + ": no key name before '='");
      continue;
    }
    const int idx = keys.indexOf(name);
    if (idx < 0) {
      errors.emplace_back(n, at + ": key '" + clip(name) + "': unknown key" + didYouMean(keys, name));
      continue;
    }
    const KeySpec& spec = keys.keys()[static_cast<std::size_t>(idx)];
    Entry& e = cfg.entries_[static_cast<std::size_t>(idx)];
    if (e.line > 0) {
      errors.emplace_back(n, at + ": key '" + spec.name + "': given twice, at " + e.origin + " and again at " +
                                 at);
      continue;
    }
    const std::string problem = splitValue(spec, t.substr(eq + 1), e.raw, e.rawMult, e.hasMult, e.quoted);
    e.origin = at;
    e.line = n;
    if (!problem.empty()) {
      errors.emplace_back(n, at + ": key '" + spec.name + "': " + problem);
      e.raw = spec.defaultValue;  // validated as the default, so the line is reported once
      e.hasMult = e.quoted = false;
    }
  }
  for (auto& err : cfg.validate()) errors.push_back(std::move(err));
  if (!errors.empty()) throw InputError(joinLines(std::move(errors)));
  return cfg;
}

void RunConfig::set(const std::string& assignment) {
  const std::string where = "command line --set";
  const std::string t = trim(assignment);
  const std::size_t eq = t.find('=');
  if (eq == std::string::npos)
    throw InputError(printable(where + ": key '" + clip(t) + "': no '=' in '" + clip(t) +
                               "'; expected Key=Value[=Multiplier]"));
  const std::string name = trim(t.substr(0, eq));
  // A run-file line cannot hold a line break; an override must not either (it would inject a line
  // into run.resolved.run). A tab is blank space, as in the file.
  for (unsigned char c : assignment)
    if ((c < 0x20 && c != '\t') || c == 0x7f)
      throw InputError(printable(where + ": key '" + clip(name) +
                                 "': the assignment holds a control character (line break, NUL, ...), "
                                 "which a run-file value cannot hold"));
  const int idx = registry_.indexOf(name);
  if (idx < 0)
    throw InputError(printable(where + ": key '" + clip(name) + "': unknown key" + didYouMean(registry_, name)));
  RunConfig updated = *this;
  Entry& e = updated.entries_[static_cast<std::size_t>(idx)];
  e = Entry{};
  const KeySpec& spec = registry_.keys()[static_cast<std::size_t>(idx)];
  const std::string problem = splitValue(spec, t.substr(eq + 1), e.raw, e.rawMult, e.hasMult, e.quoted);
  if (!problem.empty()) throw InputError(printable(where + ": key '" + spec.name + "': " + problem));
  e.origin = "command line";
  auto errors = updated.validate();
  if (!errors.empty()) throw InputError(joinLines(std::move(errors)));
  *this = std::move(updated);
}

std::string RunConfig::where(const Entry& e) const {
  if (e.line > 0) return e.origin;
  return e.origin == "command line" ? "command line --set" : source_;
}

std::vector<std::pair<long, std::string>> RunConfig::validate() {
  const auto& specs = registry_.keys();
  auto rank = [](const Entry& e) {
    if (e.line > 0) return static_cast<long>(e.line);
    return e.origin == "command line" ? kRankCommandLine : kRankDefault;
  };
  std::vector<std::pair<long, std::string>> errors;
  std::vector<bool> bad(specs.size(), false);
  std::string mapDir = baseDir_;
  const int mapDirIndex = registry_.indexOf(kMapDirectoryKey);
  std::vector<std::size_t> order;  // the Map Directory first: map files resolve against it
  if (mapDirIndex >= 0) order.push_back(static_cast<std::size_t>(mapDirIndex));
  for (std::size_t i = 0; i < specs.size(); ++i)
    if (static_cast<int>(i) != mapDirIndex) order.push_back(i);
  for (std::size_t i : order) {
    Entry& e = entries_[i];
    if (specs[i].required && e.origin == "default") {
      errors.emplace_back(kRankDefault, source_ + ": required key '" + specs[i].name + "' is missing");
      bad[i] = true;
      continue;
    }
    const std::string problem = parseEntry(i, e, mapDir);
    if (!problem.empty()) {
      errors.emplace_back(rank(e), where(e) + ": key '" + specs[i].name + "': " + problem);
      bad[i] = true;
    } else if (static_cast<int>(i) == mapDirIndex && specs[i].type == KeyType::Directory) {
      mapDir = e.textValue;
    }
  }
  for (const auto& rule : registry_.rules()) {
    const Entry* last = nullptr;  // the latest given key of the rule locates its message
    std::string lastName;
    bool skip = false;
    for (const auto& k : rule.keys) {
      const auto i = static_cast<std::size_t>(registry_.indexOf(k));
      skip = skip || bad[i];
      const long r = rank(entries_[i]);
      if (!last || (r != kRankDefault && (rank(*last) == kRankDefault || r > rank(*last)))) {
        last = &entries_[i];
        lastName = specs[i].name;
      }
    }
    if (skip || !last) continue;
    const std::string problem = rule.check(*this);
    if (!problem.empty())
      errors.emplace_back(rank(*last), where(*last) + ": key '" + lastName + "': " + problem);
  }
  return errors;
}

std::string RunConfig::parseEntry(std::size_t i, Entry& e, const std::string& mapDir) const {
  const KeySpec& spec = registry_.keys()[i];
  e.multiplier = 1;
  e.note.clear();
  if (e.hasMult) {
    if (spec.type != KeyType::Real && spec.type != KeyType::Integer && spec.type != KeyType::Map)
      return "a multiplier ('" + clip(e.rawMult) + "') applies only to numbers and maps";
    std::string dotted;
    if (parseNumber(e.rawMult, e.multiplier) == Number::Ok) {
    } else if (readDecimalComma(e.rawMult, dotted) == DecimalComma::Read && parseNumber(dotted, e.multiplier) == Number::Ok) {
      e.note = "multiplier '" + e.rawMult + "' has a decimal comma: read as " + dotted;
    } else {
      return "bad multiplier '" + clip(e.rawMult) + "': expected a finite number";
    }
  }
  switch (spec.type) {
    case KeyType::Flag: {
      const std::string v = lower(e.raw);
      if (v == "1" || v == "true" || v == "yes" || v == "on") e.flagValue = true;
      else if (v == "0" || v == "false" || v == "no" || v == "off") e.flagValue = false;
      else return "bad flag value '" + clip(e.raw) + "': expected 0 or 1 (or true/false, yes/no)";
      if (spec.role == KeyRole::Unmodelled && e.flagValue)
        return spec.process + " is not modelled by Talus" + (spec.plannedProcess ? " yet" : "") +
               " (OpenLISEM Hazard's process); set '" + spec.name + "=0' to run without it";
      return "";
    }
    case KeyType::Integer:
    case KeyType::Real: {
      if (e.raw.empty()) return "no value given; expected a number" + unitSuffix(spec);
      const std::string bad = readUserNumber(spec, e.raw, e.number, e.note);
      if (!bad.empty()) return bad;
      const double v = e.number * e.multiplier;
      if (spec.type == KeyType::Integer && (v != std::round(v) || std::fabs(v) > INT_MAX))
        return "value " + formatNumber(v) + " is not an integer";
      return checkRange(spec, v, e.number, e.multiplier);
    }
    case KeyType::Choice: {
      const std::string v = lower(e.raw);
      if (std::find(spec.choices.begin(), spec.choices.end(), v) != spec.choices.end()) {
        e.textValue = v;
        return "";
      }
      std::string list;
      for (std::size_t c = 0; c < spec.choices.size(); ++c) list += (c ? ", " : "") + spec.choices[c];
      return "bad choice '" + clip(e.raw) + "': expected one of " + list;
    }
    case KeyType::Text:
      e.textValue = e.raw;
      return "";
    case KeyType::Directory:
      if (!e.quoted && isWindowsDrivePath(e.raw)) {
        // A folder on a Windows drive cannot be here: its last name under the run-file's folder
        // (OpenLISEM's maps/ and res/ sit next to the run-file) when that exists, else the folder.
        const std::string sub = resolvePath(baseDir_, lastPathComponent(e.raw));
        std::error_code ec;
        const bool useSub = spec.name != kMapDirectoryKey || fs::is_directory(sub, ec);
        e.textValue = useSub ? sub : baseDir_;
        e.note = "Windows path '" + clip(e.raw) + "' taken as '" + e.textValue + "'";
        return "";
      }
      e.textValue = resolvePath(baseDir_, e.raw, e.quoted);
      return "";
    case KeyType::Map: {
      e.mapValue = MapValue{};
      e.mapValue.multiplier = e.multiplier;
      if (e.raw.empty()) return "no value given; expected a raster file or a number";
      double c = 0;
      const Number n = parseNumber(e.raw, c);
      if (n == Number::NotFinite) return "bad number '" + clip(e.raw) + "': not finite";
      std::string dotted;
      const DecimalComma comma = e.quoted || n == Number::Ok ? DecimalComma::None : readDecimalComma(e.raw, dotted);
      const bool commaNumber = comma == DecimalComma::Read && parseNumber(dotted, c) == Number::Ok;
      if (commaNumber) {
        e.note = "'" + e.raw + "' has a decimal comma: read as the uniform value " + dotted;
      } else if (comma == DecimalComma::Ambiguous) {
        return "value '" + clip(e.raw) + "': a decimal comma or a thousands separator? write the number with a "
               "decimal point or without the comma";
      }
      if ((n == Number::Ok || commaNumber) && !e.quoted) {
        e.mapValue.constant = c;
        return checkRange(spec, c * e.multiplier, c, e.multiplier);
      }
      e.mapValue.isFile = true;
      if (!e.quoted && isWindowsDrivePath(e.raw)) {  // a file on a Windows drive: its name in the Map Directory
        e.mapValue.file = resolvePath(mapDir, lastPathComponent(e.raw));
        e.note = "Windows path '" + clip(e.raw) + "' taken as '" + e.mapValue.file + "'";
      } else {
        e.mapValue.file = resolvePath(mapDir, e.raw, e.quoted);
      }
      if (!switchedOn(spec)) return "";  // a map of a process that is off is not read (warnings())
      std::error_code ec;
      if (!fs::exists(e.mapValue.file, ec)) {
        const std::string other = findIgnoringCase(e.mapValue.file);
        if (other.empty()) return "map file '" + e.mapValue.file + "' does not exist";
        e.note = (e.note.empty() ? "" : e.note + "; ") + "map file '" + e.mapValue.file + "' does not exist: using '" +
                 other + "' (same name but for letter case)";
        e.mapValue.file = other;
      }
      if (fs::is_directory(e.mapValue.file, ec))
        return "map '" + e.mapValue.file + "' is a folder, not a raster file";
      return "";
    }
  }
  return "";
}

const RunConfig::Entry& RunConfig::entry(const std::string& key, std::initializer_list<KeyType> types) const {
  const int idx = registry_.indexOf(key);
  if (idx < 0) throw std::logic_error("RunConfig: key '" + key + "' is not declared");
  const auto i = static_cast<std::size_t>(idx);
  const KeyType type = registry_.keys()[i].type;
  if (types.size() && std::find(types.begin(), types.end(), type) == types.end())
    throw std::logic_error("RunConfig: key '" + key + "' is a " + keyTypeName(type) + " key, not read as " +
                           keyTypeName(*types.begin()));
  return entries_[i];
}

double RunConfig::real(const std::string& key) const {
  const Entry& e = entry(key, {KeyType::Real, KeyType::Integer});
  return e.number * e.multiplier;
}

int RunConfig::integer(const std::string& key) const {
  const Entry& e = entry(key, {KeyType::Integer});
  return static_cast<int>(std::lround(e.number * e.multiplier));
}

bool RunConfig::flag(const std::string& key) const { return entry(key, {KeyType::Flag}).flagValue; }
std::string RunConfig::choice(const std::string& key) const {
  return entry(key, {KeyType::Choice}).textValue;
}
std::string RunConfig::text(const std::string& key) const { return entry(key, {KeyType::Text}).textValue; }
std::string RunConfig::directory(const std::string& key) const {
  return entry(key, {KeyType::Directory}).textValue;
}
MapValue RunConfig::map(const std::string& key) const { return entry(key, {KeyType::Map}).mapValue; }
bool RunConfig::isDefault(const std::string& key) const { return entry(key, {}).origin == "default"; }
std::string RunConfig::origin(const std::string& key) const { return entry(key, {}).origin; }

std::string RunConfig::echo() const {
  const auto& specs = registry_.keys();
  std::vector<std::string> sections;
  for (const auto& k : specs)
    if (k.role == KeyRole::Used && std::find(sections.begin(), sections.end(), k.section) == sections.end())
      sections.push_back(k.section);
  std::ostringstream os;
  if (!header_.empty()) os << header_ << "\n";
  os << "# Talus configuration resolved from " << source_ << ": every key Talus uses, paths absolute.\n";
  for (const auto& section : sections) {
    os << "\n[" << (section.empty() ? "Other" : section) << "]\n";
    for (std::size_t i = 0; i < specs.size(); ++i) {
      const KeySpec& spec = specs[i];
      const Entry& e = entries_[i];
      // The OpenLISEM keys Talus does not use are left out: the resolved file is what the run uses.
      if (spec.section != section || spec.role != KeyRole::Used) continue;
      os << "# " << (spec.help.empty() ? spec.name : spec.help);
      if (!spec.unit.empty()) os << " [" << spec.unit << "]";
      os << " (" << (e.origin == "default" ? "default" : "from " + e.origin) << ")\n";
      os << spec.name << "=" << valueText(spec.name) << "\n";
    }
  }
  return os.str();
}

std::string RunConfig::valueText(const std::string& key) const {
  const Entry& e = entry(key, {});
  const KeySpec& spec = *registry_.find(key);
  std::string value = e.raw;
  // A value read in another notation (decimal comma, day:minute) is written as the number it is.
  if ((spec.type == KeyType::Real || spec.type == KeyType::Integer) && !e.note.empty()) value = formatNumber(e.number);
  if (spec.type == KeyType::Flag) value = e.flagValue ? "1" : "0";
  if (spec.type == KeyType::Choice || spec.type == KeyType::Directory) value = e.textValue;
  if (spec.type == KeyType::Map) value = e.mapValue.isFile ? e.mapValue.file : (e.note.empty() ? e.raw : formatNumber(e.mapValue.constant));
  std::string out = quoteForEcho(value);
  double plain = 0;
  if (e.hasMult) out += "=" + (parseNumber(e.rawMult, plain) == Number::Ok ? e.rawMult : formatNumber(e.multiplier));
  return out;
}

bool RunConfig::switchedOn(const KeySpec& spec) const {
  if (spec.enabledBy.empty()) return true;
  const int idx = registry_.indexOf(spec.enabledBy);
  if (idx < 0) throw std::logic_error("RunConfig: key '" + spec.name + "' is enabled by undeclared '" + spec.enabledBy + "'");
  const std::string v = lower(entries_[static_cast<std::size_t>(idx)].raw);
  return v == "1" || v == "true" || v == "yes" || v == "on";
}

}  // namespace talus::io
