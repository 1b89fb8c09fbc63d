// OpenCL status codes turned into sentences, and the check used after every OpenCL call.
#pragma once
#include <CL/cl.h>

#include <string>

namespace talus::compute {

/// The symbolic name and a short explanation of an OpenCL status code.
std::string clErrorText(cl_int status);

/// Throws talus::ComputeError "<what>: <clErrorText(status)>" unless status is CL_SUCCESS.
void clCheck(cl_int status, const std::string& what);

}  // namespace talus::compute
