#pragma once
// Peak memory of the benchmark process, and where it rose: for the scale benchmarks.
#include <sys/resource.h>

#include <cstdio>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace anascan::bench {

inline double peak_rss_mb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes.
}

// The process's peak resident set so far (VmHWM of /proc/self/status), megabytes.
inline double high_water_mb() {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0.0;
    char line[256];
    double kb = 0.0;
    while (std::fgets(line, sizeof line, f)) {
        if (std::sscanf(line, "VmHWM: %lf kB", &kb) == 1) break;
    }
    std::fclose(f);
    return kb / 1024.0;
}

// Where the peak resident set rose (by more than 0.5 MB since the last record): between
// which two progress messages, so that the stage holding the peak can be named.
struct PeakTrace {
    double last_mb = 0.0;
    std::string previous = "start";
    std::vector<std::pair<double, std::string>> rises;

    void observe(std::string_view message) {
        const double mb = high_water_mb();
        if (mb > last_mb + 0.5) {
            last_mb = mb;
            rises.emplace_back(mb,
                               "after '" + previous + "', before '" + std::string(message) + "'");
        }
        previous = message;
    }
    void print() const {
        for (std::size_t k = rises.size() > 6 ? rises.size() - 6 : 0; k < rises.size(); ++k)
            std::printf("peak RSS rose to %.1f MB %s\n", rises[k].first, rises[k].second.c_str());
    }
};

}  // namespace anascan::bench
