#include "calibration_message.hpp"

#include <cstdint>

#include "byte_message.hpp"

namespace anascan::drivers::sl {
namespace {

/// A message starts with its kind: an error (code, message) or the values.
enum class Kind : std::uint8_t { kError = 0, kValue = 1 };

template <class T>
bool put_kind(ByteWriter& out, const Expected<T>& result) {
    out.put(result ? Kind::kValue : Kind::kError);
    if (!result) {
        out.put(static_cast<std::int32_t>(result.error().code));
        out.put_string(result.error().message);
    }
    return result.has_value();
}

Error malformed(std::string_view bytes, const std::string& file) {
    return Error{ErrorCode::kFormat, file + ": the calibration parser sent a malformed result (" +
                                         std::to_string(bytes.size()) + " bytes)"};
}

/// The error that follows an error kind; malformed when the code is not one or bytes follow.
Error get_error(ByteReader& in, std::string_view bytes, const std::string& file) {
    const auto code = in.get<std::int32_t>();
    std::string message = in.get_string();
    const bool known = code >= 0 && code <= static_cast<std::int32_t>(ErrorCode::kCancelled);
    if (!known || !in.at_end()) return malformed(bytes, file);
    return Error{static_cast<ErrorCode>(code), std::move(message)};
}

void put_camera(ByteWriter& out, const CameraIntrinsics& camera) {
    for (int i = 0; i < 9; ++i) out.put(camera.K.data()[i]);
    out.put_vector(camera.distortion);
    out.put<std::int32_t>(camera.width_px);
    out.put<std::int32_t>(camera.height_px);
}

CameraIntrinsics get_camera(ByteReader& in) {
    CameraIntrinsics camera;
    for (int i = 0; i < 9; ++i) camera.K.data()[i] = in.get<double>();
    camera.distortion = in.get_vector<double>();
    camera.width_px = in.get<std::int32_t>();
    camera.height_px = in.get<std::int32_t>();
    return camera;
}

}  // namespace

std::string encode_result(const Expected<StereoCalibration>& result) {
    ByteWriter out;
    if (put_kind(out, result)) {
        put_camera(out, result->cam1);
        put_camera(out, result->cam2);
        for (int i = 0; i < 16; ++i) out.put(result->T_cam1_cam2.matrix().data()[i]);
    }
    return std::move(out).take();
}

std::string encode_result(const Expected<std::optional<RecordedPatternLayout>>& result) {
    ByteWriter out;
    if (put_kind(out, result)) {
        out.put<std::uint8_t>(result->has_value() ? 1 : 0);
        if (*result) out.put(**result);
    }
    return std::move(out).take();
}

Expected<StereoCalibration> decode_stereo_calibration(std::string_view bytes,
                                                      const std::string& file) {
    ByteReader in(bytes);
    const auto kind = in.get<Kind>();
    if (kind == Kind::kError) return fail(get_error(in, bytes, file));
    StereoCalibration calibration;
    calibration.cam1 = get_camera(in);
    calibration.cam2 = get_camera(in);
    for (int i = 0; i < 16; ++i) calibration.T_cam1_cam2.matrix().data()[i] = in.get<double>();
    if (kind != Kind::kValue || !in.at_end()) return fail(malformed(bytes, file));
    return calibration;
}

Expected<std::optional<RecordedPatternLayout>> decode_pattern_layout(std::string_view bytes,
                                                                     const std::string& file) {
    ByteReader in(bytes);
    const auto kind = in.get<Kind>();
    if (kind == Kind::kError) return fail(get_error(in, bytes, file));
    std::optional<RecordedPatternLayout> layout;
    const auto present = in.get<std::uint8_t>();
    if (present == 1) layout = in.get<RecordedPatternLayout>();
    if (kind != Kind::kValue || present > 1 || !in.at_end()) return fail(malformed(bytes, file));
    return layout;
}

}  // namespace anascan::drivers::sl
