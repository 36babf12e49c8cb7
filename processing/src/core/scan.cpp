#include "anascan/processing/core/scan.hpp"

namespace anascan {

const char* to_string(DeviceKind kind) {
    switch (kind) {
        case DeviceKind::kUnknown:
            return "unknown";
        case DeviceKind::kStructuredLight:
            return "structured-light";
        case DeviceKind::kTimeOfFlight:
            return "time-of-flight";
        case DeviceKind::kImported:
            return "imported";
    }
    return "unknown";
}

}  // namespace anascan
