#pragma once
/// \file
/// Compact multi-view links (docs/multiview-refinement.md, "Compact links"). A link's fine
/// registration is accurate when it samples many source points (along a weakly constrained
/// direction its error falls with the square root of the samples), but storing every
/// correspondence for the multi-view solve costs memory per link. `compress_link` keeps an
/// evenly spread subset that has the same optimum and about the same stiffness as all of
/// them: the kept correspondences carry the weight of the whole set, and their target points
/// are shifted along their normals by the least amount that makes their point-to-plane
/// gradient vanish at the pose where the fine registration converged.
///
/// Thread safety: a pure function.

#include <cstddef>
#include <vector>

#include "anascan/processing/core/pose.hpp"
#include "anascan/processing/registration/fine/fine_registration.hpp"

namespace anascan {

/// At most `max_count` of `all` (unchanged when they are fewer, or `max_count` is 0), with
/// the optimum of `all` at `T_target_source` (the link's converged relative pose).
std::vector<FineCorrespondence> compress_link(std::vector<FineCorrespondence> all,
                                              const Pose& T_target_source, std::size_t max_count);

}  // namespace anascan
