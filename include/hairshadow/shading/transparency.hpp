#pragma once
/// @file
/// Transparent hair (Sintorn & Assarsson 2009, section 3.4): every hair fragment of the camera's view
/// blended by an estimate of its depth order, from occupancy and slab maps built from the camera,
/// against exact back-to-front blending, the weighted-average blending of Bavoil & Myers (2008) and
/// opaque hair. The fragments are the CPU renderer's anti-aliased lines, each with alpha = coverage
/// times the strand's opacity and its Kajiya-Kay colour.

#include <hairshadow/methods/published.hpp>
#include <hairshadow/shading/cpu_renderer.hpp>

#include <algorithm>
#include <string_view>

namespace hairshadow {

/// How hair fragments are blended over what lies behind them.
enum class transparency {
    none,      ///< opaque hair: each pixel shows its nearest fragment
    occupancy, ///< occupancy-ordered blending (Sintorn & Assarsson 3.4)
    weighted,  ///< weighted-average blending (Bavoil & Myers 2008)
    exact,     ///< back-to-front blending of the sorted fragments
};

inline transparency parse_transparency(std::string_view name) {
    if (name == "none") return transparency::none;
    if (name == "occupancy") return transparency::occupancy;
    if (name == "weighted") return transparency::weighted;
    if (name == "exact") return transparency::exact;
    throw argument_error("unknown transparency '" + std::string(name) + "'; valid: none, occupancy, weighted, exact");
}

/// A hair fragment seen from the camera.
struct camera_fragment {
    float depth; ///< view distance, normalised to [0, 1] between the camera's near and far planes
    float alpha;
    glm::vec3 colour;
};

/// Every pixel's hair fragments in front of the opaque surface, in drawing order.
struct camera_fragments {
    int width = 0, height = 0;
    std::vector<std::uint64_t> offsets; ///< CSR: pixel i's fragments are [offsets[i], offsets[i + 1])
    std::vector<camera_fragment> fragments;

