#include "ply_vertex.hpp"

#include <algorithm>
#include <array>

namespace anascan::io::ply_detail {
namespace {

static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "Vector3f must be 3 packed floats");
static_assert(sizeof(Rgb8) == 3, "Rgb8 must be 3 packed bytes");

constexpr std::size_t kSlotCount = 13;

std::size_t index(Slot slot) { return static_cast<std::size_t>(slot); }

Slot slot_named(std::string_view name) {
    struct Entry {
        std::string_view name;
        Slot slot;
    };
    static constexpr std::array<Entry, 17> kNames{{
        {"x", Slot::kX},
        {"y", Slot::kY},
        {"z", Slot::kZ},
        {"nx", Slot::kNx},
        {"ny", Slot::kNy},
        {"nz", Slot::kNz},
        {"red", Slot::kRed},
        {"green", Slot::kGreen},
        {"blue", Slot::kBlue},
        {"r", Slot::kRed},
        {"g", Slot::kGreen},
        {"b", Slot::kBlue},
        {"diffuse_red", Slot::kRed},
        {"diffuse_green", Slot::kGreen},
        {"diffuse_blue", Slot::kBlue},
        {"intensity", Slot::kIntensity},
        {"confidence", Slot::kConfidence},
    }};
    for (const Entry& entry : kNames) {
        if (entry.name == name) return entry.slot;
    }
    return Slot::kNone;
}

bool slot_used(const VertexPlan& plan, Slot slot) {
    switch (slot) {
        case Slot::kX:
        case Slot::kY:
        case Slot::kZ:
            return plan.positions;
        case Slot::kNx:
        case Slot::kNy:
        case Slot::kNz:
            return plan.normals;
        case Slot::kRed:
        case Slot::kGreen:
        case Slot::kBlue:
            return plan.colors;
        case Slot::kIntensity:
            return plan.intensity;
        case Slot::kConfidence:
            return plan.confidence;
        case Slot::kExtra:
            return true;
        case Slot::kNone:
            return false;
    }
    return false;
}

VertexSink sink_for(PointCloud& cloud, Slot slot, PlyScalar type) {
    const std::size_t s = index(slot);
    VertexSink sink{.type = type};
    if (slot >= Slot::kX && slot <= Slot::kZ) {
        sink.floats = cloud.positions.data()->data() + (s - index(Slot::kX));
        sink.stride = 3;
        sink.offset = cloud.origin_m[static_cast<Eigen::Index>(s - index(Slot::kX))];
    } else if (slot >= Slot::kNx && slot <= Slot::kNz) {
        sink.floats = cloud.normals.data()->data() + (s - index(Slot::kNx));
        sink.stride = 3;
    } else if (slot >= Slot::kRed && slot <= Slot::kBlue) {
        sink.bytes = &cloud.colors.data()->r + (s - index(Slot::kRed));
        sink.stride = 3;
    } else if (slot == Slot::kIntensity) {
        sink.floats = cloud.intensity.data();
        sink.stride = 1;
    } else if (slot == Slot::kConfidence) {
        sink.floats = cloud.confidence.data();
        sink.stride = 1;
    }
    return sink;
}

// Merges the fields of `first` and the next two slots into one 12-byte copy when they are
// float32 at consecutive offsets.
void merge_run(std::vector<FixedField>& fields, std::vector<Slot>& slots, Slot first) {
    std::array<std::size_t, 3> at{};
    std::size_t found = 0;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::size_t component = index(slots[i]) - index(first);
        if (index(slots[i]) >= index(first) && component < 3) {
            at[component] = i;
            ++found;
        }
    }
    if (found != 3) return;
    for (std::size_t c = 0; c < 3; ++c) {
        const FixedField& field = fields[at[c]];
        if (field.sink.type != PlyScalar::kFloat32 || field.sink.offset != 0.0) return;
        if (field.offset != fields[at[0]].offset + 4 * c) return;
    }
    fields[at[0]].run = 3;
    // Erase the two absorbed fields, the later index first.
    for (std::size_t c : {std::max(at[1], at[2]), std::min(at[1], at[2])}) {
        fields.erase(fields.begin() + static_cast<std::ptrdiff_t>(c));
        slots.erase(slots.begin() + static_cast<std::ptrdiff_t>(c));
    }
}

}  // namespace

