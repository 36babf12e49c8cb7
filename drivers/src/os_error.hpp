#pragma once
// Operating-system error numbers as the error classes callers react to.

#include <string>

#include "anascan/processing/core/error.hpp"

namespace anascan::drivers {

/// ENODEV, ENXIO, ENOENT, ESHUTDOWN, EPIPE → kDisconnected; EBUSY → kBusy; ETIMEDOUT,
/// EAGAIN → kTimeout; EINVAL, ERANGE → kInvalidArgument; everything else → kIo.
ErrorCode classify_errno(int error_number);

/// "<device>: <what>: <strerror> (errno N)", classified by classify_errno.
Error errno_error(const std::string& device, const std::string& what, int error_number);

}  // namespace anascan::drivers
