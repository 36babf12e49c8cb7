// LiveRegistrar: merging groups by the capture order. The operator walks around the stone, so
// a scan's neighbours in the order predict its pose (the motion priors, run backwards from
// the scans after it). A scan that opened a group of its own because it did not register
// against the one before it (e.g. scan 2 of the demo session: 37° from scan 1, and their
// 2 mm copies let the pair slide) is placed by the scans that follow once they are in
// another group, and the two groups merge. See docs/live-registration.md.
#include "live/state.hpp"

namespace anascan::acquisition {
namespace {

/// Entries a group must gain before a sequence merge with it is tried again.
constexpr std::size_t kRetryAfterScans = 3;

}  // namespace

std::vector<live::Prior> LiveRegistrar::State::sequence_priors(std::size_t i, int group,
                                                               int direction) const {
    std::vector<Pose> neighbours;
    for (std::ptrdiff_t j = static_cast<std::ptrdiff_t>(i) + direction;
         j >= 0 && j < static_cast<std::ptrdiff_t>(scans.size()) && neighbours.size() < 3;
         j += direction) {
        const live::ScanEntry& n = scans[static_cast<std::size_t>(j)];
        if (n.excluded || !n.flagged.empty()) continue;
        if (!live::active(n) || n.group != group || n.side != scans[i].side) break;
        neighbours.push_back(n.T_group_scan);
    }
    return live::motion_priors(neighbours);
}

std::optional<std::vector<PoseUpdate>> LiveRegistrar::State::sequence_merge(std::size_t i,
                                                                            int direction) {
    const std::ptrdiff_t j = static_cast<std::ptrdiff_t>(i) + direction;
    if (j < 0 || j >= static_cast<std::ptrdiff_t>(scans.size())) return std::nullopt;
    const live::ScanEntry& next = scans[static_cast<std::size_t>(j)];
    if (!live::active(next) || next.group == scans[i].group || next.side != scans[i].side)
        return std::nullopt;
    const int into = next.group;
    const std::size_t size = members(into).size();
    auto [it, first] = sequence_merge_tried.try_emplace({i, direction}, size);
    if (!first && size < it->second + kRetryAfterScans) return std::nullopt;
    it->second = size;
    ++report.merge_attempts;
    for (const auto& [name, T] : sequence_priors(i, into, direction)) {
        // A merge moves a whole group: only the usual bound on the correction.
        live::Verified v = verify_hypothesis(scans[i], into, T, live::CorrectionCheck::kBound);
        if (!v.rejection.empty()) continue;
        // T_into_from maps the scan's group into `into`; the lower id survives.
        const int from = scans[i].group;
        const Pose T_into_from =
            orthonormalized(v.fine.T_target_source * scans[i].T_group_scan.inverse());
        return into < from ? merge(into, from, T_into_from)
                           : merge(from, into, orthonormalized(T_into_from.inverse()));
    }
    return std::vector<PoseUpdate>{};  // One try per call: a new scan may be waiting.
}

std::vector<PoseUpdate> LiveRegistrar::State::merge_by_sequence() {
    for (std::size_t i = 0; i < scans.size(); ++i) {
        if (!live::active(scans[i])) continue;
        for (const int direction : {+1, -1}) {
            if (auto done = sequence_merge(i, direction)) return std::move(*done);
        }
    }
    return {};
}

}  // namespace anascan::acquisition
