// The names of block statuses and hole kinds, as the features files store them (kept apart
// from the feature extraction so that the readers of those files need nothing else).
#include "anascan/processing/reassembly/block_features.hpp"

namespace anascan::reassembly {

const char* to_string(BlockStatus status) {
    switch (status) {
        case BlockStatus::kOk:
            return "ok";
        case BlockStatus::kEmpty:
            return "empty";
        case BlockStatus::kNoNormals:
            return "no normals";
        case BlockStatus::kBadMesh:
            return "bad mesh";
        case BlockStatus::kNonManifold:
            return "non-manifold";
        case BlockStatus::kNoPlanarFace:
            return "no planar face";
        case BlockStatus::kTooFewFaces:
            return "too few faces";
        case BlockStatus::kTooNoisy:
            return "too noisy";
    }
    return "unknown";
}

const char* to_string(HoleKind kind) {
    return kind == HoleKind::kClampChannel ? "clamp channel" : "dowel";
}

}  // namespace anascan::reassembly
