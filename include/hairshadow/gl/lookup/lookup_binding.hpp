#pragma once
/// @file
/// Look-ups that compose: a method's GLSL look-up with every name given a prefix of the caller's, so
/// that any number of look-ups (two lights, a key light and a fill light with different methods)
/// share one shader; and the binding of a look-up's uniforms and textures to a program that need not
/// be current (glProgramUniform, GL 4.1).

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/gl/context/error.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdio>
#include <string>
#include <string_view>

namespace hairshadow::gl {

/// The prefix of the library's own GLSL names: hs_transmittance, hs_lookup_view, HS_LAYERS.
inline constexpr std::string_view default_lookup_prefix = "hs_";

/// Throws argument_error unless `prefix` can start GLSL names: a letter, then letters, digits and
/// single underscores, at most 32 characters, not GL's reserved "gl_".
inline void check_lookup_prefix(std::string_view prefix) {
    const auto fail = [&](const char* why) { throw argument_error("look-up prefix '" + std::string(prefix) + "': " + why); };
    if (prefix.empty() || prefix.size() > 32) fail("needs 1 to 32 characters");
    if (!std::isalpha(static_cast<unsigned char>(prefix[0]))) fail("must start with a letter");
    for (char c : prefix)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') fail("may hold only letters, digits and '_'");
    if (prefix.find("__") != std::string_view::npos) fail("GLSL reserves names with two underscores in a row");
    if (prefix.size() >= 3 && std::tolower(static_cast<unsigned char>(prefix[0])) == 'g' && std::tolower(static_cast<unsigned char>(prefix[1])) == 'l' &&
        prefix[2] == '_')
        fail("GLSL reserves names starting with gl_");
}

/// The first lines of every composed look-up: a shader that includes it under an older #version
/// fails with this message rather than a syntax error deep in the look-up. GLSL 4.30 is what the
/// library's tests compile the look-ups under (the GL back end needs GL 4.3 anyway).
inline constexpr std::string_view lookup_version_check =
    "// hairshadow's look-up: GLSL 4.30 or newer\n"
    "#if __VERSION__ < 430\n"
    "#error the hairshadow look-up needs GLSL 4.30 or newer: begin the shader with #version 430 core or newer\n"
    "#endif\n";

/// `name` (one of the library's, starting hs_) under `prefix`: hs_transmittance -> key_transmittance.
inline std::string prefixed_name(std::string_view name, std::string_view prefix) {
    return std::string(prefix) + std::string(name.substr(name.rfind("hs_", 0) == 0 ? 3 : 0));
}

/// GLSL source with every name of the library's renamed under `prefix`: identifiers starting hs_
/// start with `prefix` instead, and macros starting HS_ with `prefix` in upper case (so two prefixes
/// must differ in more than case). Words are renamed whole, in code and comments alike.
inline std::string prefix_glsl(std::string_view source, std::string_view prefix) {
    check_lookup_prefix(prefix);
    std::string macro_prefix(prefix);
    for (auto& c : macro_prefix) c = char(std::toupper(static_cast<unsigned char>(c)));
    const auto word_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    std::string out;
    out.reserve(source.size() + source.size() / 8);
    for (std::size_t i = 0; i < source.size();) {
        if (!word_char(source[i])) {
            out += source[i++];
            continue;
        }
        std::size_t end = i;
        while (end < source.size() && word_char(source[end])) ++end;
        const auto word = source.substr(i, end - i);
        if (word.rfind("hs_", 0) == 0) out.append(prefix).append(word.substr(3));
        else if (word.rfind("HS_", 0) == 0) out.append(macro_prefix).append(word.substr(3));
        else out.append(word);
        i = end;
    }
    return out;
}

/// Sets a look-up's uniforms on program `prog` (current or not) and binds its textures to consecutive
/// units from `first_unit`, each with no sampler object; the active texture unit is left as found.
/// Binding a user's look-up (the default), every uniform must be active in the program: a look-up
/// that cannot be bound (a prefix the program does not use, a look-up it does not call) throws
/// argument_error naming the missing uniform, as does a name that is not a linked program. The
/// library's own passes bind what their programs kept (missing_uniform::skip). Allocates nothing.
class lookup_binder {
public:
    enum class missing_uniform { refuse, skip };

