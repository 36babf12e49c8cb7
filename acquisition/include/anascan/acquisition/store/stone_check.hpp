#pragma once
/// \file
/// Whether a capture would add another stone to a session: a session documents one stone,
/// and scans of two stones in one session make a model of neither. Used by `anascan
/// capture` before it adds scans to an existing session; the field app can ask the same.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "anascan/acquisition/store/session_store.hpp"

namespace anascan::acquisition {

/// The scene a simulated device URI looks at, without a "-turned" suffix (the same stone
/// turned over): `sim:structured-light/small-block-turned` -> "small-block". Empty for a
/// URI that names no scene (real devices).
std::string stone_of_device(std::string_view device_uri);

/// Why scans from `device_uri` would belong to another stone than the session's scans so
/// far (read from the devices that captured them), or nullopt when nothing says so. Only
/// devices that name their scene can tell: a real scanner looks at whatever stone is in
/// the tent.
std::optional<std::string> another_stone_reason(const std::vector<DeviceRecord>& devices,
                                                std::string_view device_uri);

}  // namespace anascan::acquisition
