#include "anascan/processing/voxel_grid.hpp"

namespace anascan {}  // namespace anascan
