#include "umockdev_testbed.hpp"

#include <gtest/gtest.h>
#include <umockdev.h>

#include <cstdlib>
#include <cstring>

namespace anascan::drivers::test {

Testbed::Testbed() : testbed_(umockdev_testbed_new()) {}

Testbed::~Testbed() { g_object_unref(testbed_); }

std::string Testbed::add_from_string(const std::string& description) {
    GError* error = nullptr;
    if (!umockdev_testbed_add_from_string(testbed_, description.c_str(), &error)) {
        ADD_FAILURE() << "umockdev: " << error->message;
        g_error_free(error);
        return {};
    }
    const std::size_t p = description.find("P: ");
    const std::size_t end = description.find('\n', p);
    return "/sys" + description.substr(p + 3, end - p - 3);
}

void Testbed::attach(const std::string& dev_path, UMockdevIoctlBase* handler) {
    GError* error = nullptr;
    if (!umockdev_testbed_attach_ioctl(testbed_, dev_path.c_str(), handler, &error)) {
        ADD_FAILURE() << "umockdev attach " << dev_path << ": " << error->message;
        g_error_free(error);
    }
}

void Testbed::detach(const std::string& dev_path) {
    GError* error = nullptr;
    if (!umockdev_testbed_detach_ioctl(testbed_, dev_path.c_str(), &error)) g_error_free(error);
}

void Testbed::remove(const std::string& sysfs_path) {
    umockdev_testbed_remove_device(testbed_, sysfs_path.c_str());
}

void Testbed::uevent(const std::string& sysfs_path, const std::string& action) {
    umockdev_testbed_uevent(testbed_, sysfs_path.c_str(), action.c_str());
}

std::string Testbed::sys_dir() const {
    gchar* dir = umockdev_testbed_get_sys_dir(testbed_);
    std::string s = dir;
    g_free(dir);
    return s;
}

}  // namespace anascan::drivers::test
