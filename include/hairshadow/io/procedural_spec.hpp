#pragma once
/// @file
/// Parses `procedural:NAME[:key=value...]` into procedural_options.

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/parse.hpp>
#include <hairshadow/procedural/generators.hpp>

#include <string>
#include <string_view>

namespace hairshadow {

/// The grammar of procedural model specs, for error messages and --help.
inline constexpr std::string_view procedural_grammar =
    "procedural:straight|wavy|curly|clumped[:strands=N][:segments=N][:seed=N][:length=F][:radius=F]"
    "[:amplitude=F][:wavelength=F][:clumps=N]";


/// True when `source` names a procedural model rather than a file.
inline bool is_procedural_spec(std::string_view source) { return source.starts_with("procedural:"); }

/// Parses a procedural spec; throws argument_error quoting the grammar on anything unknown.
inline procedural_options parse_procedural_spec(std::string_view spec) {
    const auto bad = [&](const std::string& why) {
        return argument_error("bad model spec '" + std::string(spec) + "': " + why + "; expected " + std::string(procedural_grammar));
    };
    if (!is_procedural_spec(spec)) throw bad("it does not start with 'procedural:'");
    const auto parts = detail::split(spec.substr(11), ':');
    procedural_options o;
    if (parts[0] == "straight") o.style = hair_style::straight;
    else if (parts[0] == "wavy") o.style = hair_style::wavy;
    else if (parts[0] == "curly") o.style = hair_style::curly;
    else if (parts[0] == "clumped") o.style = hair_style::clumped;
    else throw bad("unknown style '" + std::string(parts[0]) + "'");
    for (std::size_t i = 1; i < parts.size(); ++i) {
        const auto eq = parts[i].find('=');
        if (eq == std::string_view::npos) throw bad("'" + std::string(parts[i]) + "' is not key=value");
        const auto key = parts[i].substr(0, eq);
        const auto value = parts[i].substr(eq + 1);
        try {
            if (key == "strands") o.strands = detail::parse_number<std::size_t>(value, key);
            else if (key == "segments") o.segments = detail::parse_number<std::size_t>(value, key);
            else if (key == "seed") o.seed = detail::parse_number<std::uint64_t>(value, key);
            else if (key == "length") o.length = detail::parse_number<float>(value, key);
            else if (key == "radius") o.head_radius = detail::parse_number<float>(value, key);
            else if (key == "amplitude") o.wave_amplitude = detail::parse_number<float>(value, key);
            else if (key == "wavelength") o.wave_length = detail::parse_number<float>(value, key);
            else if (key == "clumps") o.clumps = detail::parse_number<std::size_t>(value, key);
            else throw bad("unknown key '" + std::string(key) + "'");
        } catch (const argument_error& e) {
            if (std::string_view(e.what()).starts_with("bad model spec")) throw;
            throw bad(e.what());
        }
    }
    return o;
}

} // namespace hairshadow
