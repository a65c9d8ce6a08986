// hairshadow.ShadowMap's object (map_handle.hpp).
#include <glad/gl.h>

#include "map_handle.hpp"

#include <hairshadow/gl/context/context.hpp>
#include <hairshadow/gl/maps/registry.hpp>
#include <hairshadow/gl/passes/hair_mesh.hpp>

#include <mutex>

namespace hspy {

using namespace hairshadow;

namespace {
raster_options raster_of(std::optional<float> alpha, float wide, unsigned threads) {
    raster_options o;
    o.exec = {threads};
    o.fixed_alpha = alpha;
    o.wide_line_width = wide;
    o.check();
    return o;
}

gl::build_path path_of(const std::string& path) {
    return path.empty() ? gl::default_build_path() : path == "compute" ? gl::build_path::compute : gl::build_path::raster;
}
} // namespace

shadow_map_handle::shadow_map_handle(const std::string& spec, const std::string& backend, const std::string& context, const std::string& gl_path)
    : spec_(parse_method_spec(spec)) {
    if (backend == "gl") {
        if (names_exact_reference(spec_)) throw argument_error("the exact reference (" + spec_.text + ") is CPU-only; use backend='cpu'");
        if (!gl_path.empty() && gl_path != "compute" && gl_path != "raster")
            throw argument_error("unknown GL build path '" + gl_path + "'; valid: compute, raster");
        gl_context(context);
        context_kind_ = gl_context_kind();
        gl::require_version(4, 3, "the GL back end"); // both paths: before pointing from one to the other
        if (path_of(gl_path) == gl::build_path::compute)
            gl::require_compute_path(gl_path.empty() ? "the default gl_path ('compute')" : "gl_path='compute'", "use gl_path='raster'");
        gl_path_ = gl_path;
    } else if (backend != "cpu") {
        throw argument_error("unknown backend '" + backend + "'; valid: cpu, gl");
    } else if (!gl_path.empty()) {
        throw argument_error("gl_path chooses how backend='gl' builds; add backend='gl'");
    } else {
        map_ = make_shadow_map(spec_);
    }
}

shadow_map_handle::~shadow_map_handle() {
    if (!gl_ && !mesh_) return;
    try {
        gl_context(context_kind_); // GL objects are deleted on their own context
    } catch (...) {
        retire_gl_objects(std::move(gl_), std::move(mesh_)); // on another thread: deleted at GL's next use on its own
    }
}

template <class F>
auto shadow_map_handle::reading(F&& f) {
    if (on_gl()) { // GL state and the read-back change under any call
        std::unique_lock lock(mutex_);
        gl_context(context_kind_);
        return f();
    }
    std::shared_lock lock(mutex_);
    return f();
}

void shadow_map_handle::build(const hair_model& model, const light_spec& light, int resolution, std::optional<float> alpha, float wide, unsigned threads) {
    check_resolution(resolution);
    if (on_gl() && wide > 0.0f) throw argument_error("wide lines need backend='cpu': core GL draws lines one pixel wide");
    const auto options = raster_of(alpha, wide, threads);
    const auto space = light_space::fit(light, model.bounds(), resolution);
    std::unique_lock lock(mutex_);
    built_ = false; // until this build is through
    if (on_gl()) {
        gl_context(context_kind_);
        if (!gl_) {
            gl_ = gl::make_gl_shadow_map(spec_);
            gl_->set_build_path(path_of(*gl_path_));
        }
        mesh_ = std::make_unique<gl::hair_mesh>(model);
        gl_->build(*mesh_, space, options);
        read_back_ = false;
    } else {
        map_->build(model, space, options);
    }
    built_ = true;
}

void shadow_map_handle::require_built() const {
    if (!built_) throw argument_error("the " + spec_.text + " map is not built: call build(model, light, resolution) first");
}

void shadow_map_handle::check_texel(int x, int y) const {
    const int res = on_gl() ? gl_->light().resolution() : map_->light().resolution();
    if (x < 0 || y < 0 || x >= res || y >= res)
        throw argument_error("texel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the " + std::to_string(res) + "x" +
                             std::to_string(res) + " map");
}

const any_shadow_map& shadow_map_handle::cpu_maps() {
    require_built();
    if (on_gl() && !read_back_) {
        map_ = gl_->to_cpu();
        read_back_ = true;
    }
    return *map_;
}

void shadow_map_handle::transmittance(std::span<const glm::vec3> points, std::span<float> out, const query_options& options, const execution& exec) {
    if (on_gl() && (options.box_filter || options.jitter))
        throw argument_error("box_filter and jitter are CPU queries; the GLSL look-up has neither: use backend='cpu'");
    options.check();
    reading([&] {
        require_built();
        if (on_gl()) {
            const auto t = gl_->transmittance(points, options.depth_bias);
            std::copy(t.begin(), t.end(), out.begin());
        } else {
            map_->transmittance(points, out, options, exec);
        }
    });
}

void shadow_map_handle::along_ray(int x, int y, std::span<const float> depths, std::span<float> out, bool optical) {
    reading([&] {
        const auto& map = cpu_maps();
        check_texel(x, y);
        for (std::size_t i = 0; i < depths.size(); ++i) out[i] = optical ? map.optical_depth(x, y, depths[i]) : map.transmittance(x, y, depths[i]);
    });
}

shadow_map_handle::stored_values shadow_map_handle::stored_maps() {
    return reading([&] {
        const auto& map = cpu_maps();
        const int res = map.light().resolution(), k = map.stored_maps();
        std::vector<float> out(std::size_t(res) * std::size_t(res) * std::size_t(k));
        std::size_t i = 0;
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x)
                for (int j = 0; j < k; ++j) out[i++] = map.stored_optical_depth(x, y, j);
        return stored_values{std::move(out), res, k};
    });
}

