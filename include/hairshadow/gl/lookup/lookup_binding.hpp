#pragma once
/// @file
/// Look-ups that compose: a method's GLSL look-up with every name given a prefix of the caller's, so
/// that any number of look-ups (two lights, a key light and a fill light with different methods)
/// share one shader; and the binding of a look-up's uniforms and textures to a program that need not
/// be current (glProgramUniform, GL 4.1).

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/gl/context/error.hpp>

#include <cctype>
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
class lookup_binder {
public:
    lookup_binder(GLuint prog, int first_unit, std::string_view prefix) : program_(prog), unit_(first_unit), prefix_(prefix) {
        check_lookup_prefix(prefix);
        GLint units = 0;
        glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &units);
        if (first_unit < 0 || first_unit >= units)
            throw argument_error("look-up texture unit " + std::to_string(first_unit) + " is outside [0, " + std::to_string(units) + ")");
        max_units_ = units;
    }

    GLint location(std::string_view name) const { return glGetUniformLocation(program_, prefixed_name(name, prefix_).c_str()); }
    void set(std::string_view name, float v) const { glProgramUniform1f(program_, location(name), v); }
    void set(std::string_view name, int v) const { glProgramUniform1i(program_, location(name), v); }
    void set(std::string_view name, const glm::mat4& m) const { glProgramUniformMatrix4fv(program_, location(name), 1, GL_FALSE, &m[0][0]); }

    /// Binds `texture` (of `target`) to the next unit and points sampler uniform `name` at it.
    void texture(std::string_view name, GLenum target, GLuint texture) {
        if (unit_ >= max_units_) throw argument_error("the look-up needs texture units beyond GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS");
        GLint active = 0;
        glGetIntegerv(GL_ACTIVE_TEXTURE, &active);
        glActiveTexture(GLenum(GL_TEXTURE0 + unit_));
        glBindTexture(target, texture);
        glActiveTexture(GLenum(active));
        glBindSampler(GLuint(unit_), 0);
        glProgramUniform1i(program_, location(name), unit_++);
    }

private:
    GLuint program_;
    int unit_, max_units_ = 0;
    std::string_view prefix_;
};

/// Sets the light's frustum uniforms of lookup/light.glsl (hs_lookup_*).
inline void set_lookup_frustum(const lookup_binder& b, const light_space& light) {
    b.set("hs_lookup_view_projection", light.view_projection());
    b.set("hs_lookup_view", light.view());
    b.set("hs_lookup_near", light.near_plane());
    b.set("hs_lookup_far", light.far_plane());
    b.set("hs_lookup_resolution", light.resolution());
}

} // namespace hairshadow::gl
