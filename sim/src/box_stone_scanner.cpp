#include "anascan/sim/box_stone_scanner.hpp"

namespace anascan::sim {}  // namespace anascan::sim
