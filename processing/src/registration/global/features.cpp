// The features global registration matches (paper §4.2.1): descriptor radii from the
// object's size, integral invariants per scan, feature patches at saliency levels shared by
// all scans of a registration.
#include <algorithm>

#include "anascan/processing/registration/global/global_registration.hpp"

namespace anascan {

InvariantRadii registration_radii_m(double largest_diagonal_m,
                                    const GlobalRegistrationConfig& config) {
    const bool automatic = std::all_of(config.radii_m.begin(), config.radii_m.end(),
                                       [](double r) { return r == 0.0; });
    return automatic ? radii_for_object_size_m(largest_diagonal_m) : config.radii_m;
}

InvariantRadii registration_radii_m(std::span<const PointCloud* const> clouds,
                                    const GlobalRegistrationConfig& config) {
    double size_m = 0.0;
    for (const PointCloud* cloud : clouds) {
        size_m = std::max(size_m, static_cast<double>(local_bounds(*cloud).extent().norm()));
    }
    return registration_radii_m(size_m, config);
}

IntegralInvariantResult describe_scan(const PointCloud& cloud, const InvariantRadii& radii_m,
                                      const GlobalRegistrationConfig& config) {
    IntegralInvariantConfig invariant_config = config.invariants;
    invariant_config.radii_m = radii_m;
    return compute_integral_invariants(cloud, invariant_config);
}

std::vector<ScanFeatures> scan_features(std::vector<IntegralInvariantResult> invariants,
                                        std::span<const double> spacings_m,
                                        const GlobalRegistrationConfig& config) {
    std::vector<const IntegralInvariantResult*> valid;
    for (const IntegralInvariantResult& scan : invariants) {
        if (scan.status == IntegralInvariantStatus::kOk) valid.push_back(&scan);
    }
    const SaliencyLevels levels = saliency_levels(valid, config.patches);
    std::vector<ScanFeatures> features(invariants.size());
    for (std::size_t i = 0; i < invariants.size(); ++i) {
        if (invariants[i].status == IntegralInvariantStatus::kOk) {
            features[i].patches = extract_feature_patches(invariants[i], levels, config.patches);
        }
        features[i].invariants = std::move(invariants[i]);
        features[i].spacing_m = i < spacings_m.size() ? spacings_m[i] : 0.0;
    }
    return features;
}

}  // namespace anascan
