#pragma once
/// @file
/// hairshadow: self-shadowing and transparency of hair and other thin semi-transparent geometry.
/// The CPU umbrella header: models and their readers, lights, the rasteriser, the exact reference and
/// every method's policies and compositions (the run-time registry is <hairshadow/methods/registry.hpp>),
/// and the CPU renderer: Kajiya-Kay hair, opaque meshes with depth shadow maps, cameras.
/// It needs only GLM; every file reader is the project's own. PNG output (`<hairshadow/io/png.hpp>`)
/// needs stb's header and is included separately.

#include <hairshadow/config.hpp>

#include <hairshadow/core/bounds.hpp>
#include <hairshadow/core/error.hpp>
#include <hairshadow/core/hair_model.hpp>
#include <hairshadow/core/light.hpp>
#include <hairshadow/core/parallel.hpp>
#include <hairshadow/core/parse.hpp>
#include <hairshadow/core/random.hpp>
#include <hairshadow/core/triangle_mesh.hpp>

#include <hairshadow/io/data_format.hpp>
#include <hairshadow/io/hair_format.hpp>
#include <hairshadow/io/load.hpp>
#include <hairshadow/io/obj_format.hpp>
#include <hairshadow/io/points_file.hpp>
#include <hairshadow/io/procedural_spec.hpp>
#include <hairshadow/io/tfx_format.hpp>

#include <hairshadow/procedural/generators.hpp>
#include <hairshadow/procedural/motion.hpp>

#include <hairshadow/raster/fragment.hpp>
#include <hairshadow/raster/line_rule.hpp>
#include <hairshadow/raster/rasterizer.hpp>

#include <hairshadow/core/map_queries.hpp>

#include <hairshadow/methods/adaptive_volumetric_shadow_maps.hpp>
#include <hairshadow/methods/fourier_opacity_maps.hpp>
#include <hairshadow/methods/hair_count_deep_shadows.hpp>
#include <hairshadow/methods/moment_shadow_maps.hpp>
#include <hairshadow/methods/published.hpp>
#include <hairshadow/methods/spec.hpp>

#include <hairshadow/reference/compressed_deep_shadow_map.hpp>
#include <hairshadow/reference/deep_shadow_map.hpp>
#include <hairshadow/reference/point_error.hpp>
#include <hairshadow/reference/temporal_error.hpp>
#include <hairshadow/reference/transmittance_curve_error.hpp>

#include <hairshadow/shading/camera.hpp>
#include <hairshadow/shading/cpu_renderer.hpp>
#include <hairshadow/shading/depth_shadow_map.hpp>
#include <hairshadow/shading/image.hpp>
#include <hairshadow/shading/image_error.hpp>
#include <hairshadow/shading/kajiya_kay.hpp>
#include <hairshadow/shading/scene.hpp>
#include <hairshadow/shading/transparency.hpp>
