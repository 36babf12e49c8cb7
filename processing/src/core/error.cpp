#include "anascan/processing/core/error.hpp"

namespace anascan {

std::string_view to_string(ErrorCode code) {
    switch (code) {
        case ErrorCode::kIo:
            return "io";
        case ErrorCode::kFormat:
            return "format";
        case ErrorCode::kTruncated:
            return "truncated";
        case ErrorCode::kUnsupported:
            return "unsupported";
        case ErrorCode::kInvalidArgument:
            return "invalid-argument";
        case ErrorCode::kEmpty:
            return "empty";
        case ErrorCode::kDisconnected:
            return "disconnected";
        case ErrorCode::kTimeout:
            return "timeout";
        case ErrorCode::kBusy:
            return "busy";
        case ErrorCode::kCancelled:
            return "cancelled";
    }
    return "unknown";
}

}  // namespace anascan
