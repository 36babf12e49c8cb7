#include "anascan/drivers/structured_light/stereo_calibration.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>

#include "anascan/processing/io/file_bytes.hpp"
#include "calibration_message.hpp"
#include "calibration_parse.hpp"
#include "isolated_call.hpp"

namespace anascan::drivers::sl {
namespace {

/// Inputs on which OpenCV 4.6's FileStorage parsers fail badly, found by fuzz_calibration, are
/// refused before OpenCV sees them: a NUL byte (the XML parser reads a null pointer), and
/// text after a document start "---" (the YAML parser never returns when a marker-like line
/// such as "--%-" follows). OpenCV writes neither: its files are text, "---" alone on its line.
/// The child process bounds these faults too; the check stays because it names the line or
/// byte at once, where the child would end in a time-limit error after seconds or a crash.
Expected<void> refuse_parser_traps(const std::filesystem::path& path) {
    auto bytes = io::read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    const std::string_view text(bytes->data(), bytes->size());
    if (const std::size_t nul = text.find('\0'); nul != std::string_view::npos) {
        return fail(ErrorCode::kFormat, path.string() + ": byte " + std::to_string(nul) +
                                            ": a NUL byte; a calibration file is OpenCV YAML "
                                            "or XML text");
    }
    std::size_t line_number = 1;
    for (std::size_t start = 0; start < text.size(); ++line_number) {
        const std::size_t end = std::min(text.find('\n', start), text.size());
        const std::string_view line = text.substr(start, end - start);
        if (line.starts_with("---") &&
            line.find_first_not_of(" \t\r", 3) != std::string_view::npos) {
            return fail(ErrorCode::kFormat,
                        path.string() + ": line " + std::to_string(line_number) +
                            ": text after the document start '---'; a calibration file is an "
                            "OpenCV YAML document with '---' alone on its line");
        }
        start = end + 1;
    }
    return {};
}

/// Whether a node may be read as a matrix: a sequence holds its own elements; an
/// `!!opencv-matrix` map must declare at most `max_elements` and hold as many as it
/// declares. OpenCV allocates rows x cols before it reads the data, so a hostile `rows`
/// would allocate gigabytes: this is checked first.
bool plausible_matrix(const cv::FileNode& node, long long max_elements) {
    if (!node.isMap()) return true;
    const cv::FileNode rows = node["rows"], cols = node["cols"], data = node["data"];
    if (!rows.isInt() || !cols.isInt() || !data.isSeq()) return false;
    const long long r = int(rows), c = int(cols);
    return r > 0 && c > 0 && r * c <= max_elements &&
           data.size() == static_cast<std::size_t>(r * c);
}

/// A matrix of doubles stored under `key` with the given shape (cols 0: any).
Expected<cv::Mat> read_matrix(const cv::FileStorage& fs, const std::string& file,
                              const std::string& key, int rows, int cols) {
    const cv::FileNode node = fs[key];
    if (node.empty()) return fail(ErrorCode::kFormat, file + ": missing key '" + key + "'");
    cv::Mat m;
    if (plausible_matrix(node, static_cast<long long>(rows) * (cols > 0 ? cols : 16))) node >> m;
    if (m.empty() || m.channels() != 1 || m.rows != rows || (cols > 0 && m.cols != cols)) {
        return fail(ErrorCode::kFormat, file + ": '" + key + "' is not a " + std::to_string(rows) +
                                            "x" + (cols > 0 ? std::to_string(cols) : "N") +
                                            " matrix");
    }
    cv::Mat d;
    m.convertTo(d, CV_64F);
    return d;
}

Expected<CameraIntrinsics> read_camera(const cv::FileStorage& fs, const std::string& file,
                                       const std::string& name) {
    auto K = read_matrix(fs, file, name + "_intrinsics", 3, 3);
    if (!K) return fail(K.error());
    CameraIntrinsics cam;
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) cam.K(r, c) = K->at<double>(r, c);
    if (!(cam.K(0, 0) > 0.0) || !(cam.K(1, 1) > 0.0) || cam.K(2, 2) != 1.0)
        return fail(ErrorCode::kFormat,
                    file + ": '" + name + "_intrinsics' is not a camera matrix");
    // OpenCV's samples spell it "distorsion"; accept the English spelling too.
    cv::FileNode dist = fs[name + "_distorsion"];
    if (dist.empty()) dist = fs[name + "_distortion"];
    if (!dist.empty()) {
        cv::Mat d;
        if (plausible_matrix(dist, 8)) dist >> d;
        if (d.total() > 8 || (d.rows != 1 && d.cols != 1))
            return fail(ErrorCode::kFormat, file + ": '" + name + "' distortion is not a vector");
        d.convertTo(d, CV_64F);
        cam.distortion.assign(d.begin<double>(), d.end<double>());
    }
    const cv::FileNode size = fs[name + "_size"];
    if (size.isSeq() && size.size() == 2 && size[0].isInt() && size[1].isInt()) {
        cam.width_px = int(size[0]);
        cam.height_px = int(size[1]);
    }
    if (cam.width_px <= 0 || cam.height_px <= 0)
        return fail(ErrorCode::kFormat, file + ": missing or bad '" + name + "_size' [w, h]");
    return cam;
}

Expected<Pose> read_extrinsics(const cv::FileStorage& fs, const std::string& file, double unit_m) {
    auto R = read_matrix(fs, file, "R", 3, 3);
    if (!R) return fail(R.error());
    auto T = read_matrix(fs, file, "T", 3, 1);
    if (!T) return fail(T.error());
    Pose pose = Pose::Identity();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) pose.linear()(r, c) = R->at<double>(r, c);
        pose.translation()(r) = T->at<double>(r) * unit_m;
    }
    const Eigen::Matrix3d RtR = pose.linear().transpose() * pose.linear();
    if (!RtR.isIdentity(1e-6) || pose.linear().determinant() < 0.0)
        return fail(ErrorCode::kFormat, file + ": 'R' is not a rotation matrix");
    return pose;
}

