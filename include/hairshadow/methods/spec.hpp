#pragma once
/// @file
/// Method specs: the text form of a method (`osm:16`, `dom:3`, `occ:128:4:8bit`, `dsm`, ...).

#include <hairshadow/core/error.hpp>
#include <hairshadow/core/parse.hpp>
#include <hairshadow/reconstruction/fibre_density.hpp>

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>

namespace hairshadow {

/// The grammar of method specs.
inline constexpr std::string_view method_grammar =
    "osm:N[:uniform|gamma] (N = 1, 2, 4, ..., 512) | dom:K (K = 1..8) | dc:K (K = 1..8) | occ:S:B (S = 32, 64, 128, 256; "
    "B = 1, 2, 4, 8) | docc:S:B (hybrid: occupancy slices from each texel's first fragment) | rosm:N (hybrid: opacity maps in "
    "each texel's depth range, N = 4, 8, ..., 256) | adsm[:SPACING:RADIUS:ALPHA[:MAX]] (TressFX's approximate deep shadow "
    "maps: fibre spacing in radii, fibre radius in world units, fibre alpha, and optionally a cap on the fibres counted, a whole number; default "
    "0.4:0.0021:0.35 and no cap, as TressFX's shader) | adsm:auto (each texel's "
    "measured fibre density) | dsm (exact) | dsm:EPS (Lokovic-Veach compression, 0 < EPS < 1); "
    "append :8bit to osm, dom, dc or occ for emulated 8-bit accumulation";

/// A bad method spec; what() quotes the valid grammar.
class spec_error : public argument_error {
public:
    using argument_error::argument_error;
};

/// The method families.
enum class method_family { osm, dom, dc, occ, docc, rosm, adsm, dsm };

/// A parsed method spec.
struct method_spec {
    std::string text;
    method_family family = method_family::dsm;
    int layers = 0;                 ///< N, K or S
    int slabs = 0;                  ///< B (occ, docc)
    bool gamma = false;             ///< osm: gamma spacing
    bool eight_bit = false;         ///< emulated 8-bit accumulation
    std::optional<float> tolerance; ///< dsm: compression tolerance
    fibre_density_parameters density; ///< adsm: TressFX's fibre parameters
    bool measured_density = false;    ///< adsm:auto
};

namespace detail {
inline constexpr std::array<int, 10> osm_sizes{1, 2, 4, 8, 16, 32, 64, 128, 256, 512};
inline constexpr std::array<int, 8> small_sizes{1, 2, 3, 4, 5, 6, 7, 8};
inline constexpr std::array<int, 4> slice_sizes{32, 64, 128, 256};
inline constexpr std::array<int, 4> slab_sizes{1, 2, 4, 8};
inline constexpr std::array<int, 7> rosm_sizes{4, 8, 16, 32, 64, 128, 256};

template <std::size_t Size>
bool one_of(int n, const std::array<int, Size>& allowed) {
    return std::find(allowed.begin(), allowed.end(), n) != allowed.end();
}
} // namespace detail

/// Parses a method spec; throws spec_error with the grammar on anything else.
inline method_spec parse_method_spec(std::string_view text) {
    const auto bad = [&](const std::string& why) {
        return spec_error("bad method spec '" + std::string(text) + "': " + why + "; valid: " + std::string(method_grammar));
    };
    auto parts = detail::split(text, ':');
    method_spec spec;
    spec.text = std::string(text);
    if (parts.size() > 1 && parts.back() == "8bit") {
        spec.eight_bit = true;
        parts.pop_back();
    }
    // A count is a name's part, written as one would say it: no sign and no leading zero (dom:03 is a typo).
    auto number = [&](std::string_view s) {
        if (s.size() > 1 && s[0] == '0') throw bad("'" + std::string(s) + "' has a leading zero");
        try {
            return detail::parse_number<int>(s, "count");
        } catch (const argument_error&) {
            throw bad("'" + std::string(s) + "' is not a whole number");
        }
    };
    const auto& name = parts[0];
    if (name == "osm" && (parts.size() == 2 || parts.size() == 3)) {
        spec.family = method_family::osm;
        spec.layers = number(parts[1]);
        if (!detail::one_of(spec.layers, detail::osm_sizes)) throw bad("osm needs N = 1, 2, 4, ..., 512");
        if (parts.size() == 3) {
            if (parts[2] == "gamma") spec.gamma = true;
            else if (parts[2] != "uniform") throw bad("osm spacing must be uniform or gamma");
        }
    } else if ((name == "dom" || name == "dc") && parts.size() == 2) {
        spec.family = name == "dom" ? method_family::dom : method_family::dc;
        spec.layers = number(parts[1]);
        if (!detail::one_of(spec.layers, detail::small_sizes)) throw bad(std::string(name) + " needs K = 1..8");
    } else if ((name == "occ" || name == "docc") && parts.size() == 3) {
        spec.family = name == "occ" ? method_family::occ : method_family::docc;
        spec.layers = number(parts[1]);
        spec.slabs = number(parts[2]);
        if (!detail::one_of(spec.layers, detail::slice_sizes) || !detail::one_of(spec.slabs, detail::slab_sizes))
            throw bad(std::string(name) + " needs S = 32, 64, 128 or 256 slices and B = 1, 2, 4 or 8 slabs");
    } else if (name == "rosm" && parts.size() == 2) {
        spec.family = method_family::rosm;
        spec.layers = number(parts[1]);
        if (!detail::one_of(spec.layers, detail::rosm_sizes)) throw bad("rosm needs N = 4, 8, ..., 256");
    } else if (name == "adsm" && (parts.size() == 1 || parts.size() == 2 || parts.size() == 4 || parts.size() == 5)) {
        spec.family = method_family::adsm;
        if (parts.size() == 2) {
            if (parts[1] != "auto") throw bad("adsm takes auto or SPACING:RADIUS:ALPHA[:MAX]");
            spec.measured_density = true;
        } else if (parts.size() >= 4) {
            auto real = [&](std::string_view s, const char* what) {
                try {
                    return detail::parse_number<float>(s, what);
                } catch (const argument_error&) {
                    throw bad("the fibre " + std::string(what) + " '" + std::string(s) + "' is not a number");
                }
            };
            spec.density.spacing = real(parts[1], "spacing");
            spec.density.radius = real(parts[2], "radius");
            spec.density.alpha = real(parts[3], "alpha");
            if (parts.size() == 5) {
                const int cap = number(parts[4]);
                if (cap < 1) throw bad("the fibre cap must be at least one fibre");
                spec.density.max_fibres = float(cap);
            }
            try {
                spec.density.check();
            } catch (const argument_error& e) {
                throw bad(e.what());
            }
        }
    } else if (name == "dsm" && (parts.size() == 1 || parts.size() == 2)) {
        spec.family = method_family::dsm;
        if (parts.size() == 2) {
            float eps = 0.0f;
            try {
                eps = detail::parse_number<float>(parts[1], "tolerance");
            } catch (const argument_error&) {
                throw bad("the tolerance is not a number");
            }
            if (!(eps > 0.0f && eps < 1.0f)) throw bad("the tolerance must be in (0, 1)");
            spec.tolerance = eps;
        }
    } else {
        throw bad("unknown method or wrong number of fields");
    }
    if (spec.eight_bit && (spec.family == method_family::dsm || spec.family == method_family::docc || spec.family == method_family::rosm ||
                           spec.family == method_family::adsm))
        throw bad(":8bit applies to osm, dom, dc and occ");
    return spec;
}

namespace detail {

/// The method of a spec with the spec's parameters: policies that take parameters (a fibre density)
/// are made from them, the others as they default.
template <class Method>
Method method_of(const method_spec& spec) {
    using R = typename Method::reconstruction_type;
    if constexpr (std::is_constructible_v<R, fibre_density_parameters>) return Method(typename Method::placement_type(), R(spec.density));
    else return Method();
}

} // namespace detail

} // namespace hairshadow
