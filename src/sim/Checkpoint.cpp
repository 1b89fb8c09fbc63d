#include "sim/Checkpoint.hpp"

#include <cstring>
#include <fstream>
#include <sstream>

#include "core/Error.hpp"
#include "core/FileWrite.hpp"

namespace talus::sim {
namespace {

// Version 4 adds the work of friction and drag, version 3 the cumulative rain and infiltration,
// version 2 the particle state; version 1 to 3 files still read (no work; version 1 and 2 no rain,
// no infiltration; version 1 no particles either).
constexpr char kMagic[8] = {'T', 'A', 'L', 'U', 'S', 'C', 'K', '4'};
constexpr char kMagicV3[8] = {'T', 'A', 'L', 'U', 'S', 'C', 'K', '3'};
constexpr char kMagicV2[8] = {'T', 'A', 'L', 'U', 'S', 'C', 'K', '2'};
constexpr char kMagicV1[8] = {'T', 'A', 'L', 'U', 'S', 'C', 'K', '1'};

template <class T>
void put(std::ostream& o, const T& v) {
  o.write(reinterpret_cast<const char*>(&v), sizeof v);
}
void putString(std::ostream& o, const std::string& s) {
  put<uint64_t>(o, s.size());
  o.write(s.data(), static_cast<std::streamsize>(s.size()));
}

struct Reader {
  std::ifstream in;
  std::string path;
  template <class T>
  T get() {
    T v{};
    if (!in.read(reinterpret_cast<char*>(&v), sizeof v)) fail();
    return v;
  }
  std::string getString(uint64_t limit) {
    const uint64_t n = get<uint64_t>();
    if (n > limit) fail();
    std::string s(n, '\0');
    if (n && !in.read(s.data(), static_cast<std::streamsize>(n))) fail();
    return s;
  }
  [[noreturn]] void fail() { throw InputError("checkpoint '" + path + "' is truncated or corrupt"); }
};

}  // namespace

void writeCheckpoint(const std::string& path, const Checkpoint& c) {
  std::ostringstream o(std::ios::binary);
  o.write(kMagic, sizeof kMagic);
  putString(o, c.precision);
  put(o, c.nx);
  put(o, c.ny);
  put(o, c.time);
  put(o, c.steps);
  put(o, c.reportIndex);
  put(o, c.initialVolume);
  put(o, c.totalOutflow);
  put(o, c.totalRain);
  put(o, c.totalInfiltrated);
  put(o, c.totalSourceWork);
  put(o, c.elapsedWall);
  putString(o, c.seriesIndex);
  putString(o, std::string(c.state.begin(), c.state.end()));
  putString(o, std::string(c.particleState.begin(), c.particleState.end()));
  o.write(kMagic, sizeof kMagic);  // trailer: a complete file ends with the magic again
  writeFileAtomically(path, o.str());  // the previous checkpoint stays until this one is complete
}

Checkpoint readCheckpoint(const std::string& path) {
  Reader r{std::ifstream(path, std::ios::binary), path};
  if (!r.in) throw InputError("no checkpoint '" + path + "' (was the run started with a checkpoint interval?)");
  char magic[8];
  if (!r.in.read(magic, sizeof magic)) throw InputError("'" + path + "' is not a Talus checkpoint");
  const bool v1 = std::memcmp(magic, kMagicV1, sizeof magic) == 0;
  const bool v2 = std::memcmp(magic, kMagicV2, sizeof magic) == 0;
  const bool v3 = std::memcmp(magic, kMagicV3, sizeof magic) == 0;
  if (!v1 && !v2 && !v3 && std::memcmp(magic, kMagic, sizeof magic) != 0)
    throw InputError("'" + path + "' is not a Talus checkpoint");
  const char* version = v1 ? kMagicV1 : v2 ? kMagicV2 : v3 ? kMagicV3 : kMagic;
  Checkpoint c;
  c.precision = r.getString(16);
  c.nx = r.get<int32_t>();
  c.ny = r.get<int32_t>();
  c.time = r.get<double>();
  c.steps = r.get<int64_t>();
  c.reportIndex = r.get<int32_t>();
  c.initialVolume = r.get<double>();
  c.totalOutflow = r.get<double>();
  if (!v1 && !v2) {
    c.totalRain = r.get<double>();
    c.totalInfiltrated = r.get<double>();
  }
  if (!v1 && !v2 && !v3) c.totalSourceWork = r.get<double>();
  c.elapsedWall = r.get<double>();
  c.seriesIndex = r.getString(1ull << 30);
  const std::string state = r.getString(1ull << 40);
  c.state.assign(state.begin(), state.end());
  if (!v1) {
    const std::string particles = r.getString(1ull << 40);
    c.particleState.assign(particles.begin(), particles.end());
  }
  if (!r.in.read(magic, sizeof magic) || std::memcmp(magic, version, sizeof magic) != 0) r.fail();
  return c;
}

}  // namespace talus::sim
