#include "anascan/processing/io/ptx.hpp"

namespace anascan::io {}  // namespace anascan::io
