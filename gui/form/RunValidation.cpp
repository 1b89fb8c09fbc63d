#include "form/RunValidation.hpp"

#include <sstream>

#include "core/Error.hpp"

namespace talus::gui {

ValidationResult validateDocument(const RunFileDocument& doc) {
  ValidationResult r;
  const std::string name = doc.path().empty() ? "<new run-file>" : doc.path();
  try {
    r.config = io::RunConfig::fromText(doc.text(), doc.baseDir(), doc.keys(), name);
  } catch (const InputError& e) {
    assignErrors(e.what(), doc.keys(), r);
  }
  return r;
}

std::string describeProblems(const ValidationResult& result) {
  std::string all;
  for (const auto& [key, text] : result.fieldErrors) all += (all.empty() ? "" : "\n") + text;
  for (const auto& g : result.generalErrors) all += (all.empty() ? "" : "\n") + g;
  return all;
}

void assignErrors(const std::string& message, const io::KeyRegistry& keys, ValidationResult& result) {
  std::istringstream in(message);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const std::size_t at = line.find("key '");
    std::string key;
    if (at != std::string::npos) {
      const std::size_t end = line.find('\'', at + 5);
      if (end != std::string::npos) key = line.substr(at + 5, end - at - 5);
    }
    if (!key.empty() && keys.find(key)) {
      std::string& text = result.fieldErrors[io::normalizeKeyName(key)];
      text += (text.empty() ? "" : "\n") + line;
    } else {
      result.generalErrors.push_back(line);
    }
  }
}

}  // namespace talus::gui
