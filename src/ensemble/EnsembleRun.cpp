// Sequential, resumable running of ensemble members (see EnsembleRun.hpp).
#include "ensemble/EnsembleRun.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "core/Error.hpp"
#include "core/FileWrite.hpp"
#include "ensemble/Json.hpp"
#include "ensemble/Sampling.hpp"
#include "sim/Scene.hpp"
#include "sim/Simulation.hpp"

namespace talus::ensemble {
namespace fs = std::filesystem;

namespace {

constexpr const char* kRecord = "member.json";

std::string number17(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

/// A path as a run-file value: quoted, with \ and " escaped (RunConfig reads it back verbatim).
std::string quoted(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    o += c;
  }
  return o + "\"";
}

std::string readText(const fs::path& p) {
  std::FILE* f = std::fopen(p.c_str(), "rb");
  if (!f) return "";
  std::string s;
  char buf[4096];
  for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) s.append(buf, n);
  std::fclose(f);
  return s;
}

std::string hostName() {
  char h[256] = {0};
  if (::gethostname(h, sizeof h - 1) != 0 || !h[0]) return "host";
  std::string s(h);
  for (char& c : s)
    if (c == '/' || c == '.') c = '_';
  return s;
}

/// True when no process holds the run lock of a partial folder (its run ended, however it ended).
bool abandoned(const fs::path& partial) {
  const std::string lock = (partial / ".talus-lock").string();
  const int fd = ::open(lock.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return true;  // the run never got as far as locking: nobody is in it
  const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  ::close(fd);
  return free;
}

/// Removes the abandoned partial folders of a member; returns true when one is still in use.
bool clearPartials(const fs::path& membersDir, const std::string& name) {
  bool inUse = false;
  std::error_code ec;
  const std::string prefix = "." + name + ".partial-";
  for (const fs::directory_entry& e : fs::directory_iterator(membersDir, ec)) {
    const std::string f = e.path().filename().string();
    if (f.compare(0, prefix.size(), prefix) != 0) continue;
    if (abandoned(e.path())) fs::remove_all(e.path(), ec);
    else inUse = true;
  }
  return inUse;
}

std::string recordJson(long long member, const std::vector<std::string>& assignments, double wall) {
  std::ostringstream o;
  o << "{\n  \"member\": " << member << ",\n  \"name\": " << jsonQuote(memberName(member)) << ",\n  \"assignments\": [";
  for (std::size_t k = 0; k < assignments.size(); ++k) o << (k ? ", " : "") << jsonQuote(assignments[k]);
  o << "],\n  \"wall_s\": " << number17(wall) << "\n}\n";
  return o.str();
}

}  // namespace

std::string memberName(long long member) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "m%04lld", member);
  return buf;
}

std::string memberDir(const EnsembleSpec& spec, long long member) {
  return (fs::path(spec.outputDir) / "members" / memberName(member)).string();
}

bool memberComplete(const EnsembleSpec& spec, long long member) {
  std::error_code ec;
  return fs::is_regular_file(fs::path(memberDir(spec, member)) / kRecord, ec);
}

std::vector<std::string> memberAssignments(const EnsembleSpec& spec, const io::RunConfig& base, long long member) {
  std::vector<std::string> out;
  const std::vector<double> values = memberValues(spec, member);
  for (std::size_t k = 0; k < spec.parameters.size(); ++k) {
    const Parameter& p = spec.parameters[k];
    const io::KeySpec* key = base.registry().find(p.key);
    auto where = [&] { return spec.file + ":" + std::to_string(p.line) + ": key '" + p.key + "': "; };
    if (!key) throw InputError(where() + "not a key of the run-file format (talus keys lists them)");
    const std::string name = key->name;
    if (p.mode == ApplyMode::Value) {
      if (key->type != io::KeyType::Real && key->type != io::KeyType::Integer && key->type != io::KeyType::Map)
        throw InputError(where() + "is a " + io::keyTypeName(key->type) + " key; only numbers and maps can vary");
      out.push_back(name + "=" + number17(values[k]));
      continue;
    }
    // Scale: the draw multiplies the value of the base configuration.
    if (key->type == io::KeyType::Map) {
      const io::MapValue m = base.map(name);
      const std::string value = m.isFile ? quoted(m.file) : number17(m.constant);
      out.push_back(name + "=" + value + "=" + number17(m.multiplier * values[k]));
    } else if (key->type == io::KeyType::Real) {
      out.push_back(name + "=" + number17(base.real(name) * values[k]));
    } else {
      throw InputError(where() + "'scale' needs a real or map key; this one is " + io::keyTypeName(key->type));
    }
  }
  return out;
}

