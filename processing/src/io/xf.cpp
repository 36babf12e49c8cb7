#include "anascan/processing/io/xf.hpp"

namespace anascan::io {}  // namespace anascan::io
