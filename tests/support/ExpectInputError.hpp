// The check most hostile-input tests make: a call must throw talus::InputError whose message names
// the file, key, line or cell at fault.
#pragma once
#include <functional>
#include <initializer_list>
#include <string>

namespace talus::test {

/// True when part occurs in s.
bool contains(const std::string& s, const std::string& part);

/// Runs fn and expects a talus::InputError whose message contains every one of parts (a GoogleTest
/// failure otherwise: another exception, or none). Returns the message ("" when none was thrown).
std::string expectInputError(const std::function<void()>& fn, std::initializer_list<std::string> parts);

}  // namespace talus::test