/// The checks before any parser runs: the file exists, and it has none of the known traps.
Expected<void> check_before_parsing(const std::filesystem::path& path) {
    if (!std::filesystem::is_regular_file(path))
        return fail(ErrorCode::kIo, path.string() + ": no such calibration file");
    return refuse_parser_traps(path);
}

Expected<void> check_unit(const StereoCalibrationLoadConfig& config) {
    if (!(config.file_unit_m > 0.0))
        return fail(ErrorCode::kInvalidArgument, "calibration unit must be positive");
    return {};
}

/// An exception out of OpenCV as an error naming the file.
Error exception_error(const std::string& file, const std::exception& e) {
    if (const auto* cv_error = dynamic_cast<const cv::Exception*>(&e))
        return Error{ErrorCode::kFormat, file + ": " + cv_error->msg};
    // OpenCV's parser lets std::length_error and others out.
    return Error{ErrorCode::kFormat, file + ": not a readable calibration file (" + e.what() + ")"};
}

/// Opens the file with OpenCV and reads it: the part that runs in the child process.
Expected<StereoCalibration> read_stereo_calibration(const std::filesystem::path& path,
                                                    const StereoCalibrationLoadConfig& config) {
    const std::string file = path.string();
    try {
        cv::FileStorage fs;
        if (!fs.open(file, cv::FileStorage::READ | cv::FileStorage::FORMAT_AUTO))
            return fail(ErrorCode::kFormat, file + ": not an OpenCV FileStorage file");
        auto first = read_camera(fs, file, "cam1");
        if (!first) return fail(first.error());
        auto second = read_camera(fs, file, "cam2");
        if (!second) return fail(second.error());
        auto T_second_first = read_extrinsics(fs, file, config.file_unit_m);
        if (!T_second_first) return fail(T_second_first.error());
        // The file's R, T map its first camera into its second: X_2 = R X_1 + T.
        if (config.swap_cameras) {
            return StereoCalibration{
                .cam1 = *second, .cam2 = *first, .T_cam1_cam2 = *T_second_first};
        }
        return StereoCalibration{
            .cam1 = *first, .cam2 = *second, .T_cam1_cam2 = T_second_first->inverse()};
    } catch (const std::exception& e) {
        return fail(exception_error(file, e));
    }
}

