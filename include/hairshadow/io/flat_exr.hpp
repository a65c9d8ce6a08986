#pragma once
/// @file
/// A method's stored maps as one flat, tiled OpenEXR image (issue 45): one FLOAT channel a stored map,
/// for looking at a method's maps in any image viewer or compositor. Needs OpenEXR (link
/// OpenEXR::OpenEXR); nothing else in the library includes this header. There is no reader: the
/// maps alone do not answer queries without the method's look-up; the deep export
/// (io/deep_exr.hpp, write_sampled_deep_exr) is the one to read back.
///
/// The image is resolution x resolution pixels, pixel (x, y) = texel (x, y), scanline y = row y of the
/// map (as the deep files: the light's view upside down). Tiles of 64 x 64 texels (the whole map where
/// it is smaller), one level, ZIP compressed. Channel `mapKK.optical_depth` (flat_exr_channel_name;
/// KK zero-padded to two digits, or more where a method stores 100 maps or more, so that OpenEXR's
/// alphabetical order is k's order) holds stored_optical_depth(x, y, k) bit for bit: what map k is
/// depends on the family (docs/texel_layouts.md: the optical depth through layer k for osm, dom,
/// rosm and ue; bin k's own for dc; through slab k for occ; the k-th stored sum for the series and
/// moments methods; node k's for avsm; the texel's total for adsm's measured density). Attributes: the deep files' hairshadow/... light, method and
/// version attributes (io/detail/deep_exr_header.hpp), hairshadow/storedMaps (int) and hairshadow/maps
/// (a sentence naming the channels).

#include <hairshadow/io/detail/deep_exr_header.hpp>
#include <hairshadow/io/detail/deep_exr_sampled.hpp>
#include <hairshadow/io/detail/exr_stream.hpp>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIntAttribute.h>
#include <ImfStringAttribute.h>
#include <ImfTileDescription.h>
#include <ImfTiledOutputFile.h>

#include <algorithm>
#include <concepts>
#include <string>
#include <vector>

namespace hairshadow {

/// What write_flat_exr needs of a map (any_shadow_map, methods/registry.hpp, or a shadow_method):
/// io/ ranks below methods/, so the writer takes any type of that shape.
template <class Map>
concept stored_maps_map = requires(const Map& m) {
    { m.light() } -> std::convertible_to<const light_space&>;
    { m.stored_maps() } -> std::convertible_to<int>;
    { m.stored_optical_depth(0, 0, 0) } -> std::convertible_to<float>;
};

/// The channel holding stored map k of `maps`: "map07.optical_depth", the index zero-padded to two
/// digits or to as many as maps - 1 has.
inline std::string flat_exr_channel_name(int k, int maps) {
    const int width = std::max<int>(2, int(std::to_string(std::max(maps - 1, 0)).size()));
    std::string index = std::to_string(k);
    if (int(index.size()) < width) index.insert(0, std::size_t(width - int(index.size())), '0');
    return "map" + index + ".optical_depth";
}

namespace detail {
/// The tiled file's header: the channels, the tiles and the hairshadow attributes.
inline Imf::Header flat_exr_header(const light_space& light, int maps, int tile, const std::string& method) {
    const int res = light.resolution();
    Imf::Header h(res, res);
    h.compression() = Imf::ZIP_COMPRESSION;
    h.setTileDescription(Imf::TileDescription(unsigned(tile), unsigned(tile), Imf::ONE_LEVEL));
    for (int k = 0; k < maps; ++k) h.channels().insert(flat_exr_channel_name(k, maps), Imf::Channel(Imf::FLOAT));
    write_hairshadow_attributes(h, light, method, std::nullopt);
    h.insert("hairshadow/storedMaps", Imf::IntAttribute(maps));
    h.insert("hairshadow/maps", Imf::StringAttribute("channel mapK.optical_depth holds the optical depth the method stores in map K of each texel "
                                                     "(stored_optical_depth(x, y, K)); what map K is depends on the method family: "
                                                     "see docs/texel_layouts.md"));
    return h;
}
} // namespace detail

/// Writes the map's stored maps as a flat tiled OpenEXR image (see the file's comment), a row of tiles
/// at a time. A map that stores none (the exact map dsm, or a fixed fibre density) is refused with
/// argument_error: write_deep_exr or write_sampled_deep_exr exports those. Throws io_error where the
/// file cannot be written. `method` names the spec in the attributes; by default the map's spec().
template <stored_maps_map Map>
void write_flat_exr(const std::string& path, const Map& map, const std::string& method = "") {
    const int maps = map.stored_maps();
    const std::string spec = detail::method_text(map, method);
    if (maps <= 0)
        throw argument_error("'" + spec + "' stores no maps per texel (the exact map, or a fixed fibre density): export it as a deep image "
                             "(write_deep_exr or write_sampled_deep_exr; `hairshadow export` without --flat)");
    const light_space& light = map.light();
    const int res = light.resolution(), tile = std::min(res, 64);
    detail::exr_call(path, [&] {
        Imf::TiledOutputFile out(path.c_str(), detail::flat_exr_header(light, maps, tile, spec));
        const std::size_t row = std::size_t(res) * std::size_t(tile); // one row of tiles, one channel
        std::vector<float> values(row * std::size_t(maps));
        for (int ty = 0; ty < out.numYTiles(); ++ty) {
            const int y0 = ty * tile, y1 = std::min(res, y0 + tile);
            for (int k = 0; k < maps; ++k)
                for (int y = y0; y < y1; ++y)
                    for (int x = 0; x < res; ++x)
                        values[std::size_t(k) * row + std::size_t(y - y0) * std::size_t(res) + std::size_t(x)] = map.stored_optical_depth(x, y, k);
            Imf::FrameBuffer fb; // addressed from (0, y0): the slices hold this row of tiles only
            for (int k = 0; k < maps; ++k)
                fb.insert(flat_exr_channel_name(k, maps), Imf::Slice::Make(Imf::FLOAT, values.data() + std::size_t(k) * row, Imath::V2i(0, y0), res,
                                                                           tile, sizeof(float), sizeof(float) * std::size_t(res)));
            out.setFrameBuffer(fb);
            out.writeTiles(0, out.numXTiles() - 1, ty, ty);
        }
    });
}

} // namespace hairshadow
