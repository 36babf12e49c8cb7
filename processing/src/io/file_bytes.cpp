#include "anascan/processing/io/file_bytes.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>

namespace anascan::io {
namespace {

std::string os_reason(int error_number) { return std::strerror(error_number); }

// Owns a file descriptor; closes it once.
class FileDescriptor {
public:
    explicit FileDescriptor(int fd) : fd_(fd) {}
    ~FileDescriptor() { close(); }
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    int get() const { return fd_; }
    bool valid() const { return fd_ >= 0; }
    int close() {
        const int result = fd_ >= 0 ? ::close(fd_) : 0;
        fd_ = -1;
        return result;
    }

private:
    int fd_;
};

Expected<void> write_all(int fd, std::span<const char> bytes, const std::string& name) {
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) {
            return fail(ErrorCode::kIo,
                        name + ": cannot write: " + os_reason(errno) +
                            (errno == ENOSPC ? " (free disk space and retry)" : ""));
        }
        done += static_cast<std::size_t>(n);
    }
    return {};
}

std::filesystem::path temporary_sibling(const std::filesystem::path& path) {
    std::random_device entropy;
    return path.parent_path() /
           ("." + path.filename().string() + ".tmp" + std::to_string(entropy() % 1000000));
}

void sync_directory(const std::filesystem::path& dir) {
    FileDescriptor fd(::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY));
    if (fd.valid()) ::fsync(fd.get());  // Best effort: some file systems refuse it.
}

}  // namespace

Expected<std::vector<char>> read_file_bytes(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
        return fail(ErrorCode::kIo, name + ": is a directory, expected a file");
    }
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) return fail(ErrorCode::kIo, name + ": cannot open: " + os_reason(errno));
    const std::streamoff size = in.tellg();
    if (size < 0) return fail(ErrorCode::kIo, name + ": cannot determine the file size");
    std::vector<char> bytes(static_cast<std::size_t>(size));
    in.seekg(0);
    if (size > 0 && !in.read(bytes.data(), size)) {
        return fail(ErrorCode::kIo,
                    name + ": read failed after " + std::to_string(in.gcount()) + " bytes");
    }
    return bytes;
}

Expected<void> write_file_atomically(const std::filesystem::path& path,
                                     std::span<const char> bytes) {
    const std::string name = path.string();
    const std::filesystem::path tmp = temporary_sibling(path);
    FileDescriptor fd(::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
    if (!fd.valid()) {
        return fail(ErrorCode::kIo, name + ": cannot create a file in '" +
                                        path.parent_path().string() + "': " + os_reason(errno));
    }
    auto written = write_all(fd.get(), bytes, name);
    if (written && ::fsync(fd.get()) != 0) {
        written = fail(ErrorCode::kIo, name + ": cannot flush to disk: " + os_reason(errno));
    }
    if (written && fd.close() != 0) {
        written = fail(ErrorCode::kIo, name + ": cannot close: " + os_reason(errno));
    }
    if (written && ::rename(tmp.c_str(), path.c_str()) != 0) {
        written = fail(ErrorCode::kIo, name + ": cannot rename into place: " + os_reason(errno));
    }
    if (!written) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        return written;
    }
    sync_directory(path.parent_path());
    return {};
}

}  // namespace anascan::io
