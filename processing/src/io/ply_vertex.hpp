#pragma once
// Private to processing/src/io: where each vertex property of a PLY file goes in a
// PointCloud, and the binary fast path that decodes fixed-size vertex records with an
// offset table.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "anascan/processing/core/point_cloud.hpp"
#include "anascan/processing/io/ply.hpp"
#include "ply_header.hpp"
#include "ply_source.hpp"

namespace anascan::io::ply_detail {

/// The cloud attribute component a vertex property feeds.
enum class Slot : std::uint8_t {
    kNone,
    kX,
    kY,
    kZ,
    kNx,
    kNy,
    kNz,
    kRed,
    kGreen,
    kBlue,
    kIntensity,
    kConfidence,
    kExtra,  ///< A scalar we do not know by name, kept in PlyData::vertex_scalars.
};

/// At most this many unknown scalar properties are kept (the rest are skipped), so a file
/// of many small properties cannot make the reader allocate many times its size.
inline constexpr std::size_t kMaxExtraScalars = 8;

/// Which property feeds which slot; a group (position, normal, colour) counts only when
/// all three of its components are present, else its properties are skipped.
struct VertexPlan {
    std::vector<Slot> slots;  ///< One per property of the element.
    bool positions = false, normals = false, colors = false;
    bool intensity = false, confidence = false;
    std::vector<std::size_t> extras;  ///< Properties kept as extra scalars, in file order.
};

/// Plans the vertex element `element`.
VertexPlan plan_vertices(const PlyElement& element);

/// Sizes the cloud's attributes and the extra scalars for `count` points as the plan says.
void allocate(PointCloud& cloud, std::vector<PlyScalarProperty>& extras, const PlyElement& element,
              const VertexPlan& plan, std::size_t count);

/// Where one property's values go: value i to floats[i * stride] or bytes[i * stride].
struct VertexSink {
    float* floats = nullptr;
    std::uint8_t* bytes = nullptr;
    std::size_t stride = 0;
    PlyScalar type = PlyScalar::kFloat32;  ///< The file's type (colour scaling depends on it).
    /// Subtracted (in double) before storing: the cloud origin's component for positions of
    /// a file with an origin comment, whose coordinates are absolute.
    double offset = 0.0;
};

/// The sink of each property (no-op sinks for skipped ones); call after allocate().
/// Position sinks subtract `cloud.origin_m` (set it first).
std::vector<VertexSink> make_sinks(PointCloud& cloud, std::vector<PlyScalarProperty>& extras,
                                   const PlyElement& element, const VertexPlan& plan);

/// A PLY colour value as 8 bits: float types scale 0..1 to 0..255, 16-bit types scale
/// 0..65535 to 0..255, other integers clamp to 0..255; NaN gives 0.
std::uint8_t to_color(double value, PlyScalar type);

inline void store(const VertexSink& sink, std::size_t i, double value) {
    if (sink.floats != nullptr) {
        sink.floats[i * sink.stride] = static_cast<float>(value - sink.offset);
    } else if (sink.bytes != nullptr) {
        sink.bytes[i * sink.stride] = to_color(value, sink.type);
    }
}

/// One used property of a fixed-size binary record. `run == 3` marks three float32
/// components stored contiguously in the file and in the cloud (x y z): one 12-byte copy.
struct FixedField {
    std::size_t offset = 0;
    VertexSink sink;
    int run = 1;
};

/// The offset table of a list-free vertex element; runs are merged only when `merge_runs`
/// (i.e. the file's byte order is the machine's).
std::vector<FixedField> fixed_fields(const PlyElement& element, const VertexPlan& plan,
                                     std::span<const VertexSink> sinks, bool merge_runs);

/// Decodes `count` records of `record_bytes` starting at `base` through the offset table.
template <bool kSwap>
void decode_fixed_records(const char* base, std::size_t count, std::size_t record_bytes,
                          std::span<const FixedField> fields) {
    for (std::size_t i = 0; i < count; ++i) {
        const char* record = base + i * record_bytes;
        for (const FixedField& field : fields) {
            const VertexSink& sink = field.sink;
            if (!kSwap && field.run == 3) {
                std::memcpy(sink.floats + i * sink.stride, record + field.offset, 12);
            } else if (sink.type == PlyScalar::kFloat32 && sink.floats != nullptr &&
                       sink.offset == 0.0) {
                sink.floats[i * sink.stride] = load<float, kSwap>(record + field.offset);
            } else {
                store(sink, i, load_scalar<kSwap>(record + field.offset, sink.type));
            }
        }
    }
}

}  // namespace anascan::io::ply_detail
