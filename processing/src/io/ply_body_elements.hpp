#pragma once
// Private to processing/src/io: BodyReader's readers of the vertex, face and range_grid
// elements (included at the end of ply_body_reader.hpp).

#include "ply_body_reader.hpp"

namespace anascan::io::ply_detail {

template <class Source>
Expected<void> BodyReader<Source>::read_vertices(const PlyElement& element) {
    const VertexPlan plan = plan_vertices(element);
    if (!plan.positions) {
        return element_error(ErrorCode::kUnsupported, "no x, y and z properties");
    }
    if (!fits(element)) return doomed(element);
    PointCloud& cloud = data_.cloud;
    allocate(cloud, data_.vertex_scalars, element, plan, element.count);
    const std::vector<VertexSink> sinks = make_sinks(cloud, data_.vertex_scalars, element, plan);
    if constexpr (Source::kBinary) {
        if (!element.has_lists()) {  // fast path: offset table, no per-value checks
            const std::size_t record = element.fixed_record_bytes();
            const std::vector<FixedField> fields =
                fixed_fields(element, plan, sinks, !Source::kSwapped);
            decode_fixed_records<Source::kSwapped>(src_.data() + src_.position(), element.count,
                                                   record, fields);
            src_.skip(element.count * record);
            return {};
        }
    }
    return walk(
        element, [&](std::size_t k, double number) { store(sinks[k], index_, number); },
        [&](std::size_t k, std::size_t count) { return skip_items(element.properties[k], count); });
}

// Index of the list property holding vertex indices, or the property count when none.
inline std::size_t index_list_of(const PlyElement& element) {
    for (std::size_t k = 0; k < element.properties.size(); ++k) {
        const PlyProperty& property = element.properties[k];
        if (property.is_list &&
            (property.name == "vertex_indices" || property.name == "vertex_index")) {
            return k;
        }
    }
    return element.properties.size();
}

template <class Source>
Expected<void> BodyReader<Source>::read_faces(const PlyElement& element) {
    const std::size_t list = index_list_of(element);
    if (list == element.properties.size()) {
        data_.skipped_elements.push_back(element.name);
        return skip_element(element);
    }
    const PlyProperty& indices = element.properties[list];
    if (!is_integer(indices.type)) {
        return element_error(ErrorCode::kUnsupported, "list '" + indices.name +
                                                          "' has non-integer type " +
                                                          std::string(scalar_name(indices.type)));
    }
    if (fits(element)) data_.triangles.reserve(element.count);
    return walk(
        element, [](std::size_t, double) {},
        [&](std::size_t k, std::size_t count) {
            return k == list ? read_polygon(indices, count)
                             : skip_items(element.properties[k], count);
        });
}

// One face: checks every index, then fan-triangulates (v0, vi, vi+1).
template <class Source>
Expected<void> BodyReader<Source>::read_polygon(const PlyProperty& property, std::size_t count) {
    polygon_.clear();
    for (std::size_t i = 0; i < count; ++i) {
        const Expected<double> vertex = value(property, property.type);
        if (!vertex) return fail(vertex.error());
        if (*vertex < 0 || *vertex >= static_cast<double>(vertex_count_)) {
            return error(ErrorCode::kFormat,
                         "vertex index " + std::to_string(static_cast<std::int64_t>(*vertex)) +
                             " out of range (the file has " + std::to_string(vertex_count_) +
                             " vertices)");
        }
        polygon_.push_back(static_cast<std::int32_t>(*vertex));
    }
    if (count < 3) {
        return error(ErrorCode::kFormat, "a face needs at least 3 vertex indices, this one has " +
                                             std::to_string(count));
    }
    for (std::size_t i = 1; i + 1 < count; ++i) {
        data_.triangles.emplace_back(polygon_[0], polygon_[i], polygon_[i + 1]);
    }
    return {};
}

template <class Source>
Expected<void> BodyReader<Source>::read_range_grid(const PlyElement& element) {
    if (!header_.num_rows || !header_.num_cols) {
        return element_error(ErrorCode::kFormat,
                             "needs 'obj_info num_rows' and 'obj_info "
                             "num_cols' header lines");
    }
    const std::int64_t rows = *header_.num_rows;
    const std::int64_t cols = *header_.num_cols;
    if (static_cast<std::uint64_t>(rows * cols) != element.count) {
        return element_error(ErrorCode::kFormat,
                             std::to_string(element.count) +
                                 " entries, but num_rows * num_cols = " + std::to_string(rows) +
                                 " * " + std::to_string(cols));
    }
    const std::size_t list = index_list_of(element);
    if (list == element.properties.size()) {
        return element_error(ErrorCode::kUnsupported, "no 'vertex_indices' list property");
    }
    if (!is_integer(element.properties[list].type)) {
        return element_error(ErrorCode::kUnsupported, "non-integer 'vertex_indices'");
    }
    if (!fits(element)) return doomed(element);
    RangeGrid grid{
        .rows = static_cast<int>(rows), .cols = static_cast<int>(cols), .point_index = {}};
    grid.point_index.assign(element.count, RangeGrid::kNoSample);
    Expected<void> done = walk(
        element, [](std::size_t, double) {},
        [&](std::size_t k, std::size_t count) {
            return k == list ? read_grid_entry(element.properties[k], count, grid)
                             : skip_items(element.properties[k], count);
        });
    if (!done) return done;
    data_.grid = std::move(grid);
    return {};
}

template <class Source>
Expected<void> BodyReader<Source>::read_grid_entry(const PlyProperty& property, std::size_t count,
                                                   RangeGrid& grid) {
    if (count > 1) {
        return error(ErrorCode::kFormat, "a range_grid entry lists " + std::to_string(count) +
                                             " vertex indices (0 or 1 expected)");
    }
    if (count == 0) return {};
    const Expected<double> vertex = value(property, property.type);
    if (!vertex) return fail(vertex.error());
    if (*vertex < 0 || *vertex >= static_cast<double>(vertex_count_)) {
        return error(ErrorCode::kFormat, "vertex index " +
                                             std::to_string(static_cast<std::int64_t>(*vertex)) +
                                             " out of range (the file has " +
                                             std::to_string(vertex_count_) + " vertices)");
    }
    grid.point_index[index_] = static_cast<std::int32_t>(*vertex);
    return {};
}

}  // namespace anascan::io::ply_detail