    std::span<const camera_fragment> pixel(std::size_t i) const noexcept {
        return {fragments.data() + offsets[i], std::size_t(offsets[i + 1] - offsets[i])};
    }
};


/// The hair's fragments from `cam`: anti-aliased lines of `line_width` pixels, alpha = coverage x
/// `opacity`, coloured by `point_colours`, hidden by the surface's depths. Identical for any thread count.
inline camera_fragments collect_camera_fragments(const hair_model& hair, std::span<const glm::vec3> point_colours, const camera& cam,
                                                 const std::vector<float>& surface_inv_w, float opacity, const render_options& options = {}) {
    camera::check_image_size(cam.width, cam.height);
    const glm::mat4 vp = cam.view_projection();
    std::vector<detail::screen_point> screen(hair.point_count());
    for (std::size_t i = 0; i < screen.size(); ++i) screen[i] = detail::to_screen(vp, hair.points[i], cam.width, cam.height);
    constexpr int band_rows = 8;
    const int bands = (cam.height + band_rows - 1) / band_rows;
    using located = std::pair<std::uint32_t, camera_fragment>; // (pixel, fragment)
    std::vector<std::vector<located>> per_band(static_cast<std::size_t>(bands));
    const float span = cam.far_plane - cam.near_plane;
    parallel_for(std::size_t(bands), options.exec, [&](std::size_t band) {
        const int row0 = int(band) * band_rows, row1 = std::min(cam.height, row0 + band_rows);
        auto& out = per_band[band];
        detail::for_each_line_pixel(hair, point_colours, cam, surface_inv_w, options.line_width, row0, row1, screen,
                                    [&](int x, int y, float inv_w, float coverage, const glm::vec3& colour) {
                                        out.push_back({std::uint32_t(y * cam.width + x),
                                                       {(1.0f / inv_w - cam.near_plane) / span, std::min(coverage * opacity, HAIRSHADOW_ALPHA_MAX), colour}});
                                    });
        // Group by pixel, keeping drawing order inside each pixel.
        std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    });
    camera_fragments f;
    f.width = cam.width;
    f.height = cam.height;
    const std::size_t pixels = std::size_t(cam.width) * std::size_t(cam.height);
    f.offsets.assign(pixels + 1, 0);
    for (const auto& band : per_band)
        for (const auto& [pixel, fragment] : band) ++f.offsets[pixel + 1];
    for (std::size_t i = 0; i < pixels; ++i) f.offsets[i + 1] += f.offsets[i];
    f.fragments.reserve(f.offsets.back());
    for (const auto& band : per_band) // bands are in pixel order, and pixels inside each band
        for (const auto& [pixel, fragment] : band) f.fragments.push_back(fragment);
    return f;
}

/// Blends every pixel's fragments over `base` (the opaque surface and background) by `mode`.
/// Occupancy-ordered blending builds occupancy_maps<128, 4> from the fragments (Sintorn &
/// Assarsson's configuration) and weights each fragment by exp(-optical depth in front of its
/// slice) = (1 - alpha)^o, then rescales the hair's colour so that its alpha is the exact
/// 1 - prod(1 - alpha_i) (the paper's correction; we scale by Lambda / alpha_sum, which is what
/// makes the alpha right, where the paper's text reads alpha_sum / Lambda).
inline void blend_fragments(image& base, const camera_fragments& f, transparency mode, const execution& exec = {}) {
    const std::size_t pixels = std::size_t(f.width) * std::size_t(f.height);
    occupancy_maps<128, 4> order;
    if (mode == transparency::occupancy) {
        // The maps are square: the image sits in the corner of a square of its longer side. Both
        // are row by row, so the fragments keep their order.
        const int side = std::max(f.width, f.height);
        if (side > 4096) throw argument_error("occupancy-ordered blending builds maps of the image's longer side squared: at most 4096 pixels");
        std::vector<std::uint64_t> offsets(std::size_t(side) * std::size_t(side) + 1, 0);
        for (std::size_t y = 0; y < std::size_t(f.height); ++y)
            for (std::size_t x = 0; x < std::size_t(f.width); ++x)
                offsets[y * std::size_t(side) + x + 1] = f.offsets[y * std::size_t(f.width) + x + 1] - f.offsets[y * std::size_t(f.width) + x];
        for (std::size_t i = 1; i < offsets.size(); ++i) offsets[i] += offsets[i - 1];
        std::vector<fragment> plain(f.fragments.size());
        for (std::size_t i = 0; i < plain.size(); ++i) plain[i] = {f.fragments[i].depth, f.fragments[i].alpha};
        const fragment_buffer buffer(side, std::move(offsets), std::move(plain));
        // The maps are read by pixel and depth only: any light of that resolution will do.
        order.build(buffer, light_space::fit(light_spec::directional({0, 0, -1}), aabb{glm::vec3(0.0f), glm::vec3(1.0f)}, side), exec);
    }
    parallel_for(pixels, exec, [&](std::size_t i) {
        const auto frags = f.pixel(i);
        if (frags.empty()) return;
        glm::vec3& out = base.pixels[i];
        switch (mode) {
        case transparency::none: {
            const auto nearest = std::min_element(frags.begin(), frags.end(), [](const auto& a, const auto& b) { return a.depth < b.depth; });
            out = nearest->colour;
            break;
        }
        case transparency::exact: {
            // Nearest first; of equal depths (where a strand's segments meet) the first drawn is in
            // front, as under GL's depth peeling, and as transparency::none picks.
            thread_local std::vector<camera_fragment> sorted; // reused: no allocation per pixel
            sorted.assign(frags.begin(), frags.end());
            std::stable_sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return a.depth < b.depth; });
            for (auto g = sorted.rbegin(); g != sorted.rend(); ++g) out = g->alpha * g->colour + (1.0f - g->alpha) * out; // back to front
            break;
        }
        case transparency::weighted: { // Bavoil & Myers: the average colour and alpha, n times
            glm::vec3 colour(0.0f);
            float alpha = 0.0f;
            for (const auto& g : frags) colour += g.alpha * g.colour, alpha += g.alpha;
            if (!(alpha > 0.0f)) break; // nothing visible
            const float mean_alpha = alpha / float(frags.size());
            const float behind = std::pow(1.0f - mean_alpha, float(frags.size()));
            out = colour / alpha * (1.0f - behind) + behind * out;
            break;
        }
        case transparency::occupancy: {
            const int x = int(i % std::size_t(f.width)), y = int(i / std::size_t(f.width));
            const auto& t = order.texel(x, y);
            glm::vec3 colour(0.0f);
            float alpha_sum = 0.0f, total = 0.0f;
            for (const auto& g : frags) {
                const float in_front = occupancy_bitcount<4>::optical_depth_in_front<depth_range<128>, float_accumulation>(order.placement(), t.placement,
                                                                                                                      t.data, g.depth);
                const float weight = std::exp(-in_front) * g.alpha; // (1 - alpha)^o alpha
                colour += weight * g.colour;
                alpha_sum += weight;
                total += -std::log1p(-g.alpha);
            }
            if (!(alpha_sum > 0.0f)) break;
            const float lambda = 1.0f - std::exp(-total); // 1 - prod(1 - alpha_i)
            out = colour * (lambda / alpha_sum) + (1.0f - lambda) * out;
            break;
        }
        }
    }, 1024);
}

/// Renders the scene with transparent hair of `opacity` per strand: the opaque mesh as render_cpu
/// draws it, then every hair fragment blended by `mode`; transparency::none is render_cpu itself
/// (opaque hair, anti-aliased by coverage).
inline image render_transparent(const scene& sc, const camera& cam, std::span<const lit_light> lights, transparency mode, float opacity,
                                const render_options& options = {}) {
    if (mode == transparency::none) return render_cpu(sc, cam, lights, options);
    if (!(opacity > 0.0f && opacity <= 1.0f)) throw argument_error("hair opacity must be in (0, 1]");
    render_options opaque = options;
    opaque.draw_hair = false;
    image out = render_cpu(sc, cam, lights, opaque);
    const auto surface = detail::rasterise_mesh(sc.mesh, cam, options.exec);
    const auto colours = shade_hair_points(sc, cam, lights, options.exec);
    blend_fragments(out, collect_camera_fragments(sc.hair, colours, cam, surface.inv_w, opacity, options), mode, options.exec);
    return out;
}

} // namespace hairshadow
