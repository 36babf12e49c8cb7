#pragma once
// How the session database stores poses, vectors, times and enums as text/integers.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "anascan/acquisition/store/session_store.hpp"

namespace anascan::acquisition::codec {

/// 16 numbers, row-major, space separated, round-trip precision.
std::string pose_to_text(const Pose& T);
/// Inverse of pose_to_text; nullopt when not 16 finite numbers with a rigid last row.
std::optional<Pose> pose_from_text(std::string_view text);
std::optional<std::string> pose_to_text(const std::optional<Pose>& T);

std::optional<std::string> vector_to_text(const std::optional<Eigen::Vector3d>& v);
std::optional<Eigen::Vector3d> vector_from_text(std::string_view text);

std::int64_t to_ns(TimePoint t);
TimePoint from_ns(std::int64_t ns);

/// Inverse of anascan::to_string(DeviceKind); kUnknown for an unknown name.
DeviceKind device_kind_from_string(std::string_view name);

}  // namespace anascan::acquisition::codec
