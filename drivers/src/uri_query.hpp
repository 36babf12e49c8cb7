#pragma once
// What the composed devices (`sl:`, `depth:`) share: the query of their URI target,
// `PATH?key=value&key=value` (the nested camera URIs stay readable, unknown keys are
// errors), and opening a part by URI as a camera.

#include <initializer_list>
#include <map>
#include <string>

#include "anascan/drivers/camera.hpp"
#include "anascan/drivers/device_registry.hpp"
#include "anascan/processing/core/expected.hpp"

namespace anascan::drivers {

struct UriQuery {
    std::string path;                           ///< Before the '?'.
    std::map<std::string, std::string> values;  ///< key -> value.
};

/// Splits `target`; kInvalidArgument (naming `uri`) for an item that is not KEY=VALUE or a
/// key not in `known` (the message lists them).
Expected<UriQuery> parse_uri_query(const std::string& uri, const std::string& target,
                                   std::initializer_list<const char*> known);

/// The value of `key` as an integer or a number; `fallback` when absent; kInvalidArgument
/// naming `uri` and the key when it does not parse.
Expected<int> query_int(const UriQuery& q, const std::string& key, int fallback,
                        const std::string& uri);
Expected<double> query_double(const UriQuery& q, const std::string& key, double fallback,
                              const std::string& uri);

/// Opens `uri` with `registry`; kUnsupported when it is not a camera.
Expected<std::unique_ptr<Camera>> open_as_camera(const DeviceRegistry& registry,
                                                 const std::string& uri);

}  // namespace anascan::drivers
