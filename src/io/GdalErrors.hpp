// Internal to src/io: GDAL registration, the collection of GDAL's error messages for our exceptions
// (the only files that include GDAL are in src/io), and the process id that names temporary files
// of atomic writes.
#pragma once
#include <cpl_error.h>
#include <gdal.h>

#include <mutex>
#include <string>

#ifdef _WIN32
#include <process.h>
#else
#include <unistd.h>
#endif

namespace talus::io::detail {

/// This process's id, for the names of temporary files (name.tmp-PID).
inline long processId() {
#ifdef _WIN32
  return static_cast<long>(_getpid());
#else
  return static_cast<long>(getpid());
#endif
}

/// Registers GDAL's drivers once per process.
inline void ensureGdalRegistered() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

/// While alive, routes this thread's GDAL errors away from stderr and collects the failure
/// messages, so they can be put into our exception text.
class GdalErrorScope {
 public:
  GdalErrorScope() {
    CPLErrorReset();
    CPLPushErrorHandlerEx(&GdalErrorScope::handler, this);
  }
  ~GdalErrorScope() { CPLPopErrorHandler(); }
  GdalErrorScope(const GdalErrorScope&) = delete;
  GdalErrorScope& operator=(const GdalErrorScope&) = delete;

  /// True once GDAL reported a failure (CE_Failure or CE_Fatal) inside this scope.
  bool failed() const { return failures_ > 0; }

  /// The collected failure messages, else GDAL's last message, else the fallback text.
  std::string describe(const std::string& fallback) const {
    if (!messages_.empty()) return messages_;
    const char* last = CPLGetLastErrorMsg();
    if (last != nullptr && *last != '\0') return last;
    return fallback;
  }

 private:
  static void CPL_STDCALL handler(CPLErr cls, CPLErrorNum /*num*/, const char* msg) {
    auto* self = static_cast<GdalErrorScope*>(CPLGetErrorHandlerUserData());
    if (self == nullptr || (cls != CE_Failure && cls != CE_Fatal)) return;
    ++self->failures_;
    if (self->failures_ > 3 || msg == nullptr) return;  // the first few say enough
    if (!self->messages_.empty()) self->messages_ += "; ";
    self->messages_ += msg;
  }

  int failures_ = 0;
  std::string messages_;
};

}  // namespace talus::io::detail
