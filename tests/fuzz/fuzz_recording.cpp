// libFuzzer harness for the files of a device recording: the manifest (device.json), the
// settings JSON inside it and in every scan's metadata, the frame file (frames.bin) and a
// recorded scan (scans/NNNNNN.json with its .ply). The first byte picks the reader; a scan
// record's next two bytes give the JSON's length, the rest is the PLY. Any input gives a
// result or an error whose message names the file; nothing may crash, leak or allocate
// more than the input can hold.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "anascan/drivers/settings.hpp"
#include "frame_file.hpp"
#include "recording_manifest.hpp"
#include "scan_record.hpp"

namespace {

namespace fs = std::filesystem;
using namespace anascan;
using namespace anascan::drivers;

template <typename T>
void require_named(const Expected<T>& result, std::string_view name) {
    if (!result && result.error().message.find(name) == std::string::npos) std::abort();
}

const fs::path& work_dir() {
    static const fs::path dir = [] {
        fs::path d =
            fs::temp_directory_path() / ("anascan-fuzz-recording-" + std::to_string(getpid()));
        fs::create_directories(d);
        return d;
    }();
    // Registered after `dir` is made, so it runs before `dir` is destroyed.
    static const bool removed_at_exit = (std::atexit([] {
                                             std::error_code ec;
                                             fs::remove_all(work_dir(), ec);
                                         }),
                                         true);
    (void)removed_at_exit;
    return dir;
}

void write(const fs::path& path, std::string_view bytes) {
    std::ofstream(path, std::ios::binary | std::ios::trunc)
        .write(bytes.data(), std::streamsize(bytes.size()));
}

void fuzz_manifest(std::string_view text) {
    const fs::path path = work_dir() / "device.json";
    const auto manifest = manifest_from_json(std::string(text), path);
    require_named(manifest, path.string());
    if (manifest) {
        const auto again = manifest_from_json(manifest_to_json(*manifest), path);
        if (!again) std::abort();  // what we write, we read
    }
}

void fuzz_settings(std::string_view text) {
    const auto settings = settings_from_json(text, "fuzz-settings.json");
    require_named(settings, "fuzz-settings.json");
    if (settings && !settings_from_json(settings_to_json(*settings), "again.json")) std::abort();
}

void fuzz_frames(std::string_view bytes) {
    const fs::path path = work_dir() / "frames.bin";
    write(path, bytes);
    auto reader = FrameFileReader::open(path);
    require_named(reader, path.string());
    if (!reader) return;
    for (int frames = 0; frames < 64; ++frames) {
        const auto frame = reader->next();
        require_named(frame, path.string());
        if (!frame) break;
        require_named(check_frame(*frame, path.string()), path.string());
    }
}

void fuzz_scan_record(std::string_view bytes) {
    if (bytes.size() < 2) return;
    const std::size_t json_size = std::min<std::size_t>(
        bytes.size() - 2, std::uint8_t(bytes[0]) | std::size_t(std::uint8_t(bytes[1])) << 8);
    const fs::path json = work_dir() / "000001.json";
    write(json, bytes.substr(2, json_size));
    write(work_dir() / "000001.ply", bytes.substr(2 + json_size));
    const auto scan = read_scan_record(json);
    if (!scan && scan.error().message.find(work_dir().string()) == std::string::npos) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::string_view rest(reinterpret_cast<const char*>(data) + 1, size - 1);
    switch (data[0] % 4) {
        case 0:
            fuzz_manifest(rest);
            break;
        case 1:
            fuzz_settings(rest);
            break;
        case 2:
            fuzz_frames(rest);
            break;
        default:
            fuzz_scan_record(rest);
            break;
    }
    return 0;
}
