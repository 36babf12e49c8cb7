#include "anascan/processing/io/stanford_conf.hpp"

namespace anascan::io {}  // namespace anascan::io
