#pragma once
/// \file
/// Whether a new scan of a session shows the session's stone: a session documents one
/// stone, and scans of two stones in one session make a model of neither. Decided from the
/// scans' geometry only (a real scanner names no stone): a scan the live registrar joined
/// to the model is of the stone; one that joined nothing is compared with the model by
/// processing's pose-free size and surface signals (`compare_with_stone`), and one the
/// registrar fitted onto the stone and then took out because the fit contradicts the stone
/// (a flagged scan) is treated as another object: a stone seen again fits without
/// contradiction, and a smaller stone of the same kind passes both pose-free signals. Used by
/// `anascan capture` on the first scan it adds to a session that has a model; see
/// docs/stone-check.md.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "anascan/acquisition/live/live_registration.hpp"
#include "anascan/acquisition/store/session_store.hpp"
#include "anascan/processing/core/expected.hpp"
#include "anascan/processing/evaluation/stone_identity.hpp"

namespace anascan::acquisition {

enum class StoneCheckOutcome {
    kNoModel,     ///< No registered scan before this one: nothing to compare with.
    kJoined,      ///< The registrar joined the scan to earlier scans: the same stone.
    kLooksSame,   ///< Not joined, but size and surface fit (the other side, usually).
    kUndecided,   ///< Not joined; the size fits, the surface could not be compared.
    kOtherStone,  ///< Not joined, and its size, surface or a contradicted fit says another.
};

/// "no-model", "joined", "looks-same", "undecided", "other-stone".
const char* to_string(StoneCheckOutcome outcome);

struct StoneCheckConfig {
    std::size_t max_model_scans = 8;  ///< Model scans compared (spread over the capture order).
    StoneIdentityConfig identity{};
    LiveRegistrationConfig registration{};  ///< Its `prepare` reduces the scans.
};

struct StoneCheck {
    StoneCheckOutcome outcome = StoneCheckOutcome::kNoModel;
    std::int64_t seq = 0;
    int model_group = -1;
    std::int64_t model_scan = 0;     ///< A scan of the model (0: none): it keeps its group.
    StoneIdentityEvidence evidence;  ///< Filled when the scan was not joined.
    /// Why the registrar took the scan out of the group it had fitted it into, if it did.
    std::string contradiction;
    std::string message;  ///< One line for the operator.
};

/// Decides for the saved, registered scan `seq` (the registration worker has caught up):
/// the model is the largest group of the other scans.
Expected<StoneCheck> check_stone_of_scan(const SessionStore& store, std::int64_t seq,
                                         const StoneCheckConfig& config = {});

/// The scans after `after_seq` that are not in `model_group`, nor excluded already: what a
/// capture of another stone added, to be set aside when the operator refuses it.
std::vector<std::int64_t> scans_outside_model(const std::vector<ScanRecord>& scans,
                                              std::int64_t after_seq, int model_group);

/// A later scan of a capture whose first scan joined no part of the stone: kJoined once it
/// is in the group of the model's scan `model_seq` (the stone is confirmed); kOtherStone, with
/// the figures, when the registrar fitted it onto the stone and took it back as
/// contradicting it (a flagged scan); kUndecided otherwise (its own group, or joined to the
/// earlier new scans).
Expected<StoneCheck> check_later_scan(const SessionStore& store, std::int64_t seq,
                                      std::int64_t model_seq, const StoneCheckConfig& config = {});

}  // namespace anascan::acquisition