Expected<std::optional<RecordedPatternLayout>> read_layout(const cv::FileStorage& fs,
                                                           const std::string& file) {
    const cv::FileNode size = fs["proj_size"];
    if (size.empty()) return std::optional<RecordedPatternLayout>{};
    RecordedPatternLayout layout;
    if (size.isSeq() && size.size() == 2 && size[0].isInt() && size[1].isInt()) {
        layout.projector_width_px = int(size[0]);
        layout.projector_height_px = int(size[1]);
    }
    if (layout.projector_width_px <= 0 || layout.projector_height_px <= 0)
        return fail(ErrorCode::kFormat, file + ": bad 'proj_size' (expected [w, h])");
    const cv::FileNode steps = fs["pattern_phase_steps"];
    const cv::FileNode period = fs["pattern_phase_period_px"];
    if (!steps.empty()) layout.phase_steps = steps.isInt() ? int(steps) : -1;
    if (!period.empty()) layout.phase_period_px = period.isInt() ? int(period) : -1;
    if (layout.phase_steps < 0 || (layout.phase_steps > 0 && layout.phase_period_px < 2))
        return fail(ErrorCode::kFormat,
                    file + ": bad 'pattern_phase_steps' / 'pattern_phase_period_px'");
    return std::optional<RecordedPatternLayout>{layout};
}

/// Opens the file with OpenCV and reads the layout: the part that runs in the child process.
Expected<std::optional<RecordedPatternLayout>> read_pattern_layout(
    const std::filesystem::path& path) {
    const std::string file = path.string();
    try {
        cv::FileStorage fs(file, cv::FileStorage::READ | cv::FileStorage::FORMAT_AUTO);
        if (!fs.isOpened())
            return fail(ErrorCode::kFormat, file + ": not an OpenCV FileStorage file");
        return read_layout(fs, file);
    } catch (const std::exception& e) {
        return fail(exception_error(file, e));
    }
}

IsolatedCallConfig parser_call(const std::filesystem::path& path,
                               std::chrono::milliseconds time_limit) {
    return {.subject = path.string(), .worker = "the calibration parser", .time_limit = time_limit};
}

}  // namespace

Expected<StereoCalibration> parse_stereo_calibration(const std::filesystem::path& path,
                                                     const StereoCalibrationLoadConfig& config) {
    if (auto unit = check_unit(config); !unit) return fail(unit.error());
    if (auto checked = check_before_parsing(path); !checked) return fail(checked.error());
    return read_stereo_calibration(path, config);
}

Expected<std::optional<RecordedPatternLayout>> parse_pattern_layout(
    const std::filesystem::path& path) {
    if (auto checked = check_before_parsing(path); !checked) return fail(checked.error());
    return read_pattern_layout(path);
}

Expected<StereoCalibration> load_stereo_calibration(const std::filesystem::path& path,
                                                    const StereoCalibrationLoadConfig& config) {
    if (auto unit = check_unit(config); !unit) return fail(unit.error());
    if (auto checked = check_before_parsing(path); !checked) return fail(checked.error());
    const auto message = call_isolated(parser_call(path, config.parse_time_limit), [&] {
        return encode_result(read_stereo_calibration(path, config));
    });
    if (!message) return fail(message.error());
    return decode_stereo_calibration(*message, path.string());
}

Expected<std::optional<RecordedPatternLayout>> load_pattern_layout(
    const std::filesystem::path& path, const PatternLayoutLoadConfig& config) {
    if (auto checked = check_before_parsing(path); !checked) return fail(checked.error());
    const auto message = call_isolated(parser_call(path, config.parse_time_limit),
                                       [&] { return encode_result(read_pattern_layout(path)); });
    if (!message) return fail(message.error());
    return decode_pattern_layout(*message, path.string());
}

}  // namespace anascan::drivers::sl
