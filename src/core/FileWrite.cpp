#include "core/FileWrite.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/Error.hpp"

namespace talus {

std::string writeFailure(const std::string& path, int errorNumber) {
  return "cannot write '" + path + "': " + std::strerror(errorNumber);
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw IoError(writeFailure(path, errno));
  auto fail = [&](int err, bool opened) {
    if (opened) ::close(fd);
    ::unlink(tmp.c_str());
    throw IoError(writeFailure(path, err));
  };
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(n < 0 ? errno : ENOSPC, true);
    done += static_cast<std::size_t>(n);
  }
  // The data must be on the disk before the rename makes the file visible under its name: after a
  // crash the name holds the old file or the complete new one, never a truncated one.
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) fail(errno, true);
  if (::close(fd) != 0) fail(errno, false);
  if (::rename(tmp.c_str(), path.c_str()) != 0) fail(errno, false);
}

AppendFile::~AppendFile() {
  if (f_) std::fclose(f_);
}

void AppendFile::open(const std::string& path, bool truncate) {
  if (f_) close();
  path_ = path;
  f_ = std::fopen(path.c_str(), truncate ? "w" : "a");
  if (!f_) throw IoError(writeFailure(path, errno));
}

void AppendFile::appendLine(const std::string& line) {
  if (!f_) throw IoError("cannot write '" + path_ + "': the file is not open");
  errno = 0;
  if (std::fwrite(line.data(), 1, line.size(), f_) != line.size() || std::fputc('\n', f_) == EOF ||
      std::fflush(f_) != 0) {
    const int err = errno != 0 ? errno : EIO;
    std::fclose(f_);
    f_ = nullptr;
    throw IoError(writeFailure(path_, err));
  }
}

void AppendFile::close() {
  if (!f_) return;
  std::FILE* f = f_;
  f_ = nullptr;
  if (std::fclose(f) != 0) throw IoError(writeFailure(path_, errno));
}

}  // namespace talus
