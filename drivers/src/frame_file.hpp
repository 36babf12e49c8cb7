#pragma once
// frames.bin of a recording: append-only frame records with a CRC-32 per payload.

#include <cstdio>
#include <filesystem>
#include <memory>

#include "anascan/drivers/frame.hpp"
#include "unique_fd.hpp"

namespace anascan::drivers {

inline constexpr std::size_t kFrameHeaderBytes = 56;

/// Appends frames; fsyncs every `sync_every` frames and on flush(). Not thread-safe.
class FrameFileWriter {
public:
    static Expected<FrameFileWriter> create(const std::filesystem::path& path, int sync_every);
    Expected<void> append(const Frame& frame);
    Expected<void> flush();

private:
    FrameFileWriter(UniqueFd fd, std::filesystem::path path, int sync_every)
        : fd_(std::move(fd)), path_(std::move(path)), sync_every_(sync_every) {}
    UniqueFd fd_;
    std::filesystem::path path_;
    int sync_every_;
    int unsynced_ = 0;
};

/// Reads frames in order. Not thread-safe.
class FrameFileReader {
public:
    static Expected<FrameFileReader> open(const std::filesystem::path& path);
    /// The next frame; kEmpty at the end (or at a partial or corrupt last record, which
    /// `stopped_early()` then reports).
    Expected<Frame> next();
    void rewind();
    bool stopped_early() const { return stopped_early_; }

private:
    struct FileCloser {
        void operator()(std::FILE* f) const { std::fclose(f); }
    };
    FrameFileReader(std::unique_ptr<std::FILE, FileCloser> file, std::filesystem::path path)
        : file_(std::move(file)), path_(std::move(path)) {}
    std::unique_ptr<std::FILE, FileCloser> file_;
    std::filesystem::path path_;
    bool stopped_early_ = false;
};

}  // namespace anascan::drivers
