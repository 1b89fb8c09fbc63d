// Optional CSV output of the verification tests for the validation report
// (tools/validation/make_report.sh, docs/validation.md). When the environment variable
// TALUS_VALIDATION_OUT names a folder (created if missing), tests write their profiles (numerical
// against analytic along a line, per resolution) and error tables there as CSV; when it is unset,
// nothing is written and nothing is computed for it. Writing never changes a test's verdict: the
// tests compute their numbers as before and only copy them out; a failure to write is reported on
// stderr and ignored.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace talus::test::validation {

/// The output folder, or "" when TALUS_VALIDATION_OUT is unset or empty.
inline std::string outDir() {
  const char* d = std::getenv("TALUS_VALIDATION_OUT");
  return d != nullptr ? std::string(d) : std::string();
}

/// True when the tests should write their CSVs.
inline bool enabled() { return !outDir().empty(); }

/// One CSV cell: a number (written with 10 significant digits) or a text (written as is; the
/// tests only use texts without commas or quotes).
class Cell {
 public:
  Cell(double v) {  // NOLINT: implicit on purpose, so rows read as {x, h, hExact}
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    text_ = buf;
  }
  Cell(int v) : text_(std::to_string(v)) {}                 // NOLINT
  Cell(long long v) : text_(std::to_string(v)) {}           // NOLINT
  Cell(std::size_t v) : text_(std::to_string(v)) {}         // NOLINT
  Cell(const char* s) : text_(s) {}                         // NOLINT
  Cell(const std::string& s) : text_(s) {}                  // NOLINT
  const std::string& text() const { return text_; }

 private:
  std::string text_;
};

/// A CSV table built in memory and written in one go by write().
class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void add(const std::vector<Cell>& row) { rows_.push_back(row); }
  std::size_t rows() const { return rows_.size(); }

  /// Writes the table to outDir()/name (replacing an older file); does nothing when disabled.
  void write(const std::string& name) const {
    if (!enabled()) return;
    std::error_code ec;
    std::filesystem::create_directories(outDir(), ec);
    const std::string path = (std::filesystem::path(outDir()) / name).string();
    std::ofstream f(path, std::ios::trunc);
    for (std::size_t c = 0; c < header_.size(); ++c) f << (c ? "," : "") << header_[c];
    f << "\n";
    for (const auto& row : rows_) {
      for (std::size_t c = 0; c < row.size(); ++c) f << (c ? "," : "") << row[c].text();
      f << "\n";
    }
    if (!f) std::fprintf(stderr, "validation output: cannot write '%s'\n", path.c_str());
  }

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<Cell>> rows_;
};

}  // namespace talus::test::validation
