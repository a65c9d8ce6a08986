#pragma once
/// @file
/// The typed exceptions of hairshadow. Every error the library reports derives from hairshadow::error.

#include <stdexcept>
#include <string>
#include <utility>

namespace hairshadow {

/// Base of every exception thrown by hairshadow.
class error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// A file could not be read or written, or its content is malformed. what() is "FILE: reason".
class io_error : public error {
public:
    io_error(std::string file, std::string reason)
        : error(file + ": " + reason), file_(std::move(file)), reason_(std::move(reason)) {}
    /// The file that failed.
    const std::string& file() const noexcept { return file_; }
    /// Why it failed, without the file name.
    const std::string& reason() const noexcept { return reason_; }

private:
    std::string file_;
    std::string reason_;
};

/// A hair model breaks an invariant (no strands, non-finite coordinates, no segment of non-zero length).
class model_error : public error {
public:
    using error::error;
};

/// An argument is out of its valid range (resolution, light, method spec, option value).
class argument_error : public error {
public:
    using error::error;
};

} // namespace hairshadow
