#pragma once
/// @file
/// The published methods as compositions of policies, and the hybrids that no paper describes.

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/shadow_method.hpp>
#include <hairshadow/placement/clustered.hpp>
#include <hairshadow/placement/depth_range.hpp>
#include <hairshadow/placement/per_pixel_depth.hpp>
#include <hairshadow/placement/planar_slices.hpp>
#include <hairshadow/reconstruction/fibre_density.hpp>
#include <hairshadow/reconstruction/interpolation.hpp>
#include <hairshadow/reconstruction/occupancy_bitcount.hpp>

namespace hairshadow {

/// Opacity shadow maps (Kim & Neumann 2001): N planar slices, float sums, linear interpolation.
/// @tparam N number of maps
/// @tparam Spacing uniform_spacing (Fig. 3a) or gamma_spacing (Fig. 3c)
template <int N, class Spacing = uniform_spacing, class Accumulation = float_accumulation>
using opacity_shadow_maps = shadow_method<planar_slices<N, Spacing>, Accumulation, interpolation>;

/// Deep opacity maps (Yuksel & Keyser 2008): K layers from each texel's first fragment.
template <int K, class Accumulation = float_accumulation>
using deep_opacity_maps = shadow_method<per_pixel_depth<K>, Accumulation, interpolation>;

/// Density clustering (Mertens et al. 2004): K k-means clusters per texel as histogram bins.
template <int K, class Accumulation = float_accumulation>
using density_clustering = shadow_method<clustered<K>, Accumulation, interpolation>;

/// Occupancy maps (Sintorn & Assarsson 2009): S one-bit slices in each texel's depth range, B slabs.
template <int S, int B, class Accumulation = float_accumulation>
using occupancy_maps = shadow_method<depth_range<S>, Accumulation, occupancy_bitcount<B>>;

/// Approximate deep shadow maps, as AMD TressFX ships them: one depth map (deep opacity maps' z0, no
/// layers) and a constant density of fibres behind the first (fibre_density_parameters).
using approximate_deep_shadow_maps = shadow_method<per_pixel_depth<1>, float_accumulation, fibre_density<fibre_density_source::fixed>>;

/// Approximate deep shadow maps with each texel's density measured: occupancy maps' depth range and
/// the texel's summed optical depth (one opacity layer), spread over its fragment count.
using measured_density_shadow_maps = shadow_method<depth_range<1>, float_accumulation, fibre_density<fibre_density_source::measured>>;

// Hybrids: compositions no paper describes.

/// Deep opacity maps accumulated the way an RGBA8 target would (Kim & Neumann's 8-bit buffers).
template <int K>
using deep_opacity_maps_8bit = deep_opacity_maps<K, emulated_8bit>;

/// Occupancy bits and slabs in slices that start at each texel's first fragment and span a fixed
/// depth (deep opacity maps' layers) instead of the texel's own range.
template <int S, int B>
using deep_occupancy_maps = shadow_method<per_pixel_depth<S, layer_sizes::uniform, beyond_last_layer::extend>, float_accumulation,
                                          occupancy_bitcount<B>>;

/// Opacity maps interpolated in each texel's own depth range (occupancy maps' placement).
template <int N>
using range_opacity_maps = shadow_method<depth_range<N>, float_accumulation, interpolation>;

} // namespace hairshadow
