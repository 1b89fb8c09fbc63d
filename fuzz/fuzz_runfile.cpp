// libFuzzer target: run-file text -> talus::io::RunConfig::fromText against Talus's key registry.
// Contract checked: fromText either returns a configuration or throws talus::InputError; on success
// every accessor of every declared key (by its type) returns without throwing, echo() parses back
// to the same values, and set() with any of the input's first lines either applies or throws
// InputError. Anything else (another exception, a sanitizer report, a crash) is a finding.
//
// The base folder holds empty files dem.tif, water.tif and h.map and a folder maps/ so that run-files
// naming them get past the "map file exists" check, as real run-files do.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>
#include <typeinfo>

#include <stdlib.h>  // mkdtemp

#include "core/Error.hpp"
#include "io/KeyRegistry.hpp"
#include "io/RunConfig.hpp"
#include "sim/RunKeys.hpp"

namespace fs = std::filesystem;
using talus::io::KeyType;
using talus::io::RunConfig;

namespace {

std::string g_baseDir;

[[noreturn]] void fail(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz_runfile: %s: %s\n", what, detail.c_str());
  std::abort();
}

/// Reads every declared key through the accessor of its type; any exception is a finding.
void readAll(const RunConfig& c) {
  for (const talus::io::KeySpec& k : c.registry().keys()) {
    try {
      (void)c.isDefault(k.name);
      (void)c.origin(k.name);
      switch (k.type) {
        case KeyType::Flag: (void)c.flag(k.name); break;
        case KeyType::Integer: (void)c.integer(k.name); (void)c.real(k.name); break;
        case KeyType::Real: (void)c.real(k.name); break;
        case KeyType::Choice: (void)c.choice(k.name); break;
        case KeyType::Text: (void)c.text(k.name); break;
        case KeyType::Directory: (void)c.directory(k.name); break;
        case KeyType::Map: {
          const talus::io::MapValue m = c.map(k.name);
          if (m.isFile && m.file.empty()) fail("map key with an empty file name", k.name);
          break;
        }
      }
    } catch (const std::exception& e) {
      fail("accessor threw", k.name + ": " + typeid(e).name() + ": " + e.what());
    }
  }
}

/// Compares every key Talus uses of two configurations by value (the documented echo round trip:
/// echo() writes the keys Talus uses; the OpenLISEM keys it accepts without reading are not echoed).
void sameValues(const RunConfig& a, const RunConfig& b) {
  for (const talus::io::KeySpec& k : a.registry().keys()) {
    if (k.role != talus::io::KeyRole::Used) continue;
    bool same = true;
    switch (k.type) {
      case KeyType::Flag: same = a.flag(k.name) == b.flag(k.name); break;
      case KeyType::Integer:
      case KeyType::Real: same = a.real(k.name) == b.real(k.name); break;
      case KeyType::Choice: same = a.choice(k.name) == b.choice(k.name); break;
      case KeyType::Text: same = a.text(k.name) == b.text(k.name); break;
      case KeyType::Directory: same = a.directory(k.name) == b.directory(k.name); break;
      case KeyType::Map: {
        const auto ma = a.map(k.name), mb = b.map(k.name);
        same = ma.isFile == mb.isFile && ma.file == mb.file && ma.constant == mb.constant &&
               ma.multiplier == mb.multiplier;
        break;
      }
    }
    if (!same) fail("echo() does not parse back to the same value", k.name);
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  char pattern[] = "/tmp/talus_fuzz_runfile_XXXXXX";
  const char* dir = ::mkdtemp(pattern);
  if (dir == nullptr) {
    std::perror("fuzz_runfile: mkdtemp");
    std::exit(1);
  }
  g_baseDir = dir;
  for (const char* f : {"dem.tif", "water.tif", "h.map", "maps/dem.tif"}) {
    fs::create_directories((fs::path(g_baseDir) / f).parent_path());
    std::ofstream(fs::path(g_baseDir) / f) << "x";
  }
  std::atexit([] {
    std::error_code ec;
    fs::remove_all(g_baseDir, ec);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 64 * 1024) return 0;  // run-files are small; keep the executions fast
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto& keys = talus::talusRunKeys();
  try {
    RunConfig c = RunConfig::fromText(text, g_baseDir, keys, "fuzz.run");
    readAll(c);
    const std::string echoed = c.echo();
    try {
      const RunConfig again = RunConfig::fromText(echoed, g_baseDir, keys, "echo.run");
      sameValues(c, again);
    } catch (const talus::InputError& e) {
      fail("echo() of a valid configuration does not parse", std::string(e.what()) + "\n--- echo ---\n" + echoed);
    }
    // Each of the first lines as a --set override.
    std::size_t start = 0;
    for (int n = 0; n < 4 && start < text.size(); ++n) {
      std::size_t end = text.find('\n', start);
      if (end == std::string::npos) end = text.size();
      try {
        c.set(text.substr(start, end - start));
        readAll(c);
      } catch (const talus::InputError&) {
      }
      start = end + 1;
    }
  } catch (const talus::InputError&) {
    // the documented outcome for bad input
  } catch (const std::exception& e) {
    fail("unexpected exception", std::string(typeid(e).name()) + ": " + e.what());
  }
  return 0;
}
