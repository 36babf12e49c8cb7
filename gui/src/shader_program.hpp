#pragma once
/// \file
/// Compiling and linking a GLSL program (private to the gui module).

#include <string_view>

#include "anascan/processing/core/expected.hpp"
#include "gl_api.hpp"

namespace anascan::gui::detail {

/// Compiles and links a vertex + fragment program; the error names the stage and carries
/// the driver's log. Needs a current GL context.
Expected<GLuint> build_program(std::string_view vertex_source, std::string_view fragment_source);

}  // namespace anascan::gui::detail
