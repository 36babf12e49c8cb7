#include "thread_priority.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace anascan::field {

bool lower_this_thread_priority(int increment) {
    if (increment <= 0) return true;
    // On Linux PRIO_PROCESS with a thread id sets that thread's nice value only.
    const auto tid = static_cast<id_t>(::gettid());
    errno = 0;
    const int current = ::getpriority(PRIO_PROCESS, tid);
    if (current == -1 && errno != 0) return false;
    return ::setpriority(PRIO_PROCESS, tid, std::min(current + increment, 19)) == 0;
}

}  // namespace anascan::field
