#include "os_error.hpp"

#include <cerrno>
#include <cstring>

namespace anascan::drivers {

ErrorCode classify_errno(int e) {
    switch (e) {
        case ENODEV:
        case ENXIO:
        case ENOENT:
        case ESHUTDOWN:
        case EPIPE:
            return ErrorCode::kDisconnected;
        case EBUSY:
            return ErrorCode::kBusy;
        case ETIMEDOUT:
        case EAGAIN:
            return ErrorCode::kTimeout;
        case EINVAL:
        case ERANGE:
            return ErrorCode::kInvalidArgument;
        default:
            return ErrorCode::kIo;
    }
}

Error errno_error(const std::string& device, const std::string& what, int e) {
    std::string message =
        device + ": " + what + ": " + std::strerror(e) + " (errno " + std::to_string(e) + ")";
    if (e == EACCES || e == EPERM) message += "; is the user in the 'video' or 'plugdev' group?";
    return Error{classify_errno(e), std::move(message)};
}

}  // namespace anascan::drivers
