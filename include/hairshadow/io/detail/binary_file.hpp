#pragma once
/// @file
/// Bounded binary reading and writing for the model formats: every read checks the bytes left, so a
/// count that the file cannot hold is reported before anything is allocated for it.

#include <hairshadow/config.hpp>
#include <hairshadow/core/error.hpp>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <sys/stat.h>

namespace hairshadow::detail {

/// A C file, closed on leaving scope. The C library's files rather than <fstream> and <filesystem>:
/// those two cost a user's program a few tenths of a second of compile time (docs/performance.md).
using c_file = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;
inline c_file open_file(const std::string& path, const char* mode) noexcept { return {std::fopen(path.c_str(), mode), &std::fclose}; }

/// Reads a whole file into memory (refusing files over HAIRSHADOW_MAX_FILE_BYTES).
HAIRSHADOW_DECL std::vector<unsigned char> read_file_bytes(const std::string& path);

/// A cursor over a byte buffer; every read is checked against the end.
class byte_reader {
public:
    byte_reader(std::span<const unsigned char> bytes, std::string file) : bytes_(bytes), file_(std::move(file)) {}

    std::size_t position() const noexcept { return pos_; }
    std::size_t remaining() const noexcept { return bytes_.size() - pos_; }
    std::size_t size() const noexcept { return bytes_.size(); }
    const std::string& file() const noexcept { return file_; }

    void seek(std::size_t pos, const char* what) {
        if (pos > bytes_.size()) fail(std::string(what) + " starts past the end of the file");
        pos_ = pos;
    }
    /// Throws unless `count` items of `item_size` bytes remain; names `what` in the message.
    void require(std::uint64_t count, std::size_t item_size, const std::string& what) const {
        if (item_size != 0 && count > remaining() / item_size)
            fail("truncated: " + what + " needs " + std::to_string(count) + " x " + std::to_string(item_size) +
                 " bytes but " + std::to_string(remaining()) + " remain");
    }
    template <class T>
    T read(const char* what) {
        static_assert(std::is_trivially_copyable_v<T>);
        require(1, sizeof(T), what);
        T value;
        std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
        pos_ += sizeof(T);
        return value;
    }
    /// Reads `count` values of T after checking that the file holds them.
    template <class T>
    std::vector<T> read_array(std::uint64_t count, const std::string& what) {
        std::vector<T> values;
        append_array(count, values, what);
        return values;
    }
    /// Appends `count` values of T to `values` after checking that the file holds them.
    template <class T>
    void append_array(std::uint64_t count, std::vector<T>& values, const std::string& what) {
        static_assert(std::is_trivially_copyable_v<T>);
        require(count, sizeof(T), what);
        if (count == 0) return; // no memcpy from or to a null pointer
        const std::size_t before = values.size();
        values.resize(before + static_cast<std::size_t>(count));
        std::memcpy(values.data() + before, bytes_.data() + pos_, sizeof(T) * static_cast<std::size_t>(count));
        pos_ += sizeof(T) * static_cast<std::size_t>(count);
    }
    [[noreturn]] void fail(const std::string& reason) const { throw io_error(file_, reason); }

private:
    std::span<const unsigned char> bytes_;
    std::string file_;
    std::size_t pos_ = 0;
};

/// Accumulates bytes for a file and writes them at once.
class byte_writer {
public:
    template <class T>
    void write(const T& value) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const unsigned char*>(&value);
        bytes_.insert(bytes_.end(), p, p + sizeof(T));
    }
    template <class T>
    void write_array(const std::vector<T>& values) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const unsigned char*>(values.data());
        bytes_.insert(bytes_.end(), p, p + sizeof(T) * values.size());
    }
    void save(const std::string& path) const {
        c_file out = open_file(path, "wb");
        if (!out) throw io_error(path, "cannot open for writing");
        const bool written = bytes_.empty() || std::fwrite(bytes_.data(), 1, bytes_.size(), out.get()) == bytes_.size();
        if (!written || std::fclose(out.release()) != 0) throw io_error(path, "write failed");
    }

private:
    std::vector<unsigned char> bytes_;
};

/// Runs validate() and re-throws a model_error as an io_error naming the file.
template <class Model>
Model validated(Model model, const std::string& file) {
    try {
        validate(model);
    } catch (const model_error& e) {
        throw io_error(file, e.what());
    }
    return model;
}

#if HAIRSHADOW_KERNEL_BODIES
HAIRSHADOW_DECL std::vector<unsigned char> read_file_bytes(const std::string& path) {
    struct stat status {};
    if (::stat(path.c_str(), &status) != 0) throw io_error(path, "no such file");
    if (S_ISDIR(status.st_mode)) throw io_error(path, "is a directory");
    const c_file in = open_file(path, "rb");
    if (!in) throw io_error(path, "cannot open for reading");
    if (status.st_size < 0) throw io_error(path, "cannot determine the file size");
    if (static_cast<std::uint64_t>(status.st_size) > HAIRSHADOW_MAX_FILE_BYTES) throw io_error(path, "file is larger than the configured maximum");
    std::vector<unsigned char> bytes(static_cast<std::size_t>(status.st_size));
    if (!bytes.empty() && std::fread(bytes.data(), 1, bytes.size(), in.get()) != bytes.size()) throw io_error(path, "read failed");
    return bytes;
}
#endif

} // namespace hairshadow::detail
