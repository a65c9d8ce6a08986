#pragma once
/// @file
/// The GL twin of any shadow_method, chosen by its reconstruction: gl::maps<Method> is
/// interpolated_maps_gl for interpolation and the reconstructions built on it (hair_count), occupancy_maps_gl for occupancy_bitcount,
/// projected_maps_gl for those built on depth_projection (fourier_series, power_moments), node_maps_gl for adaptive_nodes and fibre_density_maps_gl for fibre_density. A new reconstruction adds its class and one line here.

#include <hairshadow/gl/maps/fibre_density_maps.hpp>
#include <hairshadow/gl/maps/interpolated_maps.hpp>
#include <hairshadow/gl/maps/node_maps.hpp>
#include <hairshadow/gl/maps/occupancy_maps.hpp>
#include <hairshadow/gl/maps/projected_maps.hpp>

#include <type_traits>

namespace hairshadow::gl {

namespace detail {
template <class Method, class Reconstruction = typename Method::reconstruction_type>
struct maps_of {
    static_assert(sizeof(Method) == 0, "this method's reconstruction has no GL twin");
};
template <class Method, class Reconstruction>
    requires std::is_base_of_v<interpolation, Reconstruction> // interpolation, and those built on it (hair_count)
struct maps_of<Method, Reconstruction> {
    using type = interpolated_maps_gl<Method>;
};
template <class Method, int B>
struct maps_of<Method, occupancy_bitcount<B>> {
    using type = occupancy_maps_gl<Method>;
};
template <class Method, class Reconstruction>
    requires std::is_base_of_v<hairshadow::detail::depth_projection<Reconstruction, Reconstruction::sums>, Reconstruction> // fourier_series, power_moments
struct maps_of<Method, Reconstruction> {
    using type = projected_maps_gl<Method>;
};
template <class Method, int N>
struct maps_of<Method, adaptive_nodes<N>> {
    using type = node_maps_gl<Method>;
};
template <class Method, fibre_density_source Source>
struct maps_of<Method, fibre_density<Source>> {
    using type = fibre_density_maps_gl<Method>;
};
} // namespace detail

template <class Method>
using maps = typename detail::maps_of<Method>::type;

namespace detail {
/// The GL maps of `method`, made with its parameters where they take them (a fibre density).
template <class Method>
maps<Method> maps_of_method(const Method& method) {
    if constexpr (std::is_constructible_v<maps<Method>, const Method&>) return maps<Method>(method);
    else return maps<Method>();
}
} // namespace detail

} // namespace hairshadow::gl
