#pragma once
/// @file
/// The GL twin of any shadow_method: gl::maps<Method> is interpolated_maps_gl for the interpolation
/// reconstruction and occupancy_maps_gl for occupancy_bitcount.

#include <hairshadow/gl/interpolated_maps.hpp>
#include <hairshadow/gl/occupancy_maps.hpp>

#include <type_traits>

namespace hairshadow::gl {

template <class Method>
using maps = std::conditional_t<std::is_same_v<typename Method::reconstruction_type, interpolation>, interpolated_maps_gl<Method>,
                                occupancy_maps_gl<Method>>;

} // namespace hairshadow::gl