VertexPlan plan_vertices(const PlyElement& element) {
    VertexPlan plan;
    plan.slots.assign(element.properties.size(), Slot::kNone);
    std::array<bool, kSlotCount> taken{};
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& property = element.properties[k];
        const Slot slot = property.is_list ? Slot::kNone : slot_named(property.name);
        if (slot == Slot::kNone && !property.is_list && plan.extras.size() < kMaxExtraScalars) {
            plan.extras.push_back(k);
            plan.slots[k] = Slot::kExtra;
            continue;
        }
        if (slot == Slot::kNone || taken[index(slot)]) continue;
        taken[index(slot)] = true;
        plan.slots[k] = slot;
    }
    const auto all = [&](Slot a) {
        return taken[index(a)] && taken[index(a) + 1] && taken[index(a) + 2];
    };
    plan.positions = all(Slot::kX);
    plan.normals = all(Slot::kNx);
    plan.colors = all(Slot::kRed);
    plan.intensity = taken[index(Slot::kIntensity)];
    plan.confidence = taken[index(Slot::kConfidence)];
    for (Slot& slot : plan.slots) {
        if (!slot_used(plan, slot)) slot = Slot::kNone;
    }
    return plan;
}

void allocate(PointCloud& cloud, std::vector<PlyScalarProperty>& extras, const PlyElement& element,
              const VertexPlan& plan, std::size_t count) {
    extras.clear();
    for (const std::size_t k : plan.extras)
        extras.push_back({.name = element.properties[k].name, .values = std::vector<float>(count)});
    if (plan.positions) cloud.positions.resize(count);
    if (plan.normals) cloud.normals.resize(count);
    if (plan.colors) cloud.colors.resize(count);
    if (plan.intensity) cloud.intensity.resize(count);
    if (plan.confidence) cloud.confidence.resize(count);
}

std::vector<VertexSink> make_sinks(PointCloud& cloud, std::vector<PlyScalarProperty>& extras,
                                   const PlyElement& element, const VertexPlan& plan) {
    std::vector<VertexSink> sinks(element.properties.size());
    if (cloud.positions.empty()) return sinks;  // nothing to point into
    for (std::size_t j = 0; j < plan.extras.size(); ++j) {
        sinks[plan.extras[j]] = {.floats = extras[j].values.data(),
                                 .stride = 1,
                                 .type = element.properties[plan.extras[j]].type};
    }
    for (std::size_t k = 0; k < sinks.size(); ++k) {
        if (plan.slots[k] != Slot::kNone && plan.slots[k] != Slot::kExtra) {
            sinks[k] = sink_for(cloud, plan.slots[k], element.properties[k].type);
        }
    }
    return sinks;
}

std::uint8_t to_color(double value, PlyScalar type) {
    if (type == PlyScalar::kFloat32 || type == PlyScalar::kFloat64) {
        value *= 255.0;
    } else if (type == PlyScalar::kUint16 || type == PlyScalar::kInt16) {
        value /= 257.0;
    }
    if (!(value > 0.0)) return 0;  // also NaN
    if (value >= 255.0) return 255;
    return static_cast<std::uint8_t>(value + 0.5);
}

std::vector<FixedField> fixed_fields(const PlyElement& element, const VertexPlan& plan,
                                     std::span<const VertexSink> sinks, bool merge_runs) {
    std::vector<FixedField> fields;
    std::vector<Slot> slots;
    std::size_t offset = 0;
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
        if (plan.slots[k] != Slot::kNone) {
            fields.push_back(FixedField{.offset = offset, .sink = sinks[k]});
            slots.push_back(plan.slots[k]);
        }
        offset += scalar_size(element.properties[k].type);
    }
    if (merge_runs) {
        merge_run(fields, slots, Slot::kX);
        merge_run(fields, slots, Slot::kNx);
    }
    return fields;
}

}  // namespace anascan::io::ply_detail
