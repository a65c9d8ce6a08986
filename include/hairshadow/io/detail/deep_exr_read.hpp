#pragma once
/// @file
/// Reading a deep scanline OpenEXR image for io/deep_exr.hpp, every check before any allocation the
/// file cannot justify: the header (deep scanline, square data window from 0, channels Z and A), the
/// light's attributes, and sample counts no larger than the file's bytes can hold. Needs OpenEXR.

#include <hairshadow/io/detail/deep_exr_header.hpp>
#include <hairshadow/io/detail/deep_exr_samples.hpp>
#include <hairshadow/io/detail/exr_header_bytes.hpp>
#include <hairshadow/io/detail/exr_stream.hpp>

#include <ImfChannelList.h>
#include <ImfDeepFrameBuffer.h>
#include <ImfDeepScanLineInputFile.h>
#include <ImfPartType.h>
#include <ImfTestFile.h>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace hairshadow::detail {

/// Everything read from a deep image: the light, the samples texel by texel (row y = scanline y), the
/// method spec and tolerance where the file has them.
struct deep_exr_contents {
    light_space light;
    std::vector<std::uint64_t> offsets; ///< texel t's samples are [offsets[t], offsets[t + 1])
    std::vector<deep_sample> samples;
    std::string method;
    std::optional<float> tolerance;
};

/// Most bytes of sample data one byte of the file can stand for under a compression: 1 uncompressed,
/// 64 for RLE (a run of 128 bytes in 2), and deflate's bound of about 1032 to 1 for ZIP(S).
inline double expansion_bound(Imf::Compression c) noexcept {
    if (c == Imf::NO_COMPRESSION) return 1.0;
    if (c == Imf::RLE_COMPRESSION) return 64.0;
    return 1100.0;
}

/// The side of a valid data window: square, from (0, 0), within HAIRSHADOW_MAX_RESOLUTION.
inline int checked_resolution(const Imf::Header& h, const std::string& file) {
    const auto& w = h.dataWindow();
    if (w.min.x != 0 || w.min.y != 0) throw io_error(file, "the data window does not start at (0, 0)");
    const long long width = (long long)w.max.x + 1, height = (long long)w.max.y + 1;
    if (width != height) throw io_error(file, "the data window is " + std::to_string(width) + "x" + std::to_string(height) + ", not square");
    if (width < 1 || width > HAIRSHADOW_MAX_RESOLUTION) throw io_error(file, "the data window's side is outside 1.." + std::to_string(HAIRSHADOW_MAX_RESOLUTION));
    return int(width);
}

/// Bytes one sample takes in the file: every channel's, whichever we read.
inline std::uint64_t bytes_per_sample(const Imf::ChannelList& channels) {
    std::uint64_t bytes = 0;
    for (auto c = channels.begin(); c != channels.end(); ++c) bytes += c.channel().type == Imf::HALF ? 2 : 4;
    return bytes;
}

/// Checks the header and returns the light; `size` is the file's bytes, against which the texel count is bounded.
inline light_space check_deep_header(const Imf::Header& h, const std::string& file, std::size_t size) {
    if (h.type() != Imf::DEEPSCANLINE) throw io_error(file, "not a deep scanline image (type '" + h.type() + "')");
    const int res = checked_resolution(h, file);
    for (const char* name : {"Z", "A"})
        if (!h.channels().findChannel(name)) throw io_error(file, std::string("no ") + name + " channel; a deep shadow map needs Z and A");
    if (double(res) * double(res) * 4.0 > expansion_bound(h.compression()) * double(size) + 65536.0)
        throw io_error(file, "a " + std::to_string(res) + "x" + std::to_string(res) + " sample count table cannot fit in " + std::to_string(size) + " bytes");
    light_space light = read_light_attributes(h, file);
    if (light.resolution() != res)
        throw io_error(file, "the light's resolution " + std::to_string(light.resolution()) + " differs from the data window's " + std::to_string(res));
    return light;
}

/// The frame buffer of one read: the sample counts and, per texel, where each channel's samples go.
/// OpenEXR keeps pointers to these arrays from setFrameBuffer to readPixels, so they live here.
struct deep_exr_frame {
    std::vector<unsigned int> counts;
    std::vector<char*> z, z_back, alpha;
    Imf::DeepFrameBuffer fb;
    bool has_back = false;

    deep_exr_frame(const Imf::Header& h, int res) {
        const std::size_t texels = std::size_t(res) * std::size_t(res), xs = sizeof(char*), ys = sizeof(char*) * std::size_t(res);
        counts.resize(texels), z.resize(texels), z_back.resize(texels), alpha.resize(texels);
        has_back = h.channels().findChannel("ZBack") != nullptr;
        fb.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()), sizeof(unsigned int), sizeof(unsigned int) * std::size_t(res)));
        fb.insert("Z", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(z.data()), xs, ys, sizeof(deep_sample)));
        fb.insert("A", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(alpha.data()), xs, ys, sizeof(deep_sample)));
        if (has_back) fb.insert("ZBack", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(z_back.data()), xs, ys, sizeof(deep_sample)));
    }
};

