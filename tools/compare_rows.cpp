// The measurements of `hairshadow compare` (compare_rows.hpp).
#include "compare_rows.hpp"

#include <hairshadow/io/deep_exr.hpp>

#include <limits>
#include <optional>
#include <sstream>

namespace cli {

using namespace hairshadow;

namespace {
/// What compare's image error looks at: the hair alone, lit by the map's light, from the figure's
/// default camera (azimuth 25, elevation 10), 300 pixels square, supersampled 2x2; the exact map's
/// render and the pixels the hair covers (the exact map built here, or read from a file).
class image_probe {
public:
    template <class Exact>
    image_probe(const lit_model& s, const light_spec& light, const Exact& exact, const execution& exec) {
        sc_.hair = s.model;
        sc_.lights.push_back({light, glm::vec3(1.1f)});
        cam_ = camera::framing(sc_.hair.bounds(), 25.0f, 10.0f, 300, 300, 1.15f);
        options_.exec = exec;
        options_.supersample = 2;
        coverage_.resize(std::size_t(cam_.width) * std::size_t(cam_.height));
        exact_ = render(exact, coverage_);
    }
    image_difference operator()(const any_shadow_map& map) const { return image_error(render(map), exact_, coverage_); }

private:
    template <class Map>
    image render(const Map& map, std::span<float> coverage = {}) const {
        const std::vector<lit_light> lights{{sc_.lights[0], query_of(map, options_.exec), {}}};
        return render_cpu(sc_, cam_, lights, options_, coverage);
    }
    hairshadow::scene sc_;
    camera cam_;
    render_options options_;
    image exact_;
    std::vector<float> coverage_;
};

std::string compare_preamble(const map_options& o, const lit_model& s) {
    std::ostringstream preamble;
    preamble << "Model `" << o.model << "`, light `" << o.light << "`, " << o.resolution << "x" << o.resolution << ", " << s.model.point_count()
             << " points, " << s.fragments.size() << " fragments (rasterised in " << std::lround(s.raster_ms) << " ms), " << o.exec().resolved()
             << " threads. ";
    if (s.gl) preamble << "Methods built on " << s.gl->description() << " and queried by their GLSL look-up; the reference on the CPU. ";
    else preamble << "Build times are CPU rebuilds straight from the model (rasterise and build, tile by tile), the second of two builds. ";
    preamble << "Errors are |T - T_exact| at the model's points; the curve error is the mean over texels of the mean |T - T_exact| "
                "from each texel's first fragment to its last (64 depths a texel); the image error is the mean and 99th percentile "
                "over hair pixels of |sRGB difference| from the exact map's render (the hair alone, 300x300, 2x2 supersampled, "
                "azimuth 25, elevation 10).";
    return preamble.str();
}

/// Each method against `exact` (any map answering transmittance queries: the exact map built here or
/// a deep OpenEXR file's); the curve error only where `same_texels` (the fragments' light is exact's).
template <class Exact>
std::vector<compare_row> measure(const map_options& o, const std::vector<method_spec>& specs, lit_model& s, const Exact& exact, bool same_texels) {
    const auto exec = o.exec();
    std::vector<float> reference(s.model.point_count());
    exact.transmittance(s.model.points, reference, o.query(), exec);
    const image_probe images(s, parse_light(o.light), exact, exec);
    std::vector<compare_row> rows;
    for (const auto& spec : specs) {
        const auto result = evaluate(spec, s, o, s.model.points, true);
        compare_row row{spec.text, result.layers, result.bytes, result.build_ms};
        set_errors(row, result.transmittance, reference);
        row.curve = same_texels ? transmittance_curve_error(*result.maps, exact, s.fragments, 64, exec) : std::numeric_limits<double>::quiet_NaN();
        const auto seen = images(*result.maps);
        row.image_mean = seen.mean;
        row.image_p99 = seen.p99;
        rows.push_back(row);
    }
    return rows;
}

} // namespace

comparison compare_methods(const map_options& o, const std::vector<method_spec>& specs, const scene_source& source, const std::string& reference_file) {
    std::optional<deep_exr_map> file; // read first: a bad file fails before any work
    if (!reference_file.empty()) file.emplace(read_deep_exr(reference_file));
    auto s = prepare_scene(o, true, source); // the exact reference is built on the CPU for either back end
    comparison c;
    if (!file) {
        const auto exact = make_shadow_map(parse_method("dsm"));
        exact->build(s.fragments, s.light, o.exec());
        c.rows = measure(o, specs, s, *exact, true);
        c.preamble = compare_preamble(o, s);
        return c;
    }
    const bool same = file->light().parts() == s.light.parts();
    c.rows = measure(o, specs, s, *file, same);
    c.preamble = compare_preamble(o, s) + " The reference is `" + reference_file + "` (a deep OpenEXR image of `" +
                 (file->method().empty() ? std::string("an unnamed method") : file->method()) + "`, " + std::to_string(file->resolution()) + "x" +
                 std::to_string(file->resolution()) + "), read instead of built, its own light mapping the points" +
                 (same ? "." : "; its light differs from the one fitted here, so the curve error, which needs the same texels, is not measured (nan).");
    return c;
}

} // namespace cli
