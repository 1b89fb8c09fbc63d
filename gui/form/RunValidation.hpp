// Validation of an edited run-file before a run: RunConfig parses and checks the document's text,
// and every problem is assigned to the form field of the key it names (or listed as general).
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "form/RunFileDocument.hpp"
#include "io/RunConfig.hpp"

namespace talus::gui {

struct ValidationResult {
  std::optional<io::RunConfig> config;                   ///< set when the run-file is valid
  std::map<std::string, std::string> fieldErrors;        ///< normalised key name -> problems
  std::vector<std::string> generalErrors;                ///< problems that name no declared key
  bool ok() const { return config.has_value(); }
};

/// Parses and validates the document's text as RunConfig does for `talus run`.
ValidationResult validateDocument(const RunFileDocument& doc);

/// Every problem of a result, one per line (field problems first), for the log and the terminal.
std::string describeProblems(const ValidationResult& result);

/// Adds the problems of an InputError message (one per line) to `result`: a line naming "key 'X'"
/// of a declared key goes to that field, any other line to the general list.
void assignErrors(const std::string& message, const io::KeyRegistry& keys, ValidationResult& result);

}  // namespace talus::gui
