#include "schema.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <limits>

namespace anascan::io::e57 {
namespace {

constexpr double kQuaternionNormTolerance = 1e-3;
constexpr int kMaxPrototypeDepth = 8;

std::string_view trimmed(std::string_view s) {
    const auto first = s.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

template <class T>
Expected<T> parse_number(std::string_view text, T empty_value, const XmlNode& node,
                         const XmlSource& where, std::string_view what) {
    const std::string_view s = trimmed(text);
    if (s.empty()) return empty_value;
    T value{};
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
    if (ec != std::errc() || end != s.data() + s.size()) {
        return fail(where.error(ErrorCode::kFormat, node.xml_byte,
                                std::string(what) + ": '" + std::string(s) + "' is not a number"));
    }
    if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(value)) {
            return fail(where.error(ErrorCode::kFormat, node.xml_byte,
                                    std::string(what) + " is not finite"));
        }
    }
    return value;
}

template <class T>
Expected<T> attribute_number(const XmlNode& node, std::string_view key, T default_value,
                             const XmlSource& where) {
    const std::string* a = node.attribute(key);
    if (!a) return default_value;
    return parse_number<T>(*a, default_value, node, where, node.name + " " + std::string(key));
}

// The value of child `name` of a Structure (a Float or Integer element), 0 when absent.
Expected<double> child_value(const XmlNode& parent, std::string_view name, const XmlSource& where) {
    const XmlNode* c = parent.child(name);
    if (!c) return 0.0;
    if (c->type() == "ScaledInteger") {
        const auto raw = parse_number<std::int64_t>(c->text, 0, *c, where, c->name);
        if (!raw) return fail(raw.error());
        const auto scale = attribute_number<double>(*c, "scale", 1.0, where);
        if (!scale) return fail(scale.error());
        const auto offset = attribute_number<double>(*c, "offset", 0.0, where);
        if (!offset) return fail(offset.error());
        return double(*raw) * *scale + *offset;
    }
    return parse_number<double>(c->text, 0.0, *c, where, parent.name + "/" + std::string(name));
}

Expected<Pose> read_pose(const XmlNode& pose, const XmlSource& where) {
    std::array<double, 7> v{};  // w x y z of the rotation, then x y z of the translation
    const XmlNode* rotation = pose.child("rotation");
    const XmlNode* translation = pose.child("translation");
    std::size_t k = 0;
    for (const char* axis : {"w", "x", "y", "z"}) {
        if (!rotation) break;
        const auto value = child_value(*rotation, axis, where);
        if (!value) return fail(value.error());
        v[k++] = *value;
    }
    if (!rotation) v[0] = 1.0;
    for (std::size_t i = 0; i < 3 && translation; ++i) {
        const auto value = child_value(*translation, std::string(1, char('x' + i)), where);
        if (!value) return fail(value.error());
        v[4 + i] = *value;
    }
    Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
    if (!(std::abs(q.norm() - 1.0) <= kQuaternionNormTolerance)) {
        return fail(where.error(
            ErrorCode::kFormat, pose.xml_byte,
            "pose: the rotation quaternion has norm " + std::to_string(q.norm()) + ", not 1"));
    }
    Pose T = Pose::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(v[4], v[5], v[6]);
    return T;
}

Expected<FieldSpec> read_field(const XmlNode& node, std::string name, const XmlSource& where) {
    FieldSpec f{.name = std::move(name)};
    const std::string_view type = node.type();
    if (type == "Float") {
        const std::string* precision = node.attribute("precision");
        f.kind = FieldKind::kFloat;
        f.single_precision = precision && *precision == "single";
        f.bits = f.single_precision ? 32 : 64;
        return f;
    }
    if (type != "Integer" && type != "ScaledInteger") {
        return fail(where.error(ErrorCode::kUnsupported, node.xml_byte,
                                "prototype field '" + f.name + "' of type '" + std::string(type) +
                                    "' (this reader decodes Integer, ScaledInteger and Float)"));
    }
    f.kind = type == "Integer" ? FieldKind::kInteger : FieldKind::kScaledInteger;
    const auto lo = attribute_number<std::int64_t>(node, "minimum",
                                                   std::numeric_limits<std::int64_t>::min(), where);
    const auto hi = attribute_number<std::int64_t>(node, "maximum",
                                                   std::numeric_limits<std::int64_t>::max(), where);
    const auto scale = attribute_number<double>(node, "scale", 1.0, where);
    const auto offset = attribute_number<double>(node, "offset", 0.0, where);
    if (!lo) return fail(lo.error());
    if (!hi) return fail(hi.error());
    if (!scale) return fail(scale.error());
    if (!offset) return fail(offset.error());
    if (*hi < *lo || *scale == 0.0) {
        return fail(
            where.error(ErrorCode::kFormat, node.xml_byte,
                        "prototype field '" + f.name + "': maximum below minimum or zero scale"));
    }
    f.minimum = *lo;
    f.maximum = *hi;
    f.scale = *scale;
    f.offset = *offset;
    f.bits = bits_for_range(f.minimum, f.maximum);
    return f;
}

// Appends the terminal fields under `node` in bytestream (depth-first) order.
Expected<void> flatten(const XmlNode& node, const std::string& prefix, int depth,
                       const XmlSource& where, std::vector<FieldSpec>& out) {
    for (const XmlNode& c : node.children) {
        const std::string name = prefix.empty() ? c.name : prefix + "/" + c.name;
        if (c.type() == "Structure" || c.type() == "Vector") {
            if (depth >= kMaxPrototypeDepth) {
                return fail(
                    where.error(ErrorCode::kFormat, c.xml_byte, "prototype nested too deep"));
            }
            if (auto ok = flatten(c, name, depth + 1, where, out); !ok) return ok;
            continue;
        }
        auto field = read_field(c, name, where);
        if (!field) return fail(field.error());
        out.push_back(std::move(*field));
    }
    return {};
}

Expected<CompressedVectorSpec> read_compressed_vector(const XmlNode& node, const XmlSource& where) {
    CompressedVectorSpec cv{.xml_byte = node.xml_byte};
    if (node.type() != "CompressedVector") {
        return fail(where.error(ErrorCode::kFormat, node.xml_byte,
                                node.name + " is not a CompressedVector"));
    }
    const auto offset = attribute_number<std::uint64_t>(node, "fileOffset", 0, where);
    if (!offset) return fail(offset.error());
    const auto count = attribute_number<std::uint64_t>(node, "recordCount", 0, where);
    if (!count) return fail(count.error());
    cv.physical_offset = *offset;
    cv.record_count = *count;
    const XmlNode* prototype = node.child("prototype");
    if (!prototype) {
        return fail(
            where.error(ErrorCode::kFormat, node.xml_byte, node.name + " has no prototype"));
    }
    if (auto ok = flatten(*prototype, "", 0, where, cv.fields); !ok) return fail(ok.error());
    return cv;
}

Expected<void> read_color_limits(const XmlNode& scan, const XmlSource& where, ScanSpec& out) {
    const XmlNode* limits = scan.child("colorLimits");
    if (!limits) return {};
    const auto lo = child_value(*limits, "colorRedMinimum", where);
    const auto hi = child_value(*limits, "colorRedMaximum", where);
    if (!lo) return fail(lo.error());
    if (!hi) return fail(hi.error());
    if (*hi > *lo) {
        out.has_color_limits = true;
        out.color_minimum = *lo;
        out.color_maximum = *hi;
    }
    return {};
}

Expected<ScanSpec> read_scan(const XmlNode& scan, const XmlSource& where) {
    ScanSpec spec;
    if (const XmlNode* n = scan.child("name")) spec.name = std::string(trimmed(n->text));
    if (const XmlNode* g = scan.child("guid")) spec.guid = std::string(trimmed(g->text));
    if (const XmlNode* pose = scan.child("pose")) {
        auto T = read_pose(*pose, where);
        if (!T) return fail(T.error());
        spec.T_file_scan = *T;
    }
    const XmlNode* points = scan.child("points");
    if (!points) {
        return fail(where.error(ErrorCode::kFormat, scan.xml_byte,
                                "scan '" + spec.name + "' has no points element"));
    }
    auto cv = read_compressed_vector(*points, where);
    if (!cv) return fail(cv.error());
    spec.points = std::move(*cv);
    if (auto ok = read_color_limits(scan, where, spec); !ok) return fail(ok.error());
    return spec;
}

}  // namespace

int bits_for_range(std::int64_t minimum, std::int64_t maximum) {
    const std::uint64_t range = std::uint64_t(maximum) - std::uint64_t(minimum);
    return range == 0 ? 0 : 64 - std::countl_zero(range);
}

Expected<FileSpec> read_file_spec(const XmlNode& root, const XmlSource& where) {
    if (root.name != "e57Root") {
        return fail(where.error(ErrorCode::kFormat, root.xml_byte,
                                "the XML root is '" + root.name + "', expected e57Root"));
    }
    FileSpec spec;
    if (const XmlNode* g = root.child("guid")) spec.guid = std::string(trimmed(g->text));
    if (const XmlNode* images = root.child("images2D")) spec.image_count = images->children.size();
    const XmlNode* data3d = root.child("data3D");
    for (std::size_t i = 0; data3d && i < data3d->children.size(); ++i) {
        auto scan = read_scan(data3d->children[i], where);
        if (!scan) return fail(scan.error());
        if (scan->name.empty()) scan->name = "scan" + std::to_string(i);
        spec.scans.push_back(std::move(*scan));
    }
    return spec;
}

}  // namespace anascan::io::e57
