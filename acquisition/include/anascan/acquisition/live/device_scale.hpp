#pragma once
/// \file
/// The lengths of a live session from the device's own scans: the registrar's constants are
/// those of a structured-light head (about 0.1 mm noise under a 2 mm voxel); a terrestrial
/// scanner's 7 mm range noise needs gates, bands and voxels several times its noise.

#include "anascan/acquisition/live/live_registration.hpp"
#include "anascan/processing/core/point_cloud.hpp"

namespace anascan::acquisition {

/// Sample spacing and noise of one scan, measured on its own points.
struct DeviceScale {
    double spacing_m = 0.0;  ///< Median distance to the nearest other point.
    /// Noise across the surface (a standard deviation): from the median distance of a point
    /// to the least-squares plane of its 63 nearest neighbours (a
    /// little low where the noise is as large as the spacing: 84 % of it at 7 mm and 6 mm).
    double noise_m = 0.0;
    std::size_t samples = 0;  ///< Neighbourhoods measured.
};

/// Measures at most `max_samples` points spread evenly through the cloud (deterministic).
/// A cloud of fewer than 16 finite points gives samples == 0.
DeviceScale measure_device_scale(const PointCloud& cloud, std::size_t max_samples = 2000);

/// `config` with every length that the device's noise bounds from below raised to that bound
/// (voxel and ground band, the fine registrations' gates and overlap distances, the vote and
/// feature tolerances); a length already above it is kept, so a structured-light head's
/// session is what the constants say.
LiveRegistrationConfig lengths_for_device(LiveRegistrationConfig config, const DeviceScale& scale);

}  // namespace anascan::acquisition
