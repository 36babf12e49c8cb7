#include "point_files.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "anascan/processing/io/text_points.hpp"
#include "commands.hpp"

namespace anascan::cli {
namespace {

namespace fs = std::filesystem;

bool one_of(const std::string& extension, std::string_view list) {
    if (extension.empty()) return false;
    for (std::size_t at = list.find(extension); at != std::string_view::npos;
         at = list.find(extension, at + 1)) {
        const std::size_t end = at + extension.size();
        if (end == list.size() || list[end] == ' ') return true;
    }
    return false;
}

constexpr std::string_view kPointExtensions = ".ply .ptx .e57 .xyz .txt .asc .pts";
constexpr std::string_view kTextExtensions = ".xyz .txt .asc";

}  // namespace

std::string lower_extension(const fs::path& path) {
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return extension;
}

void check_point_input(const fs::path& path, std::string_view extra) {
    const std::string extension = lower_extension(path);
    if (!one_of(extension, kPointExtensions) && !one_of(extension, extra)) {
        throw CommandFailed(path.string() + ": " +
                            (extension.empty() ? "no extension" : "'" + extension + "'") +
                            " is not a format anascan reads; it reads " + kReadablePointFormats +
                            (extra.empty() ? "" : " and " + std::string(extra)));
    }
    std::error_code ec;
    if (fs::is_regular_file(path, ec) && fs::file_size(path, ec) == 0 && !ec)
        throw CommandFailed(path.string() + ": empty file (0 bytes)");
}

void check_point_output(const fs::path& path, std::string_view extra) {
    const std::string extension = lower_extension(path);
    if (extension == ".ply" || one_of(extension, kTextExtensions) || one_of(extension, extra))
        return;
    throw CommandFailed(path.string() + ": cannot write " +
                        (extension.empty() ? "a file without extension" : "'" + extension + "'") +
                        "; name the output with the format wanted: " + kWritablePointFormats +
                        (extra.empty() ? "" : " or " + std::string(extra)));
}

void write_points(const fs::path& path, const PointCloud& cloud, const io::PlyWriteOptions& ply) {
    check_point_output(path);
    const Expected<void> ok = lower_extension(path) == ".ply" ? io::write_ply(path, cloud, ply)
                                                              : io::write_xyz(path, cloud);
    if (!ok) fail_command(ok.error());
}

void check_output_writable(const fs::path& path, std::string_view what) {
    if (path.empty()) return;
    const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) {
        throw CommandFailed(std::string(what) + " " + path.string() + ": the folder " +
                            dir.string() + " does not exist; create it or choose another");
    }
    const fs::path probe = dir / (".anascan-write-check-" + std::to_string(::getpid()));
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0) {
        throw CommandFailed(std::string(what) + " " + path.string() + ": cannot write in " +
                            dir.string() + " (" + std::strerror(errno) +
                            "); choose another folder before the work starts");
    }
    ::close(fd);
    ::unlink(probe.c_str());
}

}  // namespace anascan::cli
