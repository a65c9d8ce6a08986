#pragma once
/// @file
/// The methods and accumulations the run-time registries, the spec parser, the command line, the fuzz
/// dictionary and the tests know: one line each. A new method adds its family here (its header
/// declares everything else: methods/method_family.hpp).

#include <hairshadow/accumulation/emulated_8bit.hpp>
#include <hairshadow/accumulation/float_accumulation.hpp>
#include <hairshadow/methods/adaptive_volumetric_shadow_maps.hpp>
#include <hairshadow/methods/exact_reference.hpp>
#include <hairshadow/methods/fourier_opacity_maps.hpp>
#include <hairshadow/methods/hair_count_deep_shadows.hpp>
#include <hairshadow/methods/method_family.hpp>
#include <hairshadow/methods/moment_shadow_maps.hpp>
#include <hairshadow/methods/published.hpp>

namespace hairshadow {

/// Every registered method family, in the order the command line lists them (the papers' years, then
/// the engines', then ours, then the exact reference).
using registered_families =
    family_list<opacity_shadow_maps_family, density_clustering_family, deep_opacity_maps_family, occupancy_maps_family, fourier_opacity_maps_family,
                moment_shadow_maps_family, adaptive_volumetric_shadow_maps_family, approximate_deep_shadow_maps_family, hair_count_deep_shadows_family,
                deep_occupancy_maps_family, range_opacity_maps_family, exact_reference_family>;

/// Every registered accumulation; the first is the default.
using registered_accumulations = accumulation_list<float_accumulation, emulated_8bit>;

} // namespace hairshadow
