#include "io/AsciiGridScan.hpp"
#include "core/Text.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace talus::io::detail {
namespace {

constexpr std::size_t kMaxToken = 64;  // longer than any number anyone writes into a grid

/// Whitespace-separated tokens of a file, read in blocks; each token is cut at kMaxToken characters
/// (the rest is skipped), so a garbage file costs no more memory than a number.
class TokenReader {
 public:
  explicit TokenReader(const std::string& path) : file_(std::fopen(path.c_str(), "rb"), &std::fclose) {}
  bool open() const { return file_ != nullptr; }
  /// The next token; false at the end of the file.
  bool next(std::string& token) {
    token.clear();
    int c;
    while ((c = get()) != EOF && std::isspace(c)) {
    }
    if (c == EOF) return false;
    do {
      if (token.size() < kMaxToken) token += static_cast<char>(c);
    } while ((c = get()) != EOF && !std::isspace(c));
    return true;
  }

 private:
  int get() {
    if (pos_ == len_) {
      len_ = std::fread(buf_, 1, sizeof buf_, file_.get());
      pos_ = 0;
      if (len_ == 0) return EOF;
    }
    return static_cast<unsigned char>(buf_[pos_++]);
  }

  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file_;
  char buf_[1 << 16];
  std::size_t pos_ = 0, len_ = 0;
};

/// The header keywords of ESRI ASCII grids that GDAL reads (each is followed by one value).
bool isHeaderKeyword(const std::string& token) {
  const std::string t = lower(token);
  return t == "ncols" || t == "nrows" || t == "xllcorner" || t == "yllcorner" || t == "xllcenter" ||
         t == "yllcenter" || t == "cellsize" || t == "dx" || t == "dy" || t == "nodata_value";
}

/// A whole token strtod reads as a number (also "nan" and "inf", which become nodata cells).
bool isNumber(const std::string& token) {
  char* end = nullptr;
  std::strtod(token.c_str(), &end);
  return end != token.c_str() && *end == '\0';
}

}  // namespace

std::string findNonNumericAsciiCell(const std::string& path, long long nx, long long ny) {
  auto reader = std::make_unique<TokenReader>(path);  // 64 KiB buffer: not on the stack
  if (!reader->open() || nx <= 0 || ny <= 0) return "";
  std::string token;
  bool inHeader = true;
  long long index = 0;
  while (index < nx * ny && reader->next(token)) {
    if (inHeader && isHeaderKeyword(token)) {
      reader->next(token);  // its value (GDAL has checked the header already)
      continue;
    }
    inHeader = false;
    if (!isNumber(token)) {
      std::string shown = token.size() >= kMaxToken ? token + "..." : token;
      for (char& c : shown)  // the token goes into a message on a terminal
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
      return "'" + shown + "' at column " + std::to_string(index % nx) + ", row " + std::to_string(index / nx) +
             " (counting from 0 at the top left)";
    }
    ++index;
  }
  return "";
}

}  // namespace talus::io::detail
