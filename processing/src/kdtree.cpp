#include "anascan/processing/kdtree.hpp"

namespace anascan {}  // namespace anascan
