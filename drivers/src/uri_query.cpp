#include "uri_query.hpp"

#include <charconv>

namespace anascan::drivers {
namespace {

template <class T>
Expected<T> query_number(const UriQuery& q, const std::string& key, T fallback,
                         const std::string& uri, const char* what) {
    const auto it = q.values.find(key);
    if (it == q.values.end()) return fallback;
    const std::string& text = it->second;
    T v{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || end != text.data() + text.size())
        return fail(ErrorCode::kInvalidArgument, uri + ": " + key + "=" + text + " is not " + what);
    return v;
}

}  // namespace

Expected<UriQuery> parse_uri_query(const std::string& uri, const std::string& target,
                                   std::initializer_list<const char*> known) {
    UriQuery q;
    const std::size_t mark = target.find('?');
    q.path = target.substr(0, mark);
    std::string rest = mark == std::string::npos ? "" : target.substr(mark + 1);
    while (!rest.empty()) {
        const std::size_t amp = rest.find('&');
        const std::string item = rest.substr(0, amp);
        const std::size_t eq = item.find('=');
        if (eq == std::string::npos || eq == 0)
            return fail(ErrorCode::kInvalidArgument, uri + ": '" + item + "' is not KEY=VALUE");
        q.values[item.substr(0, eq)] = item.substr(eq + 1);
        rest = amp == std::string::npos ? "" : rest.substr(amp + 1);
    }
    for (const auto& entry : q.values) {
        bool ok = false;
        std::string list;
        for (const char* k : known) {
            ok = ok || entry.first == k;
            list += (list.empty() ? "" : ", ") + std::string(k);
        }
        if (!ok)
            return fail(ErrorCode::kInvalidArgument,
                        uri + ": unknown key '" + entry.first + "' (known: " + list + ")");
    }
    return q;
}

Expected<int> query_int(const UriQuery& q, const std::string& key, int fallback,
                        const std::string& uri) {
    return query_number<int>(q, key, fallback, uri, "an integer");
}

Expected<double> query_double(const UriQuery& q, const std::string& key, double fallback,
                              const std::string& uri) {
    return query_number<double>(q, key, fallback, uri, "a number");
}

Expected<std::unique_ptr<Camera>> open_as_camera(const DeviceRegistry& registry,
                                                 const std::string& uri) {
    auto device = registry.open(uri);
    if (!device) return fail(device.error());
    if ((*device)->as_camera() == nullptr)
        return fail(ErrorCode::kUnsupported, uri + ": not a camera");
    std::unique_ptr<Camera> camera((*device)->as_camera());
    (void)device->release();
    return camera;
}

}  // namespace anascan::drivers
