#pragma once
/// @file
/// Loads a hair model from a file (by extension: .hair, .tfx, .data, .obj) or a procedural spec.

#include <hairshadow/io/data_format.hpp>
#include <hairshadow/io/hair_format.hpp>
#include <hairshadow/io/obj_format.hpp>
#include <hairshadow/io/procedural_spec.hpp>
#include <hairshadow/io/tfx_format.hpp>

#include <algorithm>
#include <cctype>
#include <string>

namespace hairshadow {

/// The extension of `path` in lower case (".tfx"), which names its format.
inline std::string model_format_extension(const std::string& path) {
    // std::filesystem::path(path).extension(), without <filesystem>: the file name's last dot onwards,
    // none for a name that starts with its only dot (".hair") or is "." or "..".
    const std::string name = path.substr(path.find_last_of('/') + 1);
    const std::size_t dot = name.find_last_of('.');
    std::string ext = dot == std::string::npos || dot == 0 || name == ".." ? std::string() : name.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

/// Reads `source`: a `.hair`, `.tfx`, `.data` or `.obj` file, or `procedural:NAME[:key=value...]`.
/// Throws io_error (files) or argument_error (specs).
inline hair_model load_model(const std::string& source) {
    if (is_procedural_spec(source)) return make_procedural(parse_procedural_spec(source));
    const std::string ext = model_format_extension(source);
    if (ext == ".hair") return read_hair(source);
    if (ext == ".tfx") return read_tfx(source);
    if (ext == ".data") return read_data(source);
    if (ext == ".obj") return read_obj_hair(source);
    throw io_error(source, "unknown model format '" + ext + "' (expected .hair, .tfx, .data, .obj or procedural:...)");
}

/// Writes a model by extension: `.hair`, `.data` or `.tfx` (TressFX 4).
inline void save_model(const hair_model& model, const std::string& path) {
    const std::string ext = model_format_extension(path);
    if (ext == ".hair") return write_hair(model, path);
    if (ext == ".data") return write_data(model, path);
    if (ext == ".tfx") return write_tfx(model, path);
    throw io_error(path, "cannot write format '" + ext + "' (expected .hair, .data or .tfx)");
}

} // namespace hairshadow
