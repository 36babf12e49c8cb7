#pragma once
// RAII wrapper of a umockdev test bed (a private /sys and /dev for this process). Needs the
// process to run under umockdev-wrapper (LD_PRELOAD=libumockdev-preload.so.0).

#include <string>

#include "preload_check.hpp"

typedef struct _UMockdevTestbed UMockdevTestbed;
typedef struct _UMockdevIoctlBase UMockdevIoctlBase;

namespace anascan::drivers::test {

/// Owns one UMockdevTestbed. Not thread-safe.
class Testbed {
public:
    Testbed();
    ~Testbed();
    Testbed(const Testbed&) = delete;
    Testbed& operator=(const Testbed&) = delete;

    /// Adds a device from umockdev's text format (P:, N:, E:, A:, H: lines); returns its
    /// sysfs path. Aborts the test on a malformed description.
    std::string add_from_string(const std::string& description);
    /// Routes ioctl()/read() of /dev/<node> to `handler` (not owned).
    void attach(const std::string& dev_path, UMockdevIoctlBase* handler);
    void detach(const std::string& dev_path);
    /// Removes a device (sysfs entry and node), as an unplug does.
    void remove(const std::string& sysfs_path);
    void uevent(const std::string& sysfs_path, const std::string& action);
    std::string sys_dir() const;

private:
    UMockdevTestbed* testbed_;
};

}  // namespace anascan::drivers::test
