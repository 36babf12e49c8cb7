#pragma once
// Point and output files as the command line names them: the formats it reads and writes,
// and the checks that name a bad input or output before any work is done.

#include <filesystem>
#include <string>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/io/ply.hpp"

namespace anascan::cli {

/// Every point format the command line reads, for messages.
inline constexpr const char* kReadablePointFormats =
    "PLY (.ply), PTX (.ptx), E57 (.e57), XYZ text (.xyz, .txt, .asc), Leica PTS (.pts)";
/// Every point format the command line writes, for messages.
inline constexpr const char* kWritablePointFormats = "PLY (.ply), XYZ text (.xyz, .txt, .asc)";

/// The extension in lower case, with its dot ("" when none).
std::string lower_extension(const std::filesystem::path& path);

/// Throws CommandFailed naming the whole path when the file is empty (0 bytes) or when its
/// extension names no format `extra` or the point readers handle. `extra`: further
/// extensions the command reads.
void check_point_input(const std::filesystem::path& path, std::string_view extra = "");

/// Throws CommandFailed when write_points cannot write the format `path`'s extension names
/// and `extra` (further extensions the command writes itself, ".e57") does not name it.
void check_point_output(const std::filesystem::path& path, std::string_view extra = "");

/// Writes the cloud in the format the extension names: .ply (encoding from `ply`), or
/// .xyz/.txt/.asc as XYZ text. Throws CommandFailed on error.
void write_points(const std::filesystem::path& path, const PointCloud& cloud,
                  const io::PlyWriteOptions& ply = {});

/// Throws CommandFailed unless a file can be created in the folder `path` will be written
/// to (tried with a probe file, so a read-only or missing folder is found before the work).
/// `what` names the option in the message ("--out"). An empty path (option not given)
/// passes.
void check_output_writable(const std::filesystem::path& path, std::string_view what);

}  // namespace anascan::cli
