#include "anascan/scanner_sources/scanner_source.hpp"

#include "anascan/drivers/device_registry.hpp"
#include "anascan/sim/scanning_tour.hpp"
#include "anascan/sim/sim_backend.hpp"
#include "anascan/sim/sim_scanner.hpp"

namespace anascan::scanner_sources {
namespace {

drivers::DeviceRegistry make_registry() {
    drivers::DeviceRegistry registry = drivers::make_hardware_registry();
    (void)registry.add(sim::make_sim_backend());
    return registry;
}

drivers::DeviceSettings device_settings(const ScannerSettings& s) {
    return {.exposure_us = s.exposure_us,
            .angular_step_deg = s.angular_step_deg,
            .max_range_m = s.max_range_m};
}

sim::ScanningTourConfig tour_config(const SimulatedTour& tour) {
    return {.views = tour.views,
            .flip_after = tour.flip_after,
            .distance_m = tour.distance_m,
            .follow_footprint = tour.follow_footprint,
            .seed = tour.seed};
}

}  // namespace

ScannerOpener make_scanner_opener(ScannerSource source) {
    auto registry = std::make_shared<drivers::DeviceRegistry>(make_registry());
    auto first = std::make_shared<bool>(true);
    return [registry, source, first]() -> Expected<std::unique_ptr<drivers::Scanner>> {
        auto device = registry->open(source.uri);
        if (!device) return fail(device.error());
        drivers::Scanner* scanner = (*device)->as_scanner();
        if (scanner == nullptr)
            return fail(ErrorCode::kUnsupported,
                        source.uri + ": not a scanner (a camera?); capture needs a scanner");
        (void)device->release();
        std::unique_ptr<drivers::Scanner> owned(scanner);
        const drivers::DeviceSettings settings = device_settings(source.settings);
        if (settings != drivers::DeviceSettings{})
            if (auto ok = owned->configure(settings); !ok) return fail(ok.error());
        auto* simulated = dynamic_cast<sim::SimScanner*>(owned.get());
        if (simulated != nullptr && source.sim_unplug_after >= 0 && *first) {
            auto faults = std::make_shared<sim::SimDeviceFaults>();
            faults->unplug_after_captures = source.sim_unplug_after;
            simulated->set_faults(faults);
        }
        *first = false;
        return owned;
    };
}

std::vector<ScannerListing> list_scanners() {
    std::vector<ScannerListing> out;
    for (const drivers::DeviceInfo& info : make_registry().enumerate())
        if (info.is_scanner)
            out.push_back(
                {.uri = info.uri, .model = info.model, .simulated = is_simulated(info.uri)});
    return out;
}

bool is_simulated(const std::string& uri) { return uri.rfind("sim:", 0) == 0; }

Expected<int> footprint_views_per_side(const std::string& uri, const SimulatedTour& tour) {
    auto target = sim::sim_device_target(uri);
    if (!target) return fail(target.error());
    return sim::footprint_views_per_side(tour_config(tour), target->scene.placement,
                                         target->scene.block.size_m, target->terrestrial);
}

CaptureRequest tour_request(const SimulatedTour& tour, int index) {
    const sim::ScanningTourConfig config = tour_config(tour);
    const std::vector<sim::TourStep> steps = sim::plan_scanning_tour(config);
    if (index < 0 || index >= static_cast<int>(steps.size())) return {};
    const sim::TourStep step = steps[static_cast<std::size_t>(index)];
    return {.before =
                [config, step](drivers::Scanner& scanner) {
                    return sim::apply_tour_step(scanner, config, step);
                },
            .turned_over = step.turn_now};
}

bool tour_turns_over_before(const SimulatedTour& tour, int index) {
    const std::vector<sim::TourStep> steps = sim::plan_scanning_tour(tour_config(tour));
    return index >= 0 && index < static_cast<int>(steps.size()) &&
           steps[static_cast<std::size_t>(index)].turn_now;
}

CaptureRequest guided_request(const SimulatedTour& tour, const GuidedView& view) {
    const sim::ScanningTourConfig config = tour_config(tour);
    const sim::GuidedView guided{
        .sensor_m = view.sensor_m, .aim_m = view.aim_m, .turned = view.turned};
    return {.before = [config, guided](drivers::Scanner& scanner) {
        return sim::apply_guided_view(scanner, config, guided);
    }};
}

CaptureRequest turned_side_request(const SimulatedTour& tour, int index, int views) {
    SimulatedTour turned = tour;
    turned.views = 1 + views;
    turned.flip_after = 1;
    return tour_request(turned, 1 + index % views);
}

}  // namespace anascan::scanner_sources
