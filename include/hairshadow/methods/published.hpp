#pragma once
/// @file
/// The published methods as compositions of policies, each in a header of its own with its
/// registration, and the hybrids that no paper describes.

#include <hairshadow/methods/approximate_deep_shadow_maps.hpp>
#include <hairshadow/methods/deep_opacity_maps.hpp>
#include <hairshadow/methods/density_clustering.hpp>
#include <hairshadow/methods/hybrids.hpp>
#include <hairshadow/methods/occupancy_maps.hpp>
#include <hairshadow/methods/opacity_shadow_maps.hpp>
