#pragma once
// Plain values as bytes in this machine's own order and layout: a message between a process
// and its own fork (isolated_call.hpp), never a file format.

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace anascan::drivers {

/// Appends values to a message. Not thread-safe.
class ByteWriter {
public:
    template <class T>
    requires std::is_trivially_copyable_v<T>
    void put(const T& value) { bytes_.append(reinterpret_cast<const char*>(&value), sizeof value); }
    void put_string(std::string_view text) {
        put<std::uint64_t>(text.size());
        bytes_.append(text);
    }
    template <class T>
    requires std::is_trivially_copyable_v<T>
    void put_vector(const std::vector<T>& values) {
        put<std::uint64_t>(values.size());
        if (!values.empty())
            bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
    }
    std::string take() && { return std::move(bytes_); }

private:
    std::string bytes_;
};

/// Reads values back in the order they were put. A read past the end fails, and so does
/// every read after it: check `ok()` (and `at_end()`) once at the end. Not thread-safe.
class ByteReader {
public:
    explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}

    /// The next value; a zero value once reading failed.
    template <class T>
    requires std::is_trivially_copyable_v<T> T get() {
        T value{};
        if (!ok_ || bytes_.size() < sizeof value) {
            ok_ = false;
            return value;
        }
        std::memcpy(&value, bytes_.data(), sizeof value);
        bytes_.remove_prefix(sizeof value);
        return value;
    }
    std::string get_string() {
        const auto size = get<std::uint64_t>();
        if (!ok_ || bytes_.size() < size) {
            ok_ = false;
            return {};
        }
        std::string text(bytes_.substr(0, size));
        bytes_.remove_prefix(size);
        return text;
    }
    template <class T>
    requires std::is_trivially_copyable_v<T> std::vector<T> get_vector() {
        const auto size = get<std::uint64_t>();
        if (!ok_ || bytes_.size() / sizeof(T) < size) {
            ok_ = false;
            return {};
        }
        std::vector<T> values(size);
        if (size > 0) std::memcpy(values.data(), bytes_.data(), size * sizeof(T));
        bytes_.remove_prefix(size * sizeof(T));
        return values;
    }
    bool ok() const { return ok_; }
    bool at_end() const { return ok_ && bytes_.empty(); }

private:
    std::string_view bytes_;
    bool ok_ = true;
};

}  // namespace anascan::drivers
