#include "frame_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "os_error.hpp"

namespace anascan::drivers {
namespace {

constexpr char kMagic[4] = {'A', 'N', 'F', 'R'};
constexpr std::uint16_t kVersion = 1;

// Header layout (little-endian, the host order of every platform we build for):
// 0 magic[4], 4 version u16, 6 format u16, 8 width u32, 12 height u32, 16 stride u32,
// 20 reserved u32, 24 sequence u64, 32 timestamp_ns i64, 40 payload u64, 48 crc32 u32,
// 52 reserved u32.
template <class T>
void put(std::array<std::uint8_t, kFrameHeaderBytes>& h, std::size_t at, T v) {
    std::memcpy(h.data() + at, &v, sizeof(T));
}
template <class T>
T get(const std::array<std::uint8_t, kFrameHeaderBytes>& h, std::size_t at) {
    T v;
    std::memcpy(&v, h.data() + at, sizeof(T));
    return v;
}

/// Bytes from the current position to the end of the file (0 when it cannot tell).
std::uint64_t bytes_left(std::FILE* file) {
    const long here = std::ftell(file);
    struct stat st {};
    if (here < 0 || ::fstat(::fileno(file), &st) != 0 || st.st_size < here) return 0;
    return static_cast<std::uint64_t>(st.st_size - here);
}

std::uint32_t crc_of(const std::vector<std::uint8_t>& data) {
    return static_cast<std::uint32_t>(crc32(0L, data.data(), static_cast<uInt>(data.size())));
}

Expected<void> write_all(int fd, const void* data, std::size_t n, const std::string& path) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    while (n > 0) {
        const ssize_t w = ::write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w < 0) return fail(errno_error(path, "write", errno));
        p += w;
        n -= static_cast<std::size_t>(w);
    }
    return {};
}

}  // namespace

Expected<FrameFileWriter> FrameFileWriter::create(const std::filesystem::path& path,
                                                  int sync_every) {
    UniqueFd fd(::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644));
    if (!fd) return fail(errno_error(path.string(), "create", errno));
    return FrameFileWriter(std::move(fd), path, sync_every);
}

Expected<void> FrameFileWriter::append(const Frame& f) {
    std::array<std::uint8_t, kFrameHeaderBytes> h{};
    std::memcpy(h.data(), kMagic, 4);
    put<std::uint16_t>(h, 4, kVersion);
    put<std::uint16_t>(h, 6, static_cast<std::uint16_t>(f.format));
    put<std::uint32_t>(h, 8, static_cast<std::uint32_t>(f.width));
    put<std::uint32_t>(h, 12, static_cast<std::uint32_t>(f.height));
    put<std::uint32_t>(h, 16, static_cast<std::uint32_t>(f.stride_bytes));
    put<std::uint64_t>(h, 24, f.sequence);
    put<std::int64_t>(h, 32, f.timestamp_ns.count());
    put<std::uint64_t>(h, 40, f.data.size());
    put<std::uint32_t>(h, 48, crc_of(f.data));
    if (auto ok = write_all(fd_.get(), h.data(), h.size(), path_.string()); !ok) return ok;
    if (auto ok = write_all(fd_.get(), f.data.data(), f.data.size(), path_.string()); !ok)
        return ok;
    if (++unsynced_ >= sync_every_) return flush();
    return {};
}

Expected<void> FrameFileWriter::flush() {
    unsynced_ = 0;
    if (::fsync(fd_.get()) != 0) return fail(errno_error(path_.string(), "fsync", errno));
    return {};
}

Expected<FrameFileReader> FrameFileReader::open(const std::filesystem::path& path) {
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
    if (!file) return fail(errno_error(path.string(), "open", errno));
    return FrameFileReader(std::move(file), path);
}

void FrameFileReader::rewind() {
    std::rewind(file_.get());
    stopped_early_ = false;
}

Expected<Frame> FrameFileReader::next() {
    std::array<std::uint8_t, kFrameHeaderBytes> h{};
    const std::size_t got = std::fread(h.data(), 1, h.size(), file_.get());
    const std::string where = path_.string() + ": byte " +
                              std::to_string(std::ftell(file_.get()) - static_cast<long>(got));
    if (got == 0) return fail(ErrorCode::kEmpty, path_.string() + ": end of recording");
    if (got < h.size() || std::memcmp(h.data(), kMagic, 4) != 0 ||
        get<std::uint16_t>(h, 4) != kVersion) {
        stopped_early_ = true;
        return fail(ErrorCode::kEmpty,
                    where + ": partial or unknown frame record; recording ends here");
    }
    Frame f;
    f.format = static_cast<PixelFormat>(get<std::uint16_t>(h, 6));
    f.width = static_cast<int>(get<std::uint32_t>(h, 8));
    f.height = static_cast<int>(get<std::uint32_t>(h, 12));
    f.stride_bytes = get<std::uint32_t>(h, 16);
    f.sequence = get<std::uint64_t>(h, 24);
    f.timestamp_ns = std::chrono::nanoseconds(get<std::int64_t>(h, 32));
    const auto payload = get<std::uint64_t>(h, 40);
    if (payload > (std::uint64_t{1} << 32) ||
        get<std::uint16_t>(h, 6) > static_cast<int>(PixelFormat::kZ16)) {
        stopped_early_ = true;
        return fail(ErrorCode::kEmpty, where + ": implausible frame record; recording ends here");
    }
    if (payload > bytes_left(file_.get())) {  // a lying length: never allocate what is not there
        stopped_early_ = true;
        return fail(ErrorCode::kEmpty, where + ": frame " + std::to_string(f.sequence) +
                                           " is cut short or corrupt (shorter than its length); "
                                           "recording ends here");
    }
    f.data.resize(payload);
    if (std::fread(f.data.data(), 1, payload, file_.get()) != payload ||
        crc_of(f.data) != get<std::uint32_t>(h, 48)) {
        stopped_early_ = true;
        return fail(ErrorCode::kEmpty, where + ": frame " + std::to_string(f.sequence) +
                                           " is cut short or corrupt (CRC); recording ends here");
    }
    return f;
}

}  // namespace anascan::drivers
