// Builders of run-file key declarations (RunKeys.cpp for Talus's keys, LisemKeys.cpp for the
// OpenLISEM Hazard keys Talus knows without using): one call declares one key.
#pragma once
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/KeyRegistry.hpp"

namespace talus::sim::keys {

using io::KeyRegistry;
using io::KeyRole;
using io::KeySpec;
using io::KeyType;

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// Builders: one call declares one key. Arguments follow the order of the key table.

inline KeySpec flag(std::string name, std::string def, std::string help) {
  KeySpec k;
  k.name = std::move(name);
  k.type = KeyType::Flag;
  k.defaultValue = std::move(def);
  k.help = std::move(help);
  return k;
}

inline KeySpec real(std::string name, std::string def, std::string unit, double min, double max, std::string help) {
  KeySpec k;
  k.name = std::move(name);
  k.type = KeyType::Real;
  k.defaultValue = std::move(def);
  k.unit = std::move(unit);
  k.min = min;
  k.max = max;
  k.help = std::move(help);
  return k;
}

inline KeySpec map(std::string name, std::string def, std::string unit, double min, double max, std::string help) {
  KeySpec k = real(std::move(name), std::move(def), std::move(unit), min, max, std::move(help));
  k.type = KeyType::Map;
  return k;
}

inline KeySpec choice(std::string name, std::vector<std::string> choices, std::string def, std::string help) {
  KeySpec k;
  k.name = std::move(name);
  k.type = KeyType::Choice;
  k.choices = std::move(choices);
  k.defaultValue = std::move(def);
  k.help = std::move(help);
  return k;
}

inline KeySpec text(std::string name, std::string def, std::string help, KeyType type = KeyType::Text) {
  KeySpec k;
  k.name = std::move(name);
  k.type = type;
  k.defaultValue = std::move(def);
  k.help = std::move(help);
  return k;
}

inline KeySpec required(KeySpec k) {
  k.required = true;
  return k;
}

/// A map read only while the flag `process` is 1 (KeySpec::enabledBy).
inline KeySpec readWhen(std::string process, KeySpec k) {
  k.enabledBy = std::move(process);
  return k;
}

/// A map of the solids, read only with Include Initial Solids=1.
inline KeySpec solidMap(std::string name, std::string def, std::string unit, double min, double max, std::string help) {
  return readWhen("Include Initial Solids", map(std::move(name), std::move(def), std::move(unit), min, max, std::move(help)));
}

/// A map of the particles, read only with Use Material Point Method=1.
inline KeySpec particleMap(std::string name, std::string def, std::string unit, double min, double max, std::string help) {
  return readWhen("Use Material Point Method",
                  map(std::move(name), std::move(def), std::move(unit), min, max, std::move(help)));
}

/// Adds keys to a registry under one section.
class Section {
 public:
  Section(KeyRegistry& keys, std::string name) : keys_(keys), name_(std::move(name)) {}
  Section& operator<<(KeySpec k) {
    k.section = name_;
    keys_.add(std::move(k));
    return *this;
  }

 private:
  KeyRegistry& keys_;
  std::string name_;
};

/// An integer key.
inline KeySpec integer(std::string name, std::string def, std::string unit, double min, double max, std::string help) {
  KeySpec k = real(std::move(name), std::move(def), std::move(unit), min, max, std::move(help));
  k.type = KeyType::Integer;
  return k;
}

/// Marks a key as one OpenLISEM Hazard 2.x writes, with its default there (parametermanager.h).
inline KeySpec lisem(std::string lisemDefault, KeySpec k) {
  k.fromLisem = true;
  k.lisemDefault = std::move(lisemDefault);
  return k;
}

/// Another name for a key (OpenLISEM 6's "Begin time" for Start Time).
inline KeySpec alias(std::string other, KeySpec k) {
  k.aliases.push_back(std::move(other));
  return k;
}

/// Declares the OpenLISEM Hazard 2.x keys that Talus knows but does not use (LisemKeys.cpp).
void addLisemKeys(KeyRegistry& r);

}  // namespace talus::sim::keys
