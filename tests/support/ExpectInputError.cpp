#include "support/ExpectInputError.hpp"

#include <gtest/gtest.h>

#include <exception>

#include "core/Error.hpp"

namespace talus::test {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string expectInputError(const std::function<void()>& fn, std::initializer_list<std::string> parts) {
  try {
    fn();
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const std::string& part : parts)
      EXPECT_TRUE(contains(what, part)) << "missing '" << part << "' in: " << what.substr(0, 2000);
    return what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected talus::InputError, got another exception: " << e.what();
    return "";
  }
  ADD_FAILURE() << "expected talus::InputError, nothing was thrown";
  return "";
}

}  // namespace talus::test
