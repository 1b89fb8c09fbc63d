// Parsing and checking of ensemble files (format in docs/ensembles.md). Problems are collected and
// reported together, each with the file, line and key.
#include "ensemble/EnsembleFile.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/Error.hpp"
#include "io/KeyRegistry.hpp"
#include "core/Text.hpp"

namespace talus::ensemble {
namespace fs = std::filesystem;

namespace {

/// Ensemble files are a few hundred bytes; this stops `talus ensemble /dev/urandom`.
constexpr std::uintmax_t kMaxFileBytes = 1u << 20;
constexpr long long kMaxMembers = 1000000;

bool toNumber(const std::string& t, double& v) {
  if (t.empty()) return false;
  const char* b = t.data() + (t[0] == '+' ? 1 : 0);
  const auto [end, ec] = std::from_chars(b, t.data() + t.size(), v);
  return end == t.data() + t.size() && ec == std::errc() && std::isfinite(v);
}

std::vector<std::string> words(const std::string& s) {
  std::istringstream in(s);
  std::vector<std::string> w;
  for (std::string x; in >> x;) w.push_back(x);
  return w;
}

/// Collects problems; each becomes one line of the InputError.
struct Problems {
  std::string file;
  std::vector<std::string> lines;
  void add(int line, const std::string& key, const std::string& what) {
    lines.push_back(file + ":" + std::to_string(line) + ": " + (key.empty() ? "" : "key '" + key + "': ") + what);
  }
};

/// Reads a list of finite numbers; "" and a problem on the first word that is not one.
std::string numbers(const std::string& value, std::vector<double>& out) {
  out.clear();
  for (const std::string& w : words(value)) {
    double v = 0;
    if (!toNumber(w, v)) return "'" + w + "' is not a finite number";
    out.push_back(v);
  }
  return "";
}

/// Parses "[scale] DISTRIBUTION NUMBERS..." into p; returns "" or the problem.
std::string parseParameter(const std::string& value, Parameter& p) {
  std::vector<std::string> w = words(value);
  if (!w.empty() && lower(w[0]) == "scale") {
    p.mode = ApplyMode::Scale;
    w.erase(w.begin());
  }
  if (w.empty()) return "no distribution; expected e.g. 'uniform 0.02 0.08' (docs/ensembles.md)";
  const std::string kind = lower(w[0]);
  std::vector<double> n;
  for (std::size_t k = 1; k < w.size(); ++k) {
    double v = 0;
    if (!toNumber(w[k], v)) return "'" + w[k] + "' is not a finite number";
    n.push_back(v);
  }
  auto two = [&](const char* what) -> std::string {
    if (n.size() != 2) return kind + " takes two numbers (" + what + "), got " + std::to_string(n.size());
    p.a = n[0];
    p.b = n[1];
    return "";
  };
  if (kind == "uniform") {
    p.distribution = Distribution::Uniform;
    if (auto e = two("lower and upper bound"); !e.empty()) return e;
    if (!(p.a < p.b)) return "uniform needs lower < upper bound";
  } else if (kind == "normal" || kind == "lognormal") {
    p.distribution = kind == "normal" ? Distribution::Normal : Distribution::LogNormal;
    if (auto e = two(kind == "normal" ? "mean and standard deviation" : "mean and standard deviation of ln X");
        !e.empty())
      return e;
    if (!(p.b > 0)) return kind + " needs a standard deviation > 0";
  } else if (kind == "list") {
    p.distribution = Distribution::List;
    if (n.empty()) return "list needs at least one value";
    p.values = n;
  } else if (kind == "grid") {
    p.distribution = Distribution::Grid;
    if (n.size() != 3) return "grid takes three numbers (first, last, count), got " + std::to_string(n.size());
    if (n[2] < 1 || n[2] != std::floor(n[2]) || n[2] > 100000) return "grid count must be a whole number in 1..100000";
    const int count = static_cast<int>(n[2]);
    p.a = n[0];
    p.b = n[1];
    for (int k = 0; k < count; ++k) p.values.push_back(count == 1 ? n[0] : n[0] + (n[1] - n[0]) * k / (count - 1));
  } else {
    return "unknown distribution '" + w[0] + "'; expected uniform, normal, lognormal, list or grid";
  }
  return "";
}

}  // namespace

long long EnsembleSpec::designSize() const {
  long long n = 1;
  for (const Parameter& p : parameters)
    if (p.isDesign()) n *= static_cast<long long>(p.values.size());
  return n;
}

std::string distributionName(Distribution d) {
  switch (d) {
    case Distribution::Uniform: return "uniform";
    case Distribution::Normal: return "normal";
    case Distribution::LogNormal: return "lognormal";
    case Distribution::List: return "list";
    case Distribution::Grid: return "grid";
  }
  return "?";
}

EnsembleSpec parseEnsembleText(const std::string& text, const std::string& baseDir, const std::string& displayName) {
  EnsembleSpec s;
  s.file = displayName;
  Problems problems{displayName, {}};
  const fs::path base(baseDir);
  auto absolute = [&](const std::string& p) { return fs::absolute(base / p).lexically_normal().string(); };
  std::string section;
  int membersLine = 0, rankByLine = 0;
  bool membersGiven = false;
  std::istringstream in(text);
  std::string raw;
  for (int lineNo = 1; std::getline(in, raw); ++lineNo) {
    std::string line = trim(raw);
    if (line.empty() || line[0] == '#' || line[0] == ';') continue;
    if (line.front() == '[') {
      if (line.back() != ']') {
        problems.add(lineNo, "", "section header '" + line + "' has no closing ']'");
        continue;
      }
      section = io::normalizeKeyName(line.substr(1, line.size() - 2));
      if (section != "talus ensemble" && section != "ensemble" && section != "parameters" && section != "maps" &&
          section != "calibration")
        problems.add(lineNo, "", "unknown section '" + line + "'; expected [Ensemble], [Parameters], [Maps] or [Calibration]");
      continue;
    }
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) {
      problems.add(lineNo, "", "no '=' in '" + line + "'; expected Key=Value");
      continue;
    }
    const std::string keyText = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
    const std::string key = io::normalizeKeyName(keyText);
    auto bad = [&](const std::string& what) { problems.add(lineNo, keyText, what); };
    std::vector<double> n;
    auto oneNumber = [&](double& out) {
      if (const std::string e = numbers(value, n); !e.empty()) return bad(e);
      if (n.size() != 1) return bad("expected one number, got '" + value + "'");
      out = n[0];
    };
    auto numberList = [&](std::vector<double>& out) {
      if (const std::string e = numbers(value, out); !e.empty()) bad(e);
    };
    if (section == "parameters") {
      Parameter p;
      p.key = keyText;
      p.line = lineNo;
      if (const std::string e = parseParameter(value, p); !e.empty()) bad(e);
      else {
        for (const Parameter& q : s.parameters)
          if (io::normalizeKeyName(q.key) == key) bad("given twice (also at line " + std::to_string(q.line) + ")");
        s.parameters.push_back(p);
      }
      continue;
    }
    if (section.empty()) {
      bad("outside a section; start the file with [Ensemble]");
      continue;
    }
    if (key == "run file") {
      if (value.empty()) bad("empty");
      else s.runFile = absolute(value);
    } else if (key == "output directory") {
      if (value.empty()) bad("empty");
      else s.outputDir = absolute(value);
    } else if (key == "members") {
      double m = 0;
      oneNumber(m);
      if (m < 1 || m != std::floor(m) || m > kMaxMembers) bad("must be a whole number in 1.." + std::to_string(kMaxMembers));
      else s.members = static_cast<int>(m);
      membersGiven = true;
      membersLine = lineNo;
    } else if (key == "seed") {
      double v = 0;
      oneNumber(v);
      if (v < 0 || v != std::floor(v) || v > 9.007199254740992e15) bad("must be a whole number in 0..2^53");
      else s.seed = static_cast<unsigned long long>(v);
    } else if (key == "thickness thresholds") {
      numberList(s.thicknessThresholds);
    } else if (key == "speed thresholds") {
      numberList(s.speedThresholds);
    } else if (key == "arrival times") {
      numberList(s.arrivalTimes);
    } else if (key == "percentiles") {
      numberList(s.percentiles);
      for (double q : s.percentiles)
        if (q < 0 || q > 100) bad("percentiles must lie in 0..100");
    } else if (key == "affected threshold") {
      oneNumber(s.affectedThreshold);
      if (s.affectedThreshold < 0) bad("must be >= 0");
    } else if (key == "observed map") {
      if (value.empty()) bad("empty");
      else s.observedMap = absolute(value);
    } else if (key == "observed threshold") {
      oneNumber(s.observedThreshold);
    } else if (key == "observed runout") {
      if (const std::string e = numbers(value, n); !e.empty()) bad(e);
      else if (n.size() != 2) bad("expected the world coordinates 'x y' of the observed runout point");
      else {
        s.hasObservedRunout = true;
        s.observedX = n[0];
        s.observedY = n[1];
      }
    } else if (key == "rank by") {
      s.rankBy = lower(value);
      rankByLine = lineNo;
      if (s.rankBy != "jaccard" && s.rankBy != "d2pc" && s.rankBy != "runout")
        bad("expected jaccard, d2pc or runout, got '" + value + "'");
    } else {
      bad("unknown key (docs/ensembles.md lists the keys)");
    }
  }
  // Rules over several keys.
  if (s.runFile.empty()) problems.add(0, "Run File", "required: the base run-file every member starts from");
  else if (!fs::is_regular_file(s.runFile)) problems.add(0, "Run File", "no such file '" + s.runFile + "'");
  if (s.parameters.empty()) problems.add(0, "", "no [Parameters]: an ensemble needs at least one uncertain key");
  const long long design = s.designSize();
  bool random = false;
  for (const Parameter& p : s.parameters) random = random || !p.isDesign();
  if (design > kMaxMembers) problems.add(0, "", "the design has " + std::to_string(design) + " combinations (more than " + std::to_string(kMaxMembers) + ")");
  if (!membersGiven) {
    if (random || s.parameters.empty()) problems.add(0, "Members", "required when a parameter is drawn at random");
    else s.members = static_cast<int>(design);
  } else if (s.members > 0 && s.members % design != 0) {
    problems.add(membersLine, "Members", std::to_string(s.members) + " is not a multiple of the " +
                                             std::to_string(design) + " combinations of the list/grid parameters");
  }
  if (s.outputDir.empty()) s.outputDir = absolute(fs::path(displayName).stem().string() + "_ensemble");
  const bool observed = !s.observedMap.empty();
  if (s.rankBy.empty()) s.rankBy = observed ? "jaccard" : s.hasObservedRunout ? "runout" : "";
  if ((s.rankBy == "jaccard" || s.rankBy == "d2pc") && !observed)
    problems.add(rankByLine, "Rank By", s.rankBy + " needs an Observed Map");
  if (s.rankBy == "runout" && !s.hasObservedRunout)
    problems.add(rankByLine, "Rank By", "runout needs an Observed Runout point");
  if (observed && !fs::is_regular_file(s.observedMap)) problems.add(0, "Observed Map", "no such file '" + s.observedMap + "'");
  if (!problems.lines.empty()) {
    std::string msg = "ensemble file has " + std::to_string(problems.lines.size()) + " problem(s):";
    for (std::string& l : problems.lines) {
      // Rules without a line name the file alone.
      const std::string zero = displayName + ":0: ";
      if (l.compare(0, zero.size(), zero) == 0) l = displayName + ": " + l.substr(zero.size());
      msg += "\n  " + l;
    }
    throw InputError(msg);
  }
  return s;
}

EnsembleSpec loadEnsembleFile(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError("ensemble file '" + path + "' does not exist or is not a file");
  if (fs::file_size(path, ec) > kMaxFileBytes)
    throw InputError("ensemble file '" + path + "' is larger than 1 MiB; is it the right file?");
  std::ifstream f(path, std::ios::binary);
  if (!f) throw InputError("cannot read ensemble file '" + path + "'");
  std::ostringstream text;
  text << f.rdbuf();
  const fs::path abs = fs::absolute(path).lexically_normal();
  EnsembleSpec s = parseEnsembleText(text.str(), abs.parent_path().string(), path);
  s.file = abs.string();
  return s;
}

}  // namespace talus::ensemble
