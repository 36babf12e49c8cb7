// ThreadSanitizer builds only (cmake/AnascanSanitizers.cmake adds this file to every
// executable of the tree): TBB runs its parallel loops on the calling thread. Debian's libtbb
// is not instrumented, so TSan cannot see the synchronisation by which TBB hands a loop's data
// to its worker threads, and would report each hand-over as a race inside our loop bodies;
// with no worker threads there is no hand-over. OpenCV's loops run on TBB too. The threads of
// our own (capture session, session store, device layer, field app) are checked as before.
#include <tbb/global_control.h>

namespace {

const tbb::global_control serial_tbb(tbb::global_control::max_allowed_parallelism, 1);

}  // namespace
