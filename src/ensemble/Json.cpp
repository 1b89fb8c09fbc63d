// Recursive-descent JSON reader (RFC 8259). Nesting is limited so that a hostile file cannot
// exhaust the stack; \u escapes become UTF-8 (surrogate pairs joined).
#include "ensemble/Json.hpp"

#include <cctype>
#include <charconv>
#include <cstdio>

#include "core/Error.hpp"

namespace talus::ensemble {

class JsonParser {
 public:
  JsonParser(const std::string& text, const std::string& source) : t_(text), source_(source) {}

  JsonValue document() {
    JsonValue v = value(0);
    blank();
    if (p_ != t_.size()) fail("text after the JSON value");
    return v;
  }

 private:
  static constexpr int kMaxDepth = 64;

  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(source_ + ": invalid JSON at byte " + std::to_string(p_) + ": " + what);
  }
  void blank() {
    while (p_ < t_.size() && (t_[p_] == ' ' || t_[p_] == '\t' || t_[p_] == '\n' || t_[p_] == '\r')) ++p_;
  }
  bool literal(const char* word) {
    const std::string w(word);
    if (t_.compare(p_, w.size(), w) != 0) return false;
    p_ += w.size();
    return true;
  }
  JsonValue value(int depth) {
    if (depth > kMaxDepth) fail("nested deeper than 64 levels");
    blank();
    if (p_ >= t_.size()) fail("unexpected end");
    JsonValue v;
    const char c = t_[p_];
    if (c == '{') {
      v.type_ = JsonValue::Type::Object;
      ++p_;
      blank();
      if (p_ < t_.size() && t_[p_] == '}') {
        ++p_;
        return v;
      }
      for (;;) {
        blank();
        if (p_ >= t_.size() || t_[p_] != '"') fail("expected a member name in quotes");
        const std::string key = string();
        blank();
        if (p_ >= t_.size() || t_[p_] != ':') fail("expected ':' after a member name");
        ++p_;
        v.object_[key] = value(depth + 1);
        blank();
        if (p_ < t_.size() && t_[p_] == ',') { ++p_; continue; }
        if (p_ < t_.size() && t_[p_] == '}') { ++p_; return v; }
        fail("expected ',' or '}' in an object");
      }
    }
    if (c == '[') {
      v.type_ = JsonValue::Type::Array;
      ++p_;
      blank();
      if (p_ < t_.size() && t_[p_] == ']') {
        ++p_;
        return v;
      }
      for (;;) {
        v.array_.push_back(value(depth + 1));
        blank();
        if (p_ < t_.size() && t_[p_] == ',') { ++p_; continue; }
        if (p_ < t_.size() && t_[p_] == ']') { ++p_; return v; }
        fail("expected ',' or ']' in an array");
      }
    }
    if (c == '"') {
      v.type_ = JsonValue::Type::String;
      v.string_ = string();
      return v;
    }
    if (literal("true")) { v.type_ = JsonValue::Type::Bool; v.bool_ = true; return v; }
    if (literal("false")) { v.type_ = JsonValue::Type::Bool; return v; }
    if (literal("null")) return v;
    if (c == '-' || std::isdigit(static_cast<unsigned char>(c))) {
      v.type_ = JsonValue::Type::Number;
      const std::size_t start = p_;
      if (t_[p_] == '-') ++p_;
      auto digits = [&] {
        const std::size_t d = p_;
        while (p_ < t_.size() && std::isdigit(static_cast<unsigned char>(t_[p_]))) ++p_;
        if (p_ == d) fail("expected a digit");
      };
      if (p_ < t_.size() && t_[p_] == '0') ++p_;
      else digits();
      if (p_ < t_.size() && t_[p_] == '.') { ++p_; digits(); }
      if (p_ < t_.size() && (t_[p_] == 'e' || t_[p_] == 'E')) {
        ++p_;
        if (p_ < t_.size() && (t_[p_] == '+' || t_[p_] == '-')) ++p_;
        digits();
      }
      const auto [end, ec] = std::from_chars(t_.data() + start, t_.data() + p_, v.number_);
      if (ec != std::errc() || end != t_.data() + p_) fail("number out of range");
      return v;
    }
    fail(std::string("unexpected character '") + c + "'");
  }
  unsigned hex4() {
    if (p_ + 4 > t_.size()) fail("short \\u escape");
    unsigned u = 0;
    for (int k = 0; k < 4; ++k) {
      const char h = t_[p_++];
      u <<= 4;
      if (h >= '0' && h <= '9') u |= static_cast<unsigned>(h - '0');
      else if (h >= 'a' && h <= 'f') u |= static_cast<unsigned>(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F') u |= static_cast<unsigned>(h - 'A' + 10);
      else fail("bad hex digit in \\u escape");
    }
    return u;
  }
  static void utf8(unsigned cp, std::string& o) {
    if (cp < 0x80) o += static_cast<char>(cp);
    else if (cp < 0x800) { o += static_cast<char>(0xC0 | (cp >> 6)); o += static_cast<char>(0x80 | (cp & 0x3F)); }
    else if (cp < 0x10000) {
      o += static_cast<char>(0xE0 | (cp >> 12));
      o += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      o += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      o += static_cast<char>(0xF0 | (cp >> 18));
      o += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      o += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      o += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }
  std::string string() {
    ++p_;  // opening quote
    std::string o;
    for (;;) {
      if (p_ >= t_.size()) fail("unterminated string");
      const char c = t_[p_++];
      if (c == '"') return o;
      if (static_cast<unsigned char>(c) < 0x20) fail("control character in a string");
      if (c != '\\') { o += c; continue; }
      if (p_ >= t_.size()) fail("unterminated escape");
      const char e = t_[p_++];
      switch (e) {
        case '"': o += '"'; break;
        case '\\': o += '\\'; break;
        case '/': o += '/'; break;
        case 'b': o += '\b'; break;
        case 'f': o += '\f'; break;
        case 'n': o += '\n'; break;
        case 'r': o += '\r'; break;
        case 't': o += '\t'; break;
        case 'u': {
          unsigned cp = hex4();
          if (cp >= 0xD800 && cp < 0xDC00) {
            if (!literal("\\u")) fail("lone high surrogate");
            const unsigned lo = hex4();
            if (lo < 0xDC00 || lo >= 0xE000) fail("bad low surrogate");
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          } else if (cp >= 0xDC00 && cp < 0xE000) {
            fail("lone low surrogate");
          }
          utf8(cp, o);
          break;
        }
        default: fail(std::string("unknown escape '\\") + e + "'");
      }
    }
  }

  const std::string& t_;
  const std::string& source_;
  std::size_t p_ = 0;
};

const JsonValue* JsonValue::find(const std::string& key) const {
  if (type_ != Type::Object) return nullptr;
  const auto it = object_.find(key);
  return it == object_.end() ? nullptr : &it->second;
}

const JsonValue* JsonValue::at(const std::vector<std::string>& path) const {
  const JsonValue* v = this;
  for (const std::string& k : path)
    if (!(v = v->find(k))) return nullptr;
  return v;
}

JsonValue JsonValue::parse(const std::string& text, const std::string& source) {
  return JsonParser(text, source).document();
}

std::string jsonQuote(const std::string& s) {
  std::string o = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      o += '\\';
      o += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      o += buf;
    } else {
      o += static_cast<char>(c);
    }
  }
  return o + "\"";
}

}  // namespace talus::ensemble
