#include "anascan/processing/io/text_points.hpp"

namespace anascan::io {}  // namespace anascan::io
