#include <fcntl.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <fstream>

#include "os_error.hpp"
#include "v4l2_camera_impl.hpp"
#include "v4l2_query.hpp"

namespace anascan::drivers {

V4l2Camera::V4l2Camera(V4l2CameraConfig config, UniqueFd fd, DeviceInfo info, bool can_read,
                       bool can_stream_io)
    : config_(std::move(config)),
      fd_(std::move(fd)),
      info_(std::move(info)),
      can_read_(can_read),
      can_stream_io_(can_stream_io) {
    caps_.can_stream = true;
    caps_.profiles = v4l2::query_profiles(fd_.get());
    if (auto r = v4l2::query_control(fd_.get(), V4L2_CID_EXPOSURE_ABSOLUTE)) {
        caps_.exposure_us = NumericRange{r->min * 100.0, r->max * 100.0};  // 100 µs units
    }
    caps_.gain = v4l2::query_control(fd_.get(), V4L2_CID_GAIN);
}

Error V4l2Camera::fail_os(const std::string& what, int error_number) {
    Error e = errno_error(config_.device_path, what, error_number);
    if (e.code == ErrorCode::kDisconnected) disconnected_ = true;
    return e;
}

Expected<void> V4l2Camera::check_open() const {
    if (!fd_ || disconnected_) {
        return fail(ErrorCode::kDisconnected,
                    config_.device_path + ": the camera is closed or was unplugged");
    }
    return {};
}

Expected<void> V4l2Camera::refresh_settings() {
    v4l2_format f{};
    f.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (int e = v4l2::xioctl(fd_.get(), VIDIOC_G_FMT, &f)) return fail(fail_os("VIDIOC_G_FMT", e));
    if (auto format = v4l2::from_fourcc(f.fmt.pix.pixelformat)) {
        settings_.profile =
            StreamProfile{static_cast<int>(f.fmt.pix.width), static_cast<int>(f.fmt.pix.height),
                          *format, v4l2::query_frame_rate(fd_.get())};
    }
    stride_bytes_ = f.fmt.pix.bytesperline;
    image_bytes_ = f.fmt.pix.sizeimage;
    v4l2_control c{V4L2_CID_EXPOSURE_ABSOLUTE, 0};
    if (caps_.exposure_us && v4l2::xioctl(fd_.get(), VIDIOC_G_CTRL, &c) == 0)
        settings_.exposure_us = c.value * 100.0;
    c = {V4L2_CID_GAIN, 0};
    if (caps_.gain && v4l2::xioctl(fd_.get(), VIDIOC_G_CTRL, &c) == 0) settings_.gain = c.value;
    return {};
}

Expected<void> V4l2Camera::apply_profile(const StreamProfile& p) {
    v4l2_format f{};
    f.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    f.fmt.pix.width = static_cast<std::uint32_t>(p.width);
    f.fmt.pix.height = static_cast<std::uint32_t>(p.height);
    f.fmt.pix.pixelformat = v4l2::to_fourcc(p.format);
    f.fmt.pix.field = V4L2_FIELD_NONE;
    if (int e = v4l2::xioctl(fd_.get(), VIDIOC_S_FMT, &f)) return fail(fail_os("VIDIOC_S_FMT", e));
    if (p.frame_rate_hz > 0.0) {
        if (int e = v4l2::set_frame_rate(fd_.get(), p.frame_rate_hz))
            return fail(fail_os("VIDIOC_S_PARM", e));
    }
    if (v4l2::from_fourcc(f.fmt.pix.pixelformat) != p.format ||
        static_cast<int>(f.fmt.pix.width) != p.width ||
        static_cast<int>(f.fmt.pix.height) != p.height) {
        return fail(ErrorCode::kInvalidArgument,
                    config_.device_path + ": the driver changed the requested stream to " +
                        std::to_string(f.fmt.pix.width) + " x " + std::to_string(f.fmt.pix.height));
    }
    return {};
}

Expected<void> V4l2Camera::apply_control(std::uint32_t id, std::int32_t value, const char* name) {
    v4l2_control c{id, value};
    if (int e = v4l2::xioctl(fd_.get(), VIDIOC_S_CTRL, &c)) return fail(fail_os(name, e));
    return {};
}

Expected<void> V4l2Camera::configure(const DeviceSettings& requested) {
    if (auto ok = check_open(); !ok) return ok;
    if (streaming_) {
        return fail(ErrorCode::kBusy, config_.device_path + ": stop the stream before configuring");
    }
    if (auto ok = validate_settings(requested, caps_, info_.uri); !ok) return ok;
    if (requested.profile) {
        if (auto ok = apply_profile(*requested.profile); !ok) return ok;
    }
    if (requested.exposure_us) {
        v4l2_control manual{V4L2_CID_EXPOSURE_AUTO, V4L2_EXPOSURE_MANUAL};
        (void)v4l2::xioctl(fd_.get(), VIDIOC_S_CTRL, &manual);  // absent on fixed-exposure cameras
        const auto units = static_cast<std::int32_t>(std::lround(*requested.exposure_us / 100.0));
        if (auto ok = apply_control(V4L2_CID_EXPOSURE_ABSOLUTE, units, "set exposure"); !ok)
            return ok;
    }
    if (requested.gain) {
        const auto gain = static_cast<std::int32_t>(std::lround(*requested.gain));
        if (auto ok = apply_control(V4L2_CID_GAIN, gain, "set gain"); !ok) return ok;
    }
    return refresh_settings();
}

void V4l2Camera::close() {
    stop_stream();
    fd_.reset();
}

namespace {

std::string read_first_line(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    return line;
}

}  // namespace

Expected<std::unique_ptr<Camera>> open_v4l2_camera(const V4l2CameraConfig& config) {
    UniqueFd fd(::open(config.device_path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC));
    if (!fd) return fail(errno_error(config.device_path, "open", errno));
    v4l2_capability cap{};
    if (int e = v4l2::xioctl(fd.get(), VIDIOC_QUERYCAP, &cap)) {
        Error err = errno_error(config.device_path, "VIDIOC_QUERYCAP", e);
        if (e == ENOTTY || e == EINVAL) err.code = ErrorCode::kUnsupported;
        return fail(std::move(err));
    }
    const std::uint32_t caps =
        (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    if (!(caps & V4L2_CAP_VIDEO_CAPTURE)) {
        return fail(ErrorCode::kUnsupported, config.device_path + ": not a video capture device");
    }
    DeviceInfo info{.uri = "v4l2:" + config.device_path,
                    .model = reinterpret_cast<const char*>(cap.card),
                    .serial = reinterpret_cast<const char*>(cap.bus_info),
                    .is_camera = true};
    auto camera = std::make_unique<V4l2Camera>(config, std::move(fd), std::move(info),
                                               (caps & V4L2_CAP_READWRITE) != 0,
                                               (caps & V4L2_CAP_STREAMING) != 0);
    if (auto ok = camera->refresh_settings(); !ok) return fail(ok.error());
    camera->mark_depth_camera();
    return std::unique_ptr<Camera>(std::move(camera));
}

std::vector<DeviceInfo> enumerate_v4l2_cameras(const std::filesystem::path& sysfs_dir) {
    std::vector<DeviceInfo> found;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(sysfs_dir, ec)) {
        const std::string node = entry.path().filename().string();
        if (node.rfind("video", 0) != 0) continue;
        found.push_back(DeviceInfo{.uri = "v4l2:/dev/" + node,
                                   .model = read_first_line(entry.path() / "name"),
                                   .serial = node,
                                   .is_camera = true});
    }
    std::sort(found.begin(), found.end(),
              [](const DeviceInfo& a, const DeviceInfo& b) { return a.uri < b.uri; });
    return found;
}

Backend make_v4l2_backend() {
    return Backend{.scheme = "v4l2",
                   .description = "Video4Linux2 cameras, e.g. v4l2:/dev/video0",
                   .enumerate = [] { return enumerate_v4l2_cameras(); },
                   .open = [](const DeviceUri& uri) -> Expected<std::unique_ptr<Device>> {
                       auto camera = open_v4l2_camera({.device_path = uri.target});
                       if (!camera) return fail(camera.error());
                       return std::unique_ptr<Device>(std::move(*camera));
                   }};
}

}  // namespace anascan::drivers
