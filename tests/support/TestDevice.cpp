// The shared test device and contexts (see TestDevice.hpp).
#include "support/TestDevice.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "core/Error.hpp"

namespace talus::test {
namespace {

/// Re-throws a device problem with a headline that says why the test cannot run, also on stderr
/// (so it is visible even when a test framework swallows the exception text).
[[noreturn]] void failLoudly(const std::string& why) {
  const std::string text = "Talus tests need an OpenCL device and none could be opened: " + why +
                           "\n(tests never skip; install pocl-opencl-icd or set TALUS_DEVICE)";
  std::fprintf(stderr, "%s\n", text.c_str());
  throw ComputeError(text);
}

// The test contexts (float, double), created on first use and intentionally never deleted: OpenCL
// objects must not be released during static destruction.
compute::Context* contexts[2] = {nullptr, nullptr};

/// Drains both contexts' queues after the last test. PoCL compiles kernels lazily on its worker
/// threads; a launch still queued when main() returns would be compiled after LLVM's static
/// destructors ran (a crash in the sanitizer build, after every test had passed).
class DrainQueues : public ::testing::Environment {
 public:
  void TearDown() override {
    for (compute::Context* c : contexts)
      if (c) c->finish();
  }
};
[[maybe_unused]] const ::testing::Environment* const kDrain = ::testing::AddGlobalTestEnvironment(new DrainQueues);

}  // namespace

const compute::DeviceInfo& testDevice() {
  // Selected once; a failure is not cached, so every test that needs the device reports it.
  static const compute::DeviceInfo* device = nullptr;
  if (!device) {
    try {
      device = new compute::DeviceInfo(compute::selectDevice(""));
    } catch (const ComputeError& e) {
      failLoudly(e.what());
    }
  }
  return *device;
}

compute::Context& testContext(compute::Precision precision) {
  compute::Context*& slot = contexts[precision == compute::Precision::Double ? 1 : 0];
  if (!slot) {
    const compute::DeviceInfo& device = testDevice();
    try {
      slot = new compute::Context(device, precision);
    } catch (const ComputeError& e) {
      failLoudly(std::string("opening '") + device.name + "' for " + compute::precisionName(precision) +
                 " precision: " + e.what());
    }
  }
  return *slot;
}

}  // namespace talus::test
