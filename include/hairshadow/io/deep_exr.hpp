#pragma once
/// @file
/// Deep shadow maps as deep scanline OpenEXR images, and back (issue 45). Needs OpenEXR (link
/// OpenEXR::OpenEXR); nothing else in the library includes this header.
///
/// The image is resolution x resolution pixels, pixel (x, y) = texel (x, y) and scanline y = row y of
/// the map. OpenEXR's y grows downwards, the map's upwards (row 0 is the light's -y side), so the image
/// shows the light's view upside down. Channels: Z (FLOAT) is the light's linear depth in [0, 1]
/// (distance along the light's axis = near + Z (far - near), with near and far in the attributes),
/// A (FLOAT) the sample's alpha, and ZBack (FLOAT) where a sample is a volume. Compositing the samples
/// front to back (OpenEXR's "Interpreting OpenEXR Deep Pixels", the alpha channel alone) gives the
/// map's transmittance: T(depth) = product over samples in front of depth of (1 - A), a volume sample
/// counting 1 - (1 - A)^fraction for the fraction of it in front.
///
///   - The exact map: one point sample per fragment depth (fragments at one depth merged), Z = the
///     fragment's depth, A = 1 - exp(-(omega_i - omega_{i-1})) from the cumulative optical depths, in
///     double; compositing gives exp(-omega) within 1e-6 at every depth.
///   - A compressed map: the falling envelope of its piecewise-linear functions (their running
///     minimum, clamped at 0: a compressed function may rise a little, an alpha must lie in [0, 1];
///     detail::falling_envelope), a vertical step as a point sample, a sloped piece as volume samples,
///     cut geometrically in T until each is within tolerance / 16 of the line (detail::volume_gap_bound
///     proves the bound; about sqrt(8 / tolerance) samples a piece at most, 31 at 0.01; a budget
///     below 2^-24, a float's rounding, is held to 2^-24); so within the map's tolerance (and 1/16
///     of it) of the exact map, and within 1/16 of the tolerance of the envelope.
///   - Any other map (write_sampled_deep_exr: any method of the registry): its optical depth omega
///     sampled at N + 1 uniform depths i / N over [0, 1], one volume sample an interval, alpha taking
///     the composited transmittance to exp(-omega) at the interval's back (detail::sampled_texel_samples).
///     Compositing gives the method's exp(-omega) within 1e-6 at every sample depth and optical depth
///     linear in depth in between: exact wherever the method's optical depth is linear between the
///     sample depths, and otherwise the chord. Where omega falls with depth (occupancy's estimates,
///     series and moments ringing, a compressed map within its tolerance), the file keeps the
///     largest value so far: alphas are never negative.
///
/// All are marked tidy (deepImageState = TIDY): samples sorted by Z (then ZBack), no two overlapping;
/// a compressed map's point samples lie only at the ends of its volume samples, which OpenEXR's
/// definition of non-overlapping allows. Attributes hairshadow/... hold the light (light_space::parts,
/// bit for bit), the method spec, the tolerance where compressed, the library version and what Z means.

#include <hairshadow/core/map_queries.hpp>
#include <hairshadow/io/detail/binary_file.hpp>
#include <hairshadow/io/detail/deep_exr_read.hpp>
#include <hairshadow/io/detail/deep_exr_sampled.hpp>

#include <ImfChannelList.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineOutputFile.h>
#include <ImfHeader.h>
#include <ImfStandardAttributes.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace hairshadow {

/// A deep OpenEXR image read back (read_deep_exr): its light, its samples texel by texel, sorted by Z,
/// and the optical depth in front of any depth, so that it answers transmittance queries as the maps do.
class deep_exr_map : public map_queries<deep_exr_map> {
public:
    explicit deep_exr_map(detail::deep_exr_contents c) : c_(std::move(c)) {
        const std::size_t texels = c_.offsets.size() - 1;
        before_.resize(c_.samples.size());
        tidy_.assign(texels, 1);
        for (std::size_t t = 0; t < texels; ++t) index_texel(t);
    }

    const light_space& light() const noexcept { return c_.light; }
    int resolution() const noexcept { return c_.light.resolution(); }
    /// The method spec the file names (hairshadow/method), or "" where it names none.
    const std::string& method() const noexcept { return c_.method; }
    /// The compressed map's tolerance (hairshadow/tolerance), where the file has one.
    std::optional<float> tolerance() const noexcept { return c_.tolerance; }
    std::size_t sample_count() const noexcept { return c_.samples.size(); }

