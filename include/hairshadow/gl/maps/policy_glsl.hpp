#pragma once
/// @file
/// The GL side of a policy, read from the policy itself (docs/policies.md, "A policy on GL"), so that a
/// placement or accumulation of the user's own, with its GLSL, builds and looks up on GL without an
/// edit to the library:
/// - its GLSL: `P::glsl_source()` where the policy gives its own text, else the library's snippets
///   named by `P::glsl_name` (shaders/<glsl_name>.glsl; a placement's per-texel state, from the depth
///   range, in shaders/texel_state/<name>.glsl);
/// - its defines, `P::glsl_defines()`, and its uniforms, `p.glsl_uniforms(set)` calling
///   set(name, value) for each, where it has any;
/// - a placement's per-texel state: from the light pass's depth range (the placement's own
///   prepare_texel on the nearest and furthest fragment), unless state_pass_of<P> names passes of its
///   own (density clustering's k-means, gl/maps/cluster_state_pass.hpp);
/// - an accumulation's texture format: 8-bit (RGBA8, unsigned normalised) where it stores
///   std::uint8_t, else RGBA32F.

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/gl/passes/light_pass.hpp>
#include <hairshadow/gl/lookup/lookup_binding.hpp>
#include <hairshadow/gl/shaders.generated.hpp>
#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/raster/raster_options.hpp>

#include <cstdint>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace hairshadow::gl {

/// The library's GLSL snippet named `name` (its path under shaders/ without .glsl), or an empty view.
inline std::string_view find_library_snippet(std::string_view name) noexcept {
    for (const auto& e : shaders::all)
        if (e.name == name) return e.source;
    return {};
}
/// The same; throws argument_error where there is none.
inline std::string_view library_snippet(std::string_view name) {
    if (const auto s = find_library_snippet(name); !s.empty()) return s;
    throw argument_error("no GLSL snippet named '" + std::string(name) + "' in the library's shaders/; a policy of your own gives its text by glsl_source()");
}

namespace detail {

/// The text of a policy's GLSL: its own (glsl_source()), kept for the program's lifetime, else the
/// library's snippet `library_name`.
template <class Policy>
std::string_view policy_source(std::string_view library_name) {
    if constexpr (requires { Policy::glsl_source(); }) {
        static const std::string text(Policy::glsl_source());
        return text;
    } else {
        return library_snippet(library_name);
    }
}

/// A policy's defines (glsl_defines()), or none.
template <class Policy>
std::string policy_defines() {
    if constexpr (requires { Policy::glsl_defines(); }) return std::string(Policy::glsl_defines());
    else return "";
}

/// Sets a policy's uniforms (glsl_uniforms(set)) on a look-up binder, if it has any: set(name, value)
/// for a float, set(name, value, k) for element k of a float array (named without an allocation).
/// `required`: a uniform the program lacks is refused as the binder refuses it; else skipped (a
/// placement's uniforms, which a look-up that never locates a layer does not read: fibre density).
template <class Policy>
void set_policy_uniforms(const lookup_binder& binder, const Policy& policy, bool required = true) {
    const auto set = [&](std::string_view name, float value, int element = -1) {
        if (required) binder.set(name, value, element);
        else binder.set_if_active(name, value, element);
    };
    if constexpr (requires { policy.glsl_uniforms(set); }) policy.glsl_uniforms(set);
}

/// The per-texel state of placements whose state follows from the depth range: nothing more to draw.
struct range_state {
    static constexpr int texture_units = 0;
    static std::string defines() { return ""; }
    void run(const hair_mesh&, const light_space&, const raster_options&, const range_textures&, GLuint) {}
    void bind(lookup_binder&) const {}
    void read_back() {}
    /// The CPU texel state, from a depth-range texel (nearest in [0], furthest in [3]).
    template <class P>
    typename P::texel_state texel_state(const P& placement, const float* range, std::size_t) const {
        typename P::texel_state s{};
        const fragment pair[2] = {{range[0], 0.0f}, {range[3], 0.0f}};
        placement.prepare_texel(std::span<const fragment>(pair, 2), s); // the state's own pre-pass, on the two extremes
        return s;
    }
};

} // namespace detail

/// The passes that give a placement's texels their state on GL: from the depth range (range_state)
/// unless specialised beside the placement's GL side (density clustering: gl/maps/cluster_state_pass.hpp).
template <class P>
struct state_pass_of {
    using type = detail::range_state;
};

/// What a placement brings to a GL program, from its members (see the file's comment).
template <class P>
struct placement_glsl {
    using state_pass = typename state_pass_of<P>::type;
    /// Its defines, and its state passes'.
    static std::string defines() { return detail::policy_defines<P>() + state_pass::defines(); }
    /// Its snippets, which define hs_assign_from and hs_locate_from (a fragment's layer and a query's
    /// position from the texel's depth-range map): the placement's own text, or the library's
    /// shaders/<glsl_name>.glsl, followed by shaders/texel_state/<name>.glsl where one exists (a
    /// placement whose state passes read the first file alone keeps the second apart: clustered).
    static std::vector<std::string_view> sources() {
        if constexpr (requires { P::glsl_source(); }) {
            return {detail::policy_source<P>("")};
        } else {
            const std::string_view name = P::glsl_name; // "placement/<name>"
            const auto state = find_library_snippet("texel_state/" + std::string(name.substr(name.find('/') + 1)));
            if (state.empty()) return {library_snippet(name)};
            return {library_snippet(name), state};
        }
    }
    static void set_uniforms(const lookup_binder& binder, const P& placement) { detail::set_policy_uniforms(binder, placement, false); }
};

/// What an accumulation brings to a GL program (see the file's comment).
template <class A>
struct accumulation_glsl {
    /// Stored in 8 bits: RGBA8 targets and images, read back as unsigned bytes.
    static constexpr bool unorm8 = std::is_same_v<typename A::value_type, std::uint8_t>;
    static constexpr GLenum texture_format = unorm8 ? GL_RGBA8 : GL_RGBA32F;
    static constexpr GLenum pixel_type = unorm8 ? GL_UNSIGNED_BYTE : GL_FLOAT;
    static constexpr std::size_t texel_bytes = unorm8 ? 4 : 16;
    /// hs_encode and hs_decode.
    static std::string_view source() { return detail::policy_source<A>(A::glsl_name); }
    /// Its defines; on the compute path, the stored images' format and whether sums are 8-bit steps.
    static std::string defines() { return detail::policy_defines<A>(); }
    static std::string image_defines(std::string_view format_macro) {
        return "#define " + std::string(format_macro) + (unorm8 ? " rgba8\n#define HS_EIGHT_BIT\n" : " rgba32f\n");
    }
};

/// `before`, then the placement's sources (placement_glsl<P>::sources()), then `after`: a stage's pieces.
template <class P>
std::vector<std::string_view> around_placement(std::initializer_list<std::string_view> before, std::initializer_list<std::string_view> after) {
    std::vector<std::string_view> pieces(before);
    for (const auto s : placement_glsl<P>::sources()) pieces.push_back(s);
    pieces.insert(pieces.end(), after);
    return pieces;
}

/// Whether a placement's per-texel state comes from the range map alone.
template <class P>
inline constexpr bool range_placement = std::is_same_v<typename placement_glsl<P>::state_pass, detail::range_state>;

} // namespace hairshadow::gl
