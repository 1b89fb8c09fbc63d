// The OpenCL device every device-backed test runs on, opened once per precision and shared.
//
// Usage (any test file):
//   #include "support/TestDevice.hpp"
//   talus::compute::Context& ctx = talus::test::testContext(talus::compute::Precision::Double);
//
// The device is chosen by talus::compute::selectDevice(""), i.e. automatically or by the
// environment variable TALUS_DEVICE (an index or a name substring such as "pocl"). CI runs on the
// PoCL CPU device. There is deliberately no skipping: when no OpenCL device exists, or the device
// cannot run the requested precision, testContext throws talus::ComputeError with an explanation,
// and GoogleTest reports the calling test as FAILED with that message.
//
// The shared Context lives until the process exits (it is never destroyed, so no OpenCL call runs
// during static destruction). Its in-memory program cache and profiler are shared between tests:
// a test that needs fresh state (its own profiler totals, environment-dependent kernel sources,
// a cold program cache) should build its own Context from testDevice() instead.
#pragma once
#include "compute/Context.hpp"
#include "compute/Device.hpp"
#include "compute/Precision.hpp"

namespace talus::test {

/// The device selected for tests (selectDevice("")); throws talus::ComputeError when there is none.
const compute::DeviceInfo& testDevice();

/// The shared test Context of the given precision, created on first use. Throws
/// talus::ComputeError (failing the calling test loudly) when no OpenCL device is installed or the
/// device lacks cl_khr_fp64 and Precision::Double is requested.
compute::Context& testContext(compute::Precision precision);

}  // namespace talus::test