    /// Texel (x, y)'s samples, sorted by Z, then ZBack.
    std::span<const deep_sample> samples(int x, int y) const noexcept {
        const std::size_t t = texel(x, y);
        return {c_.samples.data() + c_.offsets[t], std::size_t(c_.offsets[t + 1] - c_.offsets[t])};
    }

    /// Optical depth of the samples in front of `depth` in texel (x, y): point samples strictly in front
    /// (the exact map's rule), volume samples by the fraction in front, -ln(1 - A) each.
    float optical_depth(int x, int y, float depth) const noexcept {
        const auto s = samples(x, y);
        const std::size_t n = std::size_t(std::partition_point(s.begin(), s.end(), [&](const deep_sample& a) { return a.z < depth; }) - s.begin());
        if (n == 0) return 0.0f;
        const std::size_t t = texel(x, y);
        if (tidy_[t]) return float(before_[c_.offsets[t] + n - 1] + detail::optical_depth_in_front(s[n - 1], depth));
        double sum = 0.0; // overlapping samples: each one's part in front
        for (std::size_t i = 0; i < n; ++i) sum += detail::optical_depth_in_front(s[i], depth);
        return float(sum);
    }
    using map_queries<deep_exr_map>::transmittance;

private:
    std::size_t texel(int x, int y) const noexcept { return std::size_t(y) * std::size_t(resolution()) + std::size_t(x); }
    /// Sorts texel t's samples, sums their optical depths and notes whether any overlaps the next.
    void index_texel(std::size_t t) {
        const auto first = c_.samples.begin() + std::ptrdiff_t(c_.offsets[t]), last = c_.samples.begin() + std::ptrdiff_t(c_.offsets[t + 1]);
        std::stable_sort(first, last, [](const deep_sample& a, const deep_sample& b) { return a.z < b.z || (a.z == b.z && a.z_back < b.z_back); });
        double sum = 0.0;
        for (auto s = first; s != last; ++s) {
            before_[std::size_t(s - c_.samples.begin())] = sum;
            sum += detail::sample_optical_depth(*s);
            if (s + 1 != last && s->z_back > (s + 1)->z) tidy_[t] = 0;
        }
    }

    detail::deep_exr_contents c_;
    std::vector<double> before_;      ///< optical depth of the texel's samples in front of each (by index)
    std::vector<unsigned char> tidy_; ///< 1 where no sample of the texel reaches past the next one's Z
};

/// Reads a deep scanline OpenEXR image from its bytes; `name` names it in errors. Throws io_error for
/// anything malformed: not OpenEXR, not deep scanline, no Z or A, a data window not square from (0, 0),
/// sample counts the bytes cannot hold, a non-finite Z or A, an A above 1, a missing hairshadow light
/// attribute (named), or whatever OpenEXR itself refuses.
inline deep_exr_map parse_deep_exr(std::span<const unsigned char> bytes, const std::string& name) {
    return deep_exr_map(detail::read_deep_contents(bytes, name));
}
/// Reads a deep scanline OpenEXR image (see parse_deep_exr).
inline deep_exr_map read_deep_exr(const std::string& path) { return parse_deep_exr(detail::read_file_bytes(path), path); }

