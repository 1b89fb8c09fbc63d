// Checked writes of output files: every byte, the flush to the disk and the close are checked, so a
// full disk, a quota or a file-size limit is an IoError with the system's reason, never a file that
// looks complete but is not.
#pragma once
#include <cstdio>
#include <string>

namespace talus {

/// Writes `bytes` to `path` atomically: a temporary file `path.tmp-PID` is written, synced and
/// closed, then renamed over `path`. On any failure the temporary file is removed, `path` is left as
/// it was, and IoError names `path` with the system's reason.
void writeFileAtomically(const std::string& path, const std::string& bytes);

/// A file that grows by lines (diagnostics.csv): each line is written and flushed at once and every
/// call is checked, so a line either reaches the file or the run hears why not.
class AppendFile {
 public:
  AppendFile() = default;
  ~AppendFile();
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;
  /// Opens `path` for appending (`truncate`: emptied first). IoError on failure.
  void open(const std::string& path, bool truncate);
  bool isOpen() const { return f_ != nullptr; }
  /// Appends `line` and a newline, and flushes. IoError on failure.
  void appendLine(const std::string& line);
  /// Closes the file, checking the close. IoError on failure.
  void close();

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
};

/// "cannot write 'path': <strerror(errno)>".
std::string writeFailure(const std::string& path, int errorNumber);

}  // namespace talus