void checkMemberRecord(const EnsembleSpec& spec, long long member, const std::vector<std::string>& expected) {
  const fs::path record = fs::path(memberDir(spec, member)) / kRecord;
  const JsonValue v = JsonValue::parse(readText(record), record.string());
  const JsonValue* a = v.find("assignments");
  std::vector<std::string> got;
  if (a && a->type() == JsonValue::Type::Array)
    for (const JsonValue& x : a->array()) got.push_back(x.string());
  if (got != expected) {
    std::string g, e;
    for (const auto& s : got) g += " " + s;
    for (const auto& s : expected) e += " " + s;
    throw InputError("member " + memberName(member) + " in '" + spec.outputDir + "' was run with" + g +
                     " but the ensemble file now gives" + e +
                     "; the file changed since: give a new Output Directory (or remove the old one)");
  }
}

RunOutcome runMembers(const EnsembleSpec& spec, const io::RunConfig& base, const std::vector<long long>& members,
                      const RunOptions& options) {
  RunOutcome outcome;
  const fs::path membersDir = fs::path(spec.outputDir) / "members";
  fs::create_directories(membersDir);
  const std::string tag = hostName() + "-" + std::to_string(::getpid());
  int position = 0;
  for (const long long m : members) {
    ++position;
    const std::string name = memberName(m);
    const std::vector<std::string> assignments = memberAssignments(spec, base, m);
    // Partial folders whose run has ended (killed, or beaten by another process) are removed.
    const bool runningElsewhere = clearPartials(membersDir, name);
    if (memberComplete(spec, m)) {
      checkMemberRecord(spec, m, assignments);
      ++outcome.skipped;
      continue;
    }
    if (runningElsewhere) {
      if (!options.quiet) std::fprintf(stderr, "talus: %s%s is being run by another process; skipped\n", options.label.c_str(), name.c_str());
      ++outcome.skipped;
      continue;
    }
    // A member folder without its record is not finished (never written so by Talus): rerun it.
    std::error_code ec;
    fs::remove_all(memberDir(spec, m), ec);
    io::RunConfig config = base;
    try {
      for (const std::string& a : assignments) config.set(a);
      if (!options.device.empty()) config.set("Device=" + options.device);
    } catch (const InputError& e) {
      throw InputError("member " + name + ": " + e.what());
    }
    const fs::path partial = membersDir / ("." + name + ".partial-" + tag);
    const auto start = std::chrono::steady_clock::now();
    try {
      const sim::Scene scene = sim::loadScene(config);
      sim::requireMaterial(scene, config);
      {
        sim::Simulation simulation(scene, config, partial.string(), sim::OutputMode::New);
        simulation.run();
      }  // the simulation (and its folder lock) ends before the folder is renamed
    } catch (const SimulationError& e) {
      outcome.failures.push_back(name + ": " + e.what());
      if (!options.quiet) std::fprintf(stderr, "talus: %s%s failed: %s\n", options.label.c_str(), name.c_str(), e.what());
      continue;
    } catch (const InputError& e) {
      throw InputError("member " + name + ": " + e.what());
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeFileAtomically((partial / kRecord).string(), recordJson(m, assignments, wall));
    fs::rename(partial, memberDir(spec, m), ec);
    if (ec) {
      // Another process finished the same member first (the target exists): keep theirs.
      if (memberComplete(spec, m)) fs::remove_all(partial, ec);
      else throw IoError("cannot rename '" + partial.string() + "' to '" + memberDir(spec, m) + "': " + ec.message());
    }
    ++outcome.ran;
    if (!options.quiet) {
      std::string set;
      for (const std::string& a : assignments) set += "  " + a;
      std::fprintf(stderr, "talus: %s%s (%d/%zu) done in %.2f s:%s\n", options.label.c_str(), name.c_str(), position,
                   members.size(), wall, set.c_str());
    }
  }
  return outcome;
}

}  // namespace talus::ensemble
