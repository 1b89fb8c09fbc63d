// A small JSON reader for the files Talus itself writes (a member's summary.json and member.json):
// the full JSON grammar (RFC 8259) into a tree of values, numbers as double. Throws
// talus::InputError naming the source and the byte offset of a syntax error.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace talus::ensemble {

class JsonValue {
 public:
  enum class Type { Null, Bool, Number, String, Array, Object };

  Type type() const { return type_; }
  bool isObject() const { return type_ == Type::Object; }
  /// The member `key` of an object, or nullptr when this is no object or has no such member.
  const JsonValue* find(const std::string& key) const;
  /// The member at a path of keys ("volume", "initial_m3"), or nullptr.
  const JsonValue* at(const std::vector<std::string>& path) const;
  double number() const { return number_; }
  bool boolean() const { return bool_; }
  const std::string& string() const { return string_; }
  const std::vector<JsonValue>& array() const { return array_; }
  /// Object members in key order.
  const std::map<std::string, JsonValue>& object() const { return object_; }

  /// Parses `text` (one JSON value with optional blank space around it); `source` names it in errors.
  static JsonValue parse(const std::string& text, const std::string& source);

 private:
  friend class JsonParser;
  Type type_ = Type::Null;
  double number_ = 0;
  bool bool_ = false;
  std::string string_;
  std::vector<JsonValue> array_;
  std::map<std::string, JsonValue> object_;
};

/// A string as a JSON string literal, quotes included (", \ and control bytes escaped).
std::string jsonQuote(const std::string& s);

}  // namespace talus::ensemble
