#pragma once
/// \file
/// Whole-file reads and crash-safe whole-file writes, with errors that name the file.

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "anascan/processing/core/expected.hpp"

namespace anascan::io {

/// Reads a whole file into memory. Errors name the file and the OS reason.
Expected<std::vector<char>> read_file_bytes(const std::filesystem::path& path);

/// Writes `bytes` so that `path` holds either its old content or all of the new content,
/// never a mix: write to a temporary file beside it, flush to disk (fsync), rename over
/// `path`, fsync the directory. A full disk or a read-only folder returns an error naming
/// the file and leaves any previous file untouched.
Expected<void> write_file_atomically(const std::filesystem::path& path,
                                     std::span<const char> bytes);

}  // namespace anascan::io
