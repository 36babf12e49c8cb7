#include "poisson.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace anascan::surface_detail {
namespace {

// Memory of Open3D's Poisson: a part per sample and a part per surface cell of the finest
// level (about one per merged sample when the cell equals the resolution, fewer when it is
// coarser). The bunny at 0.5 mm (235,064 samples, depth 9) estimates 705 MB for a measured
// peak of 531 MB (docs/surface-reconstruction.md): a bound, not a prediction.
constexpr double kBytesPerPoint = 100.0, kBytesPerCell = 1300.0;
constexpr int kMinDepth = 5, kMaxDepth = 12;

}  // namespace

PoissonDepth choose_depth(double box_m, double finest_cell_m, double resolution_m,
                          std::size_t points, std::size_t max_memory_bytes) {
    PoissonDepth d;
    d.depth = std::clamp(static_cast<int>(std::ceil(std::log2(box_m / finest_cell_m))), kMinDepth,
                         kMaxDepth);
    for (;; --d.depth) {
        d.cell_m = box_m / std::ldexp(1.0, d.depth);
        const double cells_per_sample = std::pow(resolution_m / d.cell_m, 2.0);
        d.estimated_memory_bytes = static_cast<std::size_t>(
            double(points) * (kBytesPerPoint + kBytesPerCell * cells_per_sample));
        if (d.estimated_memory_bytes <= max_memory_bytes || d.depth == kMinDepth) break;
    }
    return d;
}

namespace {

using PoissonEntry = void (*)(const PointCloud&, const PoissonParams&, Mesh&);

/// Where the module is: $ANASCAN_POISSON_MODULE, else beside the running program or where
/// an installation puts it relative to the program (BINDIR/../LIBDIR/anascan), else where
/// this build put it.
std::vector<std::string> module_candidates() {
    if (const char* given = std::getenv("ANASCAN_POISSON_MODULE"); given && *given) return {given};
    std::vector<std::string> paths;
    std::error_code ec;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        paths.push_back((self.parent_path() / kModuleName).string());
        paths.push_back(
            (self.parent_path() / ANASCAN_POISSON_MODULE_FROM_BIN / kModuleName).string());
    }
    paths.push_back(ANASCAN_POISSON_MODULE_BUILT);
    return paths;
}

Expected<PoissonEntry> load_module() {
    std::string errors;
    for (const std::string& path : module_candidates()) {
        // Never closed: the solver stays loaded for the process's life.
        void* module = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (module == nullptr) {
            errors += std::string(errors.empty() ? "" : "; ") + ::dlerror();
            continue;
        }
        if (void* entry = ::dlsym(module, "anascan_poisson_surface_v1"))
            return reinterpret_cast<PoissonEntry>(entry);
        errors += (errors.empty() ? "" : "; ") + path + ": no anascan_poisson_surface_v1";
    }
    return fail(ErrorCode::kIo, std::string("cannot load the screened Poisson module ") +
                                    kModuleName +
                                    " (set ANASCAN_POISSON_MODULE to its path): " + errors);
}

}  // namespace

Expected<Mesh> poisson_surface(const PointCloud& cloud, const PoissonParams& params) {
    static const Expected<PoissonEntry> entry = load_module();
    if (!entry) return fail(entry.error());
    Mesh mesh;
    (*entry)(cloud, params, mesh);
    return mesh;
}

}  // namespace anascan::surface_detail
