// Conversion of an OpenLISEM Hazard run-file into a Talus-style one (`talus convert-runfile`):
// only the keys Talus uses, in Talus's sections, with values as Talus reads them (numbers with a
// decimal point, minutes instead of day:minute, absolute paths); what was left out or read
// differently is listed.
#pragma once
#include <string>
#include <vector>

#include "io/KeyRegistry.hpp"

namespace talus::io {

/// A converted run-file and what the conversion did.
struct Conversion {
  std::string text;                 ///< the Talus run-file
  std::vector<std::string> report;  ///< one line per key dropped or changed (and a count of the rest)
};

/// Reads and validates the run-file at inPath (throws talus::InputError as RunConfig::load does,
/// e.g. for a process Talus does not model that is switched on) and converts it.
Conversion convertRunFile(const std::string& inPath, const KeyRegistry& keys);

}  // namespace talus::io
