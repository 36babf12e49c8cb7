#include "anascan/drivers/usb_bulk_camera.hpp"

#include <cmath>
#include <cstring>

namespace anascan::drivers {
namespace {

constexpr std::uint8_t kVendorOut = 0x40;  // LIBUSB_REQUEST_TYPE_VENDOR | ENDPOINT_OUT

/// Not thread-safe (see Camera).
class UsbBulkCamera final : public Camera {
public:
    UsbBulkCamera(std::unique_ptr<UsbTransport> transport, const SupportedUsbDevice& model)
        : transport_(std::move(transport)) {
        info_ = DeviceInfo{
            .uri = transport_->name(), .model = model.model, .kind = model.kind, .is_camera = true};
        caps_.can_stream = true;
        caps_.profiles = {model.profile};
        caps_.exposure_us = NumericRange{100.0, 100000.0};
        settings_.profile = model.profile;
        settings_.exposure_us = 10000.0;
    }
    ~UsbBulkCamera() override { close(); }

    const DeviceInfo& info() const override { return info_; }
    const Capabilities& capabilities() const override { return caps_; }
    DeviceSettings settings() const override { return settings_; }
    Expected<void> configure(const DeviceSettings& requested) override {
        if (!transport_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
        if (auto ok = validate_settings(requested, caps_, info_.uri); !ok) return ok;
        if (requested.exposure_us) {
            const auto units =
                static_cast<std::uint16_t>(std::lround(*requested.exposure_us / 100.0));
            if (auto ok = control(usb_bulk::kRequestExposure, units); !ok) return ok;
        }
        settings_ = merge_settings(settings_, requested);
        return {};
    }
    void close() override {
        stop_stream();
        transport_.reset();
    }
    Expected<void> start_stream() override {
        if (!transport_) return fail(ErrorCode::kDisconnected, info_.uri + ": closed");
        if (auto ok = control(usb_bulk::kRequestStreaming, 1); !ok) return ok;
        streaming_ = true;
        return {};
    }
    Expected<Frame> next_frame(std::chrono::milliseconds timeout) override;
    void stop_stream() override {
        if (streaming_ && transport_) (void)control(usb_bulk::kRequestStreaming, 0);
        streaming_ = false;
    }

private:
    Expected<void> control(std::uint8_t request, std::uint16_t value) {
        auto r = transport_->control_transfer(kVendorOut, request, value, 0, {},
                                              std::chrono::milliseconds(1000));
        if (!r) return fail(r.error());
        return {};
    }

    std::unique_ptr<UsbTransport> transport_;
    DeviceInfo info_;
    Capabilities caps_;
    DeviceSettings settings_;
    bool streaming_ = false;
};

Expected<Frame> UsbBulkCamera::next_frame(std::chrono::milliseconds timeout) {
    if (!transport_ || !streaming_)
        return fail(ErrorCode::kInvalidArgument, info_.uri + ": not streaming");
    const StreamProfile& p = *settings_.profile;
    const std::size_t row = bytes_per_pixel(p.format) * static_cast<std::size_t>(p.width);
    std::vector<std::uint8_t> buffer(usb_bulk::kHeaderBytes + row * p.height);
    auto got = transport_->bulk_transfer(usb_bulk::kFrameEndpoint, buffer, timeout);
    if (!got) return fail(got.error());
    if (*got < usb_bulk::kHeaderBytes || std::memcmp(buffer.data(), "AFRM", 4) != 0) {
        return fail(ErrorCode::kFormat, info_.uri + ": a bulk transfer of " + std::to_string(*got) +
                                            " bytes is not a frame (no AFRM header)");
    }
    Frame f;
    std::uint16_t w = 0, h = 0;
    std::uint32_t seq = 0;
    std::memcpy(&w, buffer.data() + 4, 2);
    std::memcpy(&h, buffer.data() + 6, 2);
    std::memcpy(&seq, buffer.data() + 12, 4);
    f.width = w;
    f.height = h;
    f.format = static_cast<PixelFormat>(buffer[8]);
    f.stride_bytes = row;
    f.sequence = seq;
    f.timestamp_ns = std::chrono::steady_clock::now().time_since_epoch();
    f.data.assign(buffer.begin() + usb_bulk::kHeaderBytes,
                  buffer.begin() + static_cast<std::ptrdiff_t>(*got));
    if (w != p.width || h != p.height || f.format != p.format)
        return fail(ErrorCode::kFormat,
                    info_.uri + ": frame " + std::to_string(seq) + " has the wrong geometry");
    if (auto ok = check_frame(f, info_.uri); !ok) return fail(ok.error());
    return f;
}

}  // namespace

std::unique_ptr<Camera> open_usb_bulk_camera(std::unique_ptr<UsbTransport> transport,
                                             const SupportedUsbDevice& model) {
    return std::make_unique<UsbBulkCamera>(std::move(transport), model);
}

}  // namespace anascan::drivers
