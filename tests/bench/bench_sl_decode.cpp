// `anascan sl decode` against OpenCV's own Gray-code stereo path, same images, one run.
// Ours: the whole command as a process (start-up, 88 JPEGs, decoding, triangulation, PLY
// written). OpenCV: in process, as opencv_contrib's structured_light pointcloud sample does
// it (imread grey + remap with the stored R1/R2/P1/P2, GrayCodePattern::decode,
// reprojectImageTo3D); no start-up, no file written, i.e. in OpenCV's favour.
// Usage: anascan_bench_sl_decode [SIDE [REPEATS]]   (SIDE: statue_front_side by default)

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "anascan/drivers/structured_light/image_files.hpp"
#include "sl_reference.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// User + system CPU time of this process (or of its finished children), seconds.
double cpu_seconds(int who) {
    rusage u{};
    ::getrusage(who, &u);
    const auto s = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
    return s(u.ru_utime) + s(u.ru_stime);
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

std::string load_average() {
    std::ifstream in("/proc/loadavg");
    std::string a, b, c;
    in >> a >> b >> c;
    return a + " " + b + " " + c;
}

/// Median wall time of the command over `repeats` runs, seconds; its stdout in `report`,
/// its mean CPU time (user + system) in `cpu_s`.
double time_command(const std::string& side_dir, int threads, int repeats, std::string& report,
                    double& cpu_s) {
    const fs::path out = fs::temp_directory_path() / "anascan_bench_sl.ply";
    const fs::path log = fs::temp_directory_path() / "anascan_bench_sl.txt";
    const std::string cmd = std::string(ANASCAN_CLI) + " -q sl decode --calibration " +
                            ANASCAN_STATUE_DIR "/calibrationParameters.yml --cam1 '" + side_dir +
                            "/pattern_cam1_im*.jpg' --cam2 '" + side_dir +
                            "/pattern_cam2_im*.jpg' --swap-cameras --threads " +
                            std::to_string(threads) + " --out " + out.string() + " > " +
                            log.string();
    std::vector<double> times;
    const double cpu0 = cpu_seconds(RUSAGE_CHILDREN);
    for (int i = 0; i < repeats; ++i) {
        const auto t0 = Clock::now();
        if (std::system(cmd.c_str()) != 0) return -1.0;
        times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    }
    cpu_s = (cpu_seconds(RUSAGE_CHILDREN) - cpu0) / repeats;
    std::ifstream in(log);
    report.clear();
    for (std::string line; std::getline(in, line);) report += line + "\n";
    fs::remove(out);
    fs::remove(log);
    return median(times);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string side = argc > 1 ? argv[1] : "statue_front_side";
    const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
    const std::string dir = std::string(ANASCAN_STATUE_DIR) + "/" + side;
    auto cam1 = anascan::drivers::sl::glob_natural(dir + "/pattern_cam1_im*.jpg");
    auto cam2 = anascan::drivers::sl::glob_natural(dir + "/pattern_cam2_im*.jpg");
    if (!cam1 || !cam2) {
        std::printf("skipped: GSoC statue data absent (%s)\n", dir.c_str());
        return 0;
    }
    std::printf("%s, %zu + %zu JPEGs; %u hardware threads; load average before: %s\n", side.c_str(),
                cam1->size(), cam2->size(), std::thread::hardware_concurrency(),
                load_average().c_str());
    std::string report;
    double cpu_all = 0.0, cpu_one = 0.0;
    const double ours_all = time_command(dir, 0, repeats, report, cpu_all);
    std::printf("anascan sl decode, all cores: %.3f s wall (median of %d), %.3f s CPU\n%s",
                ours_all, repeats, cpu_all, report.c_str());
    const double ours_one = time_command(dir, 1, repeats, report, cpu_one);
    std::printf("anascan sl decode, 1 thread:  %.3f s wall (median of %d), %.3f s CPU\n", ours_one,
                repeats, cpu_one);
    std::vector<double> peer_times;
    const double peer_cpu0 = cpu_seconds(RUSAGE_SELF);
    anascan::test::OpenCvGrayCodeResult peer;
    for (int i = 0; i < std::max(1, repeats / 2); ++i) {
        peer = anascan::test::run_opencv_graycode(ANASCAN_STATUE_DIR "/calibrationParameters.yml",
                                                  *cam1, *cam2, 1280, 800);
        if (!peer.ok) {
            std::printf("OpenCV path failed: %s\n", peer.error.c_str());
            return 1;
        }
        peer_times.push_back(peer.total_s);
    }
    const double opencv = median(peer_times);
    const double opencv_cpu = (cpu_seconds(RUSAGE_SELF) - peer_cpu0) / double(peer_times.size());
    std::printf(
        "OpenCV path: %.3f s wall (load+rectify %.3f s, decode %.3f s), %.3f s CPU, "
        "%zu points\n",
        opencv, peer.load_s, peer.decode_s, opencv_cpu, peer.cloud.size());
    if (ours_all <= 0.0 || ours_one <= 0.0) {
        std::printf("anascan sl decode failed\n");
        return 1;
    }
    std::printf(
        "speed-up (OpenCV / ours), wall: %.1fx on all cores, %.1fx on 1 thread; "
        "CPU time: %.1fx\n",
        opencv / ours_all, opencv / ours_one, opencv_cpu / cpu_all);
    std::printf("load average after: %s\n", load_average().c_str());
    return 0;
}
