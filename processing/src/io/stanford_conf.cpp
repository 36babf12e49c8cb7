#include "anascan/processing/io/stanford_conf.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "anascan/processing/io/file_bytes.hpp"
#include "text_lines.hpp"

namespace anascan::io {
namespace {

constexpr double kMinQuaternionNorm = 1e-6;
constexpr std::size_t kPoseFields = 7;
constexpr std::string_view kBmeshUsage = "'bmesh FILE tx ty tz qx qy qz qw'";
constexpr std::string_view kCameraUsage = "'camera tx ty tz qx qy qz qw'";

// Fields [first, first + 7) as "tx ty tz qx qy qz qw", meaning p_world = R(q)^T p + t.
Expected<Pose> parse_pose(const text::Fields& fields, std::size_t first, text::LineRef where) {
    std::array<double, kPoseFields> v{};
    if (auto ok = text::parse_doubles(fields, first, v, where); !ok) return fail(ok.error());
    // Scale before taking the norm so that huge or tiny components neither overflow nor
    // underflow; the quaternion is normalised anyway.
    const double scale = std::max({std::abs(v[3]), std::abs(v[4]), std::abs(v[5]), std::abs(v[6])});
    const Eigen::Quaterniond q =
        scale > 0.0 ? Eigen::Quaterniond(v[6] / scale, v[3] / scale, v[4] / scale, v[5] / scale)
                    : Eigen::Quaterniond(0.0, 0.0, 0.0, 0.0);
    if (q.norm() * scale < kMinQuaternionNorm) {
        return text::line_error(ErrorCode::kFormat, where,
                                "quaternion (qx qy qz qw) has near-zero norm");
    }
    return make_pose(q.conjugate(), Eigen::Vector3d(v[0], v[1], v[2]));
}

Unexpected<Error> field_count_error(std::string_view usage, const text::Fields& fields,
                                    text::LineRef where) {
    return text::line_error(
        ErrorCode::kFormat, where,
        "expected " + std::string(usage) + ", found " + std::to_string(fields.count) + " fields");
}

// Parses one line into `conf`; `first_line_of` maps file names to the line that named them.
Expected<void> parse_line(const text::Fields& fields, text::LineRef where, StanfordConf& conf,
                          std::unordered_map<std::string, int>& first_line_of) {
    const std::string_view keyword = fields[0];
    if (keyword == "camera") {
        if (fields.count != 1 + kPoseFields) return field_count_error(kCameraUsage, fields, where);
        if (conf.camera) return text::line_error(ErrorCode::kFormat, where, "second 'camera' line");
        const Expected<Pose> pose = parse_pose(fields, 1, where);
        if (!pose) return fail(pose.error());
        conf.camera = *pose;
        return {};
    }
    if (keyword != "bmesh") {
        return text::line_error(ErrorCode::kFormat, where,
                                "unknown keyword '" + std::string(keyword.substr(0, 32)) +
                                    "' (expected 'bmesh' or 'camera')");
    }
    if (fields.count != 2 + kPoseFields) return field_count_error(kBmeshUsage, fields, where);
    const Expected<Pose> pose = parse_pose(fields, 2, where);
    if (!pose) return fail(pose.error());
    const auto [it, inserted] = first_line_of.emplace(std::string(fields[1]), where.line);
    if (!inserted) {
        return text::line_error(ErrorCode::kFormat, where,
                                "duplicate file '" + it->first + "' (first on line " +
                                    std::to_string(it->second) + ")");
    }
    conf.entries.push_back(ConfEntry{it->first, *pose});
    return {};
}

std::string pose_fields(const Pose& T_world_scan) {
    // The file stores q with R(q) = T.linear()^T (see the header).
    const Eigen::Quaterniond q(Eigen::Matrix3d(T_world_scan.linear().transpose()));
    const Eigen::Vector3d& t = T_world_scan.translation();
    std::string out;
    for (const double value : {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()}) {
        out += ' ';
        out += text::format_exact(value);
    }
    return out;
}

}  // namespace

const ConfEntry* StanfordConf::find(std::string_view file) const {
    const auto it = std::find_if(entries.begin(), entries.end(),
                                 [&](const ConfEntry& entry) { return entry.file == file; });
    return it == entries.end() ? nullptr : &*it;
}

Expected<StanfordConf> parse_conf(std::span<const char> bytes, std::string_view source_name) {
    StanfordConf conf;
    std::unordered_map<std::string, int> first_line_of;
    text::LineReader reader(bytes, true);
    while (reader.next()) {
        const text::LineRef where{source_name, reader.line_number()};
        const text::Fields fields = text::split_fields(reader.line(), text::kBlanks);
        if (auto ok = parse_line(fields, where, conf, first_line_of); !ok) return fail(ok.error());
    }
    if (conf.entries.empty()) {
        return text::line_error(ErrorCode::kEmpty, {source_name, reader.line_number()},
                                "end of file without any " + std::string(kBmeshUsage) + " line");
    }
    return conf;
}

Expected<StanfordConf> read_conf(const std::filesystem::path& path) {
    const Expected<std::vector<char>> bytes = read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    return parse_conf(*bytes, path.filename().string());
}

std::string format_conf(const StanfordConf& conf) {
    std::string out;
    if (conf.camera) out += "camera" + pose_fields(*conf.camera) + "\n";
    for (const ConfEntry& entry : conf.entries) {
        out += "bmesh " + entry.file + pose_fields(entry.T_world_scan) + "\n";
    }
    return out;
}

Expected<void> write_conf(const std::filesystem::path& path, const StanfordConf& conf) {
    for (const ConfEntry& entry : conf.entries) {
        const bool plain = !entry.file.empty() &&
                           entry.file.find_first_of(" \t\r\n\v\f#") == std::string::npos &&
                           entry.file.find("//") == std::string::npos;
        if (!plain) {
            return fail(ErrorCode::kInvalidArgument,
                        path.filename().string() + ": file name '" + entry.file +
                            "' cannot be written to a .conf (empty, blank or comment characters)");
        }
    }
    const std::string text = format_conf(conf);
    return write_file_atomically(path, text);
}

}  // namespace anascan::io
