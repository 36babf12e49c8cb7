#include "anascan/processing/io/xf.hpp"

#include <array>
#include <cmath>

#include "anascan/processing/io/file_bytes.hpp"
#include "text_lines.hpp"

namespace anascan::io {
namespace {

constexpr double kRotationTolerance = 1e-4;
constexpr double kBottomRowTolerance = 1e-9;

// Reads the four rows; `first_line` receives the line number of the first row.
Expected<Eigen::Matrix4d> read_rows(std::span<const char> bytes, std::string_view source,
                                    int& first_line) {
    text::LineReader reader(bytes, true);
    Eigen::Matrix4d M;
    for (int row = 0; row < 4; ++row) {
        if (!reader.next()) {
            return text::line_error(
                ErrorCode::kTruncated, {source, reader.line_number()},
                "expected 4 lines of 4 numbers, found " + std::to_string(row) + " lines");
        }
        const text::LineRef where{source, reader.line_number()};
        if (row == 0) first_line = where.line;
        const text::Fields fields = text::split_fields(reader.line(), text::kBlanks);
        if (fields.count != 4) {
            return text::line_error(ErrorCode::kFormat, where,
                                    "expected 4 numbers (matrix row " + std::to_string(row + 1) +
                                        "), found " + std::to_string(fields.count) + " fields");
        }
        std::array<double, 4> values{};
        if (auto ok = text::parse_doubles(fields, 0, values, where); !ok) return fail(ok.error());
        for (int col = 0; col < 4; ++col) M(row, col) = values[col];
    }
    if (reader.next()) {
        return text::line_error(ErrorCode::kFormat, {source, reader.line_number()},
                                "unexpected content after the 4x4 matrix");
    }
    return M;
}

bool is_bottom_row(const Eigen::Matrix4d& M) {
    const Eigen::RowVector4d expected(0.0, 0.0, 0.0, 1.0);
    return (M.row(3) - expected).cwiseAbs().maxCoeff() <= kBottomRowTolerance;
}

}  // namespace

Expected<Pose> parse_xf(std::span<const char> bytes, std::string_view source_name) {
    int first_line = 1;
    const Expected<Eigen::Matrix4d> M = read_rows(bytes, source_name, first_line);
    if (!M) return fail(M.error());
    if (!is_bottom_row(*M)) {
        return text::line_error(ErrorCode::kFormat, {source_name, first_line + 3},
                                "last row must be '0 0 0 1'");
    }
    const Eigen::Matrix3d R = M->topLeftCorner<3, 3>();
    const double error = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(error <= kRotationTolerance) || R.determinant() <= 0.0) {
        return text::line_error(ErrorCode::kFormat, {source_name, first_line},
                                "the upper 3x3 of rows 1-3 is not a rotation (|R^T R - I| = " +
                                    text::format_exact(error) +
                                    ", det = " + text::format_exact(R.determinant()) + ")");
    }
    Pose T = Pose::Identity();
    T.linear() = R;
    T.translation() = M->topRightCorner<3, 1>();
    return orthonormalized(T);
}

Expected<Pose> read_xf(const std::filesystem::path& path) {
    const Expected<std::vector<char>> bytes = read_file_bytes(path);
    if (!bytes) return fail(bytes.error());
    return parse_xf(*bytes, path.filename().string());
}

std::string format_xf(const Pose& T) {
    const Eigen::Matrix4d M = T.matrix();
    std::string out;
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) {
            out += text::format_exact(M(row, col));
            out += col < 3 ? ' ' : '\n';
        }
    }
    return out;
}

Expected<void> write_xf(const std::filesystem::path& path, const Pose& T) {
    const std::string text = format_xf(T);
    return write_file_atomically(path, text);
}

}  // namespace anascan::io
