#include "anascan/drivers/structured_light/image_files.hpp"

#include <glob.h>
#include <sys/mman.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdint>
#include <optional>

#include "anascan/drivers/grey_image.hpp"

namespace anascan::drivers::sl {
namespace {

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

/// Compares the digit runs starting at a[i] and b[j] numerically (leading zeros ignored);
/// advances i and j past them. Returns <0, 0, >0.
int compare_numbers(std::string_view a, std::size_t& i, std::string_view b, std::size_t& j) {
    const auto run = [](std::string_view s, std::size_t& k) {
        while (k < s.size() && s[k] == '0') ++k;
        const std::size_t start = k;
        while (k < s.size() && is_digit(s[k])) ++k;
        return s.substr(start, k - start);
    };
    const std::string_view x = run(a, i), y = run(b, j);
    if (x.size() != y.size()) return x.size() < y.size() ? -1 : 1;
    return x.compare(y);
}

}  // namespace

bool natural_less(std::string_view a, std::string_view b) {
    std::size_t i = 0, j = 0;
    while (i < a.size() && j < b.size()) {
        if (is_digit(a[i]) && is_digit(b[j])) {
            if (const int c = compare_numbers(a, i, b, j); c != 0) return c < 0;
            continue;
        }
        if (a[i] != b[j]) return a[i] < b[j];
        ++i;
        ++j;
    }
    if ((a.size() - i) != (b.size() - j)) return (a.size() - i) < (b.size() - j);
    return a < b;  // Equal by numbers ("im01" vs "im1"): fall back to bytes, for a total order.
}

Expected<std::vector<std::filesystem::path>> glob_natural(const std::string& pattern) {
    glob_t g{};
    const int rc = ::glob(pattern.c_str(), GLOB_MARK, nullptr, &g);
    std::vector<std::filesystem::path> files;
    if (rc == 0) {
        for (std::size_t k = 0; k < g.gl_pathc; ++k) {
            const std::string p = g.gl_pathv[k];
            if (!p.empty() && p.back() != '/') files.emplace_back(p);
        }
    }
    ::globfree(&g);
    if (rc != 0 && rc != GLOB_NOMATCH)
        return fail(ErrorCode::kIo, pattern + ": cannot read the folder");
    if (files.empty()) return fail(ErrorCode::kIo, pattern + ": no file matches");
    std::sort(files.begin(), files.end(),
              [](const auto& a, const auto& b) { return natural_less(a.string(), b.string()); });
    return files;
}

namespace {

/// One uninitialised block for `count` grey images of `size`, rows of image i at
/// [i * height, (i + 1) * height). The block is asked for huge pages: first touching
/// 2.4 MB images in 4 KiB pages cost more kernel time than decoding the JPEGs did
/// (docs/structured-light.md, "Speed").
cv::Mat image_block(cv::Size size, std::size_t count) {
    cv::Mat block(size.height * int(count), size.width, CV_8UC1);
    constexpr std::uintptr_t kHuge = std::uintptr_t(2) << 20;
    const auto begin = reinterpret_cast<std::uintptr_t>(block.data);
    const std::uintptr_t end = begin + block.total();
    const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
    const std::uintptr_t last = end & ~(kHuge - 1);
    if (last > first) ::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
    return block;
}

}  // namespace

Expected<std::vector<cv::Mat>> load_grey_images(
    std::span<const std::filesystem::path> files,
    const std::function<void(std::size_t done)>& on_loaded) {
    std::vector<cv::Mat> images(files.size());
    if (files.empty()) return images;
    if (auto ok = read_grey_image(files[0], images[0]); !ok) return fail(ok.error());
    if (files.size() > 1) {
        // Each image is decoded in place into its rows of one block (an image of another
        // size gets a buffer of its own, and the decoder then refuses the sequence).
        const cv::Mat first = images[0];
        const cv::Mat block = image_block(first.size(), files.size());
        for (std::size_t i = 0; i < files.size(); ++i)
            images[i] = block.rowRange(int(i) * first.rows, int(i + 1) * first.rows);
        first.copyTo(images[0]);
    }
    std::vector<std::optional<Error>> errors(files.size());
    std::atomic<std::size_t> done{1};
    if (on_loaded) on_loaded(1);
    tbb::parallel_for(std::size_t(1), files.size(), [&](std::size_t i) {
        if (auto ok = read_grey_image(files[i], images[i]); !ok) errors[i] = ok.error();
        const std::size_t n = ++done;
        if (on_loaded) on_loaded(n);
    });
    for (const std::optional<Error>& error : errors)
        if (error) return fail(*error);
    return images;
}

}  // namespace anascan::drivers::sl