    lookup_binder(GLuint prog, int first_unit, std::string_view prefix, float depth_bias = 0.0f, missing_uniform missing = missing_uniform::refuse)
        : program_(prog), unit_(first_unit), prefix_(prefix), depth_bias_(depth_bias), missing_(missing) {
        check_lookup_prefix(prefix);
        if (!(depth_bias >= -1.0f && depth_bias <= 1.0f))
            throw argument_error("look-up depth bias " + std::to_string(depth_bias) + " is not within [-1, 1] (the map's linear depth)");
        GLint linked = GL_FALSE;
        if (prog != 0 && glIsProgram(prog)) glGetProgramiv(prog, GL_LINK_STATUS, &linked);
        if (linked != GL_TRUE) throw argument_error("look-up binding: " + std::to_string(prog) + " is not the name of a linked program");
        GLint units = 0;
        glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
        if (first_unit < 0 || first_unit >= units)
            throw argument_error("look-up texture unit " + std::to_string(first_unit) + " is outside [0, " + std::to_string(units) + ")");
        max_units_ = units;
    }

    /// A binder for one of the library's own passes, whose programs may leave out uniforms they do not read.
    static lookup_binder for_pass(GLuint prog, int first_unit) {
        return lookup_binder(prog, first_unit, default_lookup_prefix, 0.0f, missing_uniform::skip);
    }

    /// The location of the library's uniform `name` under the binder's prefix; -1 (skipped) or
    /// argument_error where the program has no such active uniform.
    /// `element`, where not negative, names an element of an array uniform: name[element].
    GLint location(std::string_view name, int element = -1) const { return find(name, element, missing_); }
    void set(std::string_view name, float v, int element = -1) const { glProgramUniform1f(program_, location(name, element), v); }
    /// The same, skipped where the program has no such active uniform.
    void set_if_active(std::string_view name, float v, int element = -1) const {
        const GLint at = find(name, element, missing_uniform::skip);
        if (at >= 0) glProgramUniform1f(program_, at, v);
    }
    void set(std::string_view name, int v) const { glProgramUniform1i(program_, location(name), v); }
    void set(std::string_view name, const glm::mat4& m) const { glProgramUniformMatrix4fv(program_, location(name), 1, GL_FALSE, &m[0][0]); }

    /// Binds `texture_name` (of `target`) to the next unit and points sampler uniform `name` at it.
    /// `element` as in location().
    void texture(std::string_view name, GLenum target, GLuint texture_name, int element = -1) {
        if (unit_ >= max_units_) throw argument_error("the look-up needs texture units beyond GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS");
        const GLint at = location(name, element); // before anything is bound
        GLint active = 0;
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
        glActiveTexture(GLenum(GL_TEXTURE0 + unit_));
        glBindTexture(target, texture_name);
        glActiveTexture(GLenum(active));
        glBindSampler(GLuint(unit_), 0);
        glProgramUniform1i(program_, at, unit_++);
    }

    /// Linear depth the look-up moves each point towards the light (query_options::depth_bias).
    float depth_bias() const noexcept { return depth_bias_; }

private:
    GLint find(std::string_view name, int element, missing_uniform missing) const {
        std::array<char, 96> full{}; // the prefix (at most 32), the library's longest name and an index, with room
        const std::string_view rest = name.substr(name.rfind("hs_", 0) == 0 ? 3 : 0);
        if (prefix_.size() + rest.size() + 16 >= full.size()) throw argument_error("look-up uniform name too long: " + std::string(name));
        char* end = std::copy(rest.begin(), rest.end(), std::copy(prefix_.begin(), prefix_.end(), full.begin()));
        if (element >= 0) std::snprintf(end, 16, "[%d]", element);
        const GLint at = glGetUniformLocation(program_, full.data());
        if (at < 0 && missing == missing_uniform::refuse)
            throw argument_error("program " + std::to_string(program_) + " has no active uniform '" + std::string(full.data()) +
                                 "': does it call " + std::string(prefix_) + "transmittance, composed with prefix '" + std::string(prefix_) + "'?");
        return at;
    }

    GLuint program_;
    int unit_, max_units_ = 0;
    std::string_view prefix_;
    float depth_bias_;
    missing_uniform missing_;
};

/// Sets the light's frustum uniforms of lookup/light.glsl (hs_lookup_*).
inline void set_lookup_frustum(const lookup_binder& b, const light_space& light) {
    b.set("hs_lookup_view_projection", light.view_projection());
    b.set("hs_lookup_view", light.view());
    b.set("hs_lookup_near", light.near_plane());
    b.set("hs_lookup_far", light.far_plane());
    b.set("hs_lookup_resolution", light.resolution());
    b.set("hs_lookup_depth_bias", b.depth_bias());
}

} // namespace hairshadow::gl