namespace detail {
/// Writes a tidy deep scanline image row by row, from `texel_samples(x, y, out)` (appending texel
/// (x, y)'s samples to out): one row's samples are held at a time, whatever the map's size. Where
/// anything fails after the file is opened, the partial file is removed.
template <class TexelSamples>
void write_deep_texels(const std::string& path, const light_space& light, bool volumes, const std::string& method, std::optional<float> tolerance,
                       TexelSamples&& texel_samples) {
    const int res = light.resolution();
    bool opened = false;
    try {
        exr_call(path, [&] {
            Imf::Header h(res, res);
            h.setType(Imf::DEEPSCANLINE);
            h.compression() = Imf::ZIPS_COMPRESSION; // one scanline a chunk
            h.channels().insert("Z", Imf::Channel(Imf::FLOAT));
            h.channels().insert("A", Imf::Channel(Imf::FLOAT));
            if (volumes) h.channels().insert("ZBack", Imf::Channel(Imf::FLOAT));
            Imf::addDeepImageState(h, Imf::DIS_TIDY);
            write_hairshadow_attributes(h, light, method, tolerance);
            Imf::DeepScanLineOutputFile out(path.c_str(), h);
            opened = true;
            const std::size_t row = std::size_t(res);
            std::vector<unsigned int> counts(row);
            std::vector<std::size_t> first(row + 1);
            std::vector<char*> z(row), z_back(row), alpha(row);
            std::vector<deep_sample> samples;
            for (int y = 0; y < res; ++y) {
                samples.clear();
                for (int x = 0; x < res; ++x) {
                    first[std::size_t(x)] = samples.size();
                    texel_samples(x, y, samples);
                }
                first[row] = samples.size();
                for (std::size_t x = 0; x < row; ++x) {
                    counts[x] = unsigned(first[x + 1] - first[x]);
                    z[x] = z_back[x] = alpha[x] = nullptr; // no samples: OpenEXR reads nothing there
                    if (counts[x] == 0) continue;
                    auto* s = samples.data() + first[x];
                    z[x] = reinterpret_cast<char*>(&s->z), z_back[x] = reinterpret_cast<char*>(&s->z_back), alpha[x] = reinterpret_cast<char*>(&s->alpha);
                }
                // A y stride of 0: every row reads the same one-row arrays, refilled before its write. This
                // needs one scanline a chunk (ZIPS): OpenEXR takes a chunk's counts when the chunk is full.
                Imf::DeepFrameBuffer fb;
                fb.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()), sizeof(unsigned int), 0));
                fb.insert("Z", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), sizeof(char*), 0, sizeof(deep_sample)));
                fb.insert("A", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(alpha.data()), sizeof(char*), 0, sizeof(deep_sample)));
                if (volumes) fb.insert("ZBack", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(z_back.data()), sizeof(char*), 0, sizeof(deep_sample)));
                out.setFrameBuffer(fb);
                out.writePixels(1);
            }
        });
    } catch (...) {
        std::error_code ignored;
        if (opened) std::filesystem::remove(path, ignored);
        throw;
    }
}
} // namespace detail

/// Writes the exact deep shadow map as point samples (see the file's comment). Throws io_error.
template <exact_deep_map Map>
void write_deep_exr(const std::string& path, const Map& map, const std::string& method = "dsm") {
    detail::write_deep_texels(path, map.light(), false, method, std::nullopt, [&](int x, int y, std::vector<deep_sample>& out) {
        detail::exact_texel_samples(map.depths(x, y), map.optical_depths(x, y), out);
    });
}

/// Writes a compressed deep shadow map as point and volume samples within tolerance / 16 of its
/// functions (see the file's comment). Throws io_error.
template <compressed_deep_map Map>
void write_deep_exr(const std::string& path, const Map& map, std::string method = "") {
    if (method.empty()) {
        std::ostringstream spec;
        spec << "dsm:" << map.tolerance();
        method = spec.str();
    }
    const double budget = double(map.tolerance()) / 16.0;
    detail::write_deep_texels(path, map.light(), true, method, map.tolerance(), [&](int x, int y, std::vector<deep_sample>& out) {
        detail::compressed_texel_samples(map.vertices(x, y), budget, out);
    });
}

/// Writes any map's optical depth, sampled at `samples` + 1 uniform depths over [0, 1] in every texel,
/// as volume samples (see the file's comment; detail::sampled_texel_samples). `method` names the spec
/// in the attributes; by default the map's spec() where it has one. Throws argument_error for samples
/// outside 1..65536, io_error where the file cannot be written.
template <optical_depth_map Map>
void write_sampled_deep_exr(const std::string& path, const Map& map, int samples = 64, const std::string& method = "") {
    if (samples < 1 || samples > 65536) throw argument_error("the depth samples of a deep export must be 1 to 65536, not " + std::to_string(samples));
    const std::vector<float> depths = detail::uniform_sample_depths(samples);
    detail::write_deep_texels(path, map.light(), true, detail::method_text(map, method), std::nullopt, [&](int x, int y, std::vector<deep_sample>& out) {
        detail::sampled_texel_samples(depths, [&](float depth) { return map.optical_depth(x, y, depth); }, out);
    });
}

} // namespace hairshadow