/// Reads the sample counts, refuses counts the file's `size` bytes cannot hold, then reads every
/// sample as FLOAT (OpenEXR converts HALF and UINT channels); ZBack = Z where there is no ZBack.
inline void read_samples(Imf::DeepScanLineInputFile& in, int res, const std::string& file, std::size_t size, deep_exr_contents& c) {
    deep_exr_frame f(in.header(), res);
    in.setFrameBuffer(f.fb);
    in.readPixelSampleCounts(0, res - 1);
    const std::size_t texels = f.counts.size();
    c.offsets.assign(texels + 1, 0);
    for (std::size_t t = 0; t < texels; ++t) c.offsets[t + 1] = c.offsets[t] + f.counts[t];
    const double claimed = double(c.offsets.back()) * double(bytes_per_sample(in.header().channels()));
    if (claimed > expansion_bound(in.header().compression()) * double(size))
        throw io_error(file, "claims " + std::to_string(c.offsets.back()) + " samples, more than its " + std::to_string(size) + " bytes can hold");
    c.samples.resize(c.offsets.back());
    for (std::size_t t = 0; t < texels; ++t) {
        if (f.counts[t] == 0) continue; // no samples: OpenEXR writes nothing there
        auto* s = c.samples.data() + c.offsets[t];
        f.z[t] = reinterpret_cast<char*>(&s->z), f.z_back[t] = reinterpret_cast<char*>(&s->z_back), f.alpha[t] = reinterpret_cast<char*>(&s->alpha);
    }
    in.readPixels(0, res - 1);
    if (!f.has_back)
        for (auto& s : c.samples) s.z_back = s.z;
}

/// Refuses non-finite depths and alphas, and alphas outside [0, 1] (OpenEXR's rule for alpha); a ZBack
/// in front of Z makes a point sample.
inline void check_samples(std::vector<deep_sample>& samples, const std::string& file) {
    for (auto& s : samples) {
        if (!std::isfinite(s.z) || !std::isfinite(s.z_back)) throw io_error(file, "a sample's Z or ZBack is not finite");
        if (!(s.alpha >= 0.0f && s.alpha <= 1.0f)) throw io_error(file, "a sample's A is not finite or is outside [0, 1]");
        if (s.z_back < s.z) s.z_back = s.z;
    }
}

/// Scanlines in one chunk of a deep scanline image, by its compression: 1 for NONE, RLE and ZIPS
/// (all that OpenEXR 3.1 accepts for deep data), 16 for ZIP (which later OpenEXR may write; 3.1
/// refuses it when it reads the header, so that case is untested here); anything else is refused.
inline int deep_lines_per_chunk(Imf::Compression c, const std::string& file) {
    if (c == Imf::NO_COMPRESSION || c == Imf::RLE_COMPRESSION || c == Imf::ZIPS_COMPRESSION) return 1;
    if (c == Imf::ZIP_COMPRESSION) return 16;
    throw io_error(file, "a deep image compressed other than NONE, RLE, ZIPS or ZIP");
}

/// The header and the chunk offset table, read and checked before DeepScanLineInputFile allocates
/// anything from them.
inline light_space checked_header(exr_memory_stream& stream, std::span<const unsigned char> bytes, const std::string& file) {
    exr_header_walk walk(bytes, file);
    int version = walk.run(); // readFrom takes it by reference
    stream.seekg(8);
    Imf::Header h;
    h.readFrom(stream, version);
    // OpenEXR reads the offset table where readFrom stops, which is not the walk's end where an
    // attribute reads other than its declared size (a floatvector of 6 bytes, 3.1's idmanifest).
    if (stream.tellg() != walk.end()) throw io_error(file, "a header attribute does not read as the size it declares");
    light_space light = check_deep_header(h, file, bytes.size());
    const std::uint64_t lines = std::uint64_t(deep_lines_per_chunk(h.compression(), file));
    check_deep_chunks(bytes, walk.end(), (std::uint64_t(light.resolution()) + lines - 1) / lines, expansion_bound(h.compression()),
                      h.lineOrder() == Imf::INCREASING_Y, file);
    return light;
}

/// Reads a deep image from its bytes; `file` names it in errors.
inline deep_exr_contents read_deep_contents(std::span<const unsigned char> bytes, const std::string& file) {
    return exr_call(file, [&] {
        exr_memory_stream stream(bytes, file);
        bool tiled = false, deep = false, multipart = false;
        if (!Imf::isOpenExrFile(stream, tiled, deep, multipart)) throw io_error(file, "not an OpenEXR file");
        if (!deep) throw io_error(file, "a flat OpenEXR image, not a deep one");
        if (tiled) throw io_error(file, "a deep tiled image; only deep scanline images are read");
        light_space light = checked_header(stream, bytes, file);
        stream.seekg(0);
        Imf::DeepScanLineInputFile in(stream);
        if (checked_resolution(in.header(), file) != light.resolution()) throw io_error(file, "the header read twice differs"); // the same bytes: never
        deep_exr_contents c{light, {}, {}, optional_string(in.header(), exr_attribute::method), {}};
        if (const auto* t = in.header().findTypedAttribute<Imf::FloatAttribute>(exr_attribute::tolerance)) c.tolerance = t->value();
        const int res = c.light.resolution();
        read_samples(in, res, file, bytes.size(), c);
        check_samples(c.samples, file);
        return c;
    });
}

} // namespace hairshadow::detail
