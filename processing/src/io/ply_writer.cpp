#include "anascan/processing/io/ply.hpp"

namespace anascan::io {}  // namespace anascan::io