std::pair<std::vector<float>, std::vector<float>> shadow_map_handle::fragments(int x, int y) {
    return reading([&] {
        auto& map = const_cast<any_shadow_map&>(cpu_maps()); // method_if is not const; nothing is written
        check_texel(x, y);
        std::pair<std::vector<float>, std::vector<float>> out;
        if (const auto* exact = map.method_if<deep_shadow_map>(); exact && !map.method_if<compressed_deep_shadow_map>()) {
            const auto d = exact->depths(x, y), o = exact->optical_depths(x, y);
            out.first.assign(d.begin(), d.end());
            out.second.assign(o.begin(), o.end());
        } else if (const auto* compressed = map.method_if<compressed_deep_shadow_map>()) {
            for (const auto& v : compressed->vertices(x, y)) out.first.push_back(v.depth), out.second.push_back(v.transmittance);
        } else {
            throw argument_error("fragments() belongs to the exact map ('dsm' or 'dsm:EPS'), not " + spec_.text);
        }
        return out;
    });
}

map_summary shadow_map_handle::summary() {
    return reading([&] {
        require_built();
        if (on_gl()) return map_summary{gl_->light(), gl_->memory_bytes(), make_shadow_map(spec_)->layer_count(), 0}; // the CPU twin's, unbuilt
        return map_summary{map_->light(), map_->memory_bytes(), map_->layer_count(), map_->fragment_count()};
    });
}

std::uint64_t shadow_map_handle::maps_hash() {
    return reading([&] { return cpu_maps().maps_hash(); });
}

std::string shadow_map_handle::map_layout() const {
    const std::string& f = spec_.family;
    if (f == "osm" || f == "dc" || f == "dom" || f == "rosm" || f == "ue") return "[y, x, k]: optical depth from the light through the end of layer k";
    if (f == "occ" || f == "docc") return "[y, x, k]: optical depth from the light through the end of slab k";
    if (f == "fom") return "[y, x, k]: the k-th summed term of the Fourier series (the optical depth's a0, then the cosine and sine coefficients)";
    if (f == "msm") return "[y, x, k]: the k-th summed power moment (optical depth weighted by depth^k)";
    if (f == "avsm") return "[y, x, k]: optical depth in front of node k";
    if (f == "adsm") return spec_.fields.empty() || spec_.fields[0] != "auto" ? "[y, x, k]: nothing (K = 0): a fixed fibre density needs only the depth map"
                                                                              : "[y, x, 0]: the texel's summed optical depth";
    if (f == "dsm") return "[y, x, k]: nothing (K = 0): the exact map's fragments are fragments(x, y)";
    return "[y, x, k]: the method's stored_optical_depth(x, y, k)";
}

} // namespace hspy
