#pragma once
/// \file
/// Errors that callers react to: classified by what the caller can do about them.

#include <string>
#include <string_view>

namespace anascan {

/// How the caller reacts: retry, ask the user for another file, reconnect, give up.
enum class ErrorCode {
    kIo,               ///< The operating system refused (missing file, permission, disk full).
    kFormat,           ///< The content is malformed (bad header, bad number, lying count).
    kTruncated,        ///< The content ends before what its header announced.
    kUnsupported,      ///< Well-formed but a variant we do not read (e.g. an unknown type).
    kInvalidArgument,  ///< The caller passed a value outside the documented range.
    kEmpty,            ///< There is nothing to work on (no points, no scans).
    kDisconnected,     ///< A device went away.
    kTimeout,          ///< A device or operation did not answer in time.
    kBusy,             ///< A device or resource is in use.
    kCancelled,        ///< The caller asked the operation to stop (e.g. a scan cancelled).
};

/// A failure with a message a user can act on. The message names the file or device and,
/// for parsers, the line or byte offset: "bun000.ply: byte 812: vertex 3 of 40256: ...".
struct Error {
    ErrorCode code = ErrorCode::kIo;
    std::string message;
};

/// Short English name of a code ("format", "truncated", ...), for logs and JSON.
std::string_view to_string(ErrorCode code);

}  // namespace anascan
