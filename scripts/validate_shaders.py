#!/usr/bin/env python3
"""Validates the GLSL snippets under shaders/ with glslangValidator (Debian's glslang-tools): each
composition below is what a program would concatenate (version line, defines, snippets, a main), so
every snippet is compiled in every configuration it is used in. Each is also compiled to SPIR-V for
OpenGL (-G), whose capabilities say what arithmetic it needs: double precision (Float64) and 64-bit
integers (Int64) run slowly or not at all on most GPUs, and GL 4.3 core has no 64-bit integers, so no
composition may need either. A probe that does need them checks first that the check can see them.

    scripts/validate_shaders.py [--validator PATH]   exit 1 on the first failure, printing the log
"""
import pathlib
import re
import struct
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHADERS = ROOT / "shaders"
VERSION = "#version 430 core\n"
ALPHA = "#define HS_ALPHA_MAX 0.999\n"

# A fragment-stage main that exercises a placement's and a reconstruction's functions.
PLANAR_MAIN = """
float hs_through_layer(int k) { return float(k); }
#include reconstruction/interpolation
out vec4 hs_out;
void main() { hs_out = vec4(hs_interpolate(hs_locate(hs_fragment_optical_depth())), float(hs_assign(0.5)), hs_encode(1.0), hs_decode(1.0)); }
"""
DEPTH_RANGE_MAIN = """
#include reconstruction/occupancy_bitcount
out vec4 hs_out;
void main() {
    uint bits[HS_WORDS];
    for (int i = 0; i < HS_WORDS; ++i) bits[i] = uint(i);
    float slabs[HS_SLABS];
    for (int i = 0; i < HS_SLABS; ++i) slabs[i] = float(i);
    vec2 range = vec2(0.1, 0.9);
    hs_out = vec4(hs_occupancy_optical_depth(hs_locate(range, hs_fragment_optical_depth()), bits, slabs), float(hs_assign(range, 0.5)), 0.0, 1.0);
}
"""
PER_PIXEL_MAIN = """
float hs_through_layer(int k) { return float(k); }
#include reconstruction/interpolation
out vec4 hs_out;
void main() { hs_out = vec4(hs_interpolate(hs_locate(0.1, 1.0, hs_fragment_optical_depth())), float(hs_assign(0.1, 1.0, 0.5)), 0.0, 1.0); }
"""

COMPOSITIONS = {
    "vertex": ("vert", "", ["raster/vertex"], "void hs_unused() {}\n"),
}
def float_bits(values):
    """A GLSL uint[] of float32 bits, as the placements' glsl_float_bits writes their tables (the shader's
    syntax is what is checked here, not the values)."""
    return "uint[](" + ", ".join("0x%08xu" % struct.unpack("<I", struct.pack("<f", v))[0] for v in values) + ")"


# The tables the library's placements define (planar_slices::fractions, per_pixel_depth::relative_boundaries);
# the compositions without them check the shaders' own fall-back.
SLICE_FRACTIONS = "#define HS_SLICE_FRACTION_BITS " + float_bits([i / 16 for i in range(17)]) + "\n"
RELATIVE_BOUNDARIES = "#define HS_RELATIVE_BOUNDARY_BITS " + float_bits([k * (k + 1) / 12 for k in range(4)]) + "\n"
for accumulation in ("float", "emulated_8bit"):
    for defines, tag in (("", "uniform"), ("#define HS_GAMMA_SPACING\n" + SLICE_FRACTIONS, "gamma")):
        COMPOSITIONS[f"planar_{tag}_{accumulation}"] = ("frag", "#define HS_LAYERS 16\n" + defines,
            ["raster/coverage", f"accumulation/{accumulation}", "placement/common", "placement/planar_slices"], PLANAR_MAIN)
    for defines, tag in ((RELATIVE_BOUNDARIES, "linear_clamp"), ("#define HS_UNIFORM_SIZES\n#define HS_BEYOND_EXTEND\n", "uniform_extend"),
                         ("#define HS_BEYOND_IGNORE\n", "linear_ignore")):
        COMPOSITIONS[f"per_pixel_{tag}_{accumulation}"] = ("frag", "#define HS_LAYERS 3\n" + defines,
            ["raster/coverage", f"accumulation/{accumulation}", "placement/common", "placement/per_pixel_depth"], PER_PIXEL_MAIN)
    for layers, slabs in ((128, 4), (32, 1), (256, 8)):
        COMPOSITIONS[f"depth_range_{layers}_{slabs}_{accumulation}"] = ("frag", f"#define HS_LAYERS {layers}\n#define HS_SLABS {slabs}\n",
            ["raster/coverage", f"accumulation/{accumulation}", "placement/common", "placement/depth_range"], DEPTH_RANGE_MAIN)


LOOKUP_MAIN = """
layout(location = 0) in vec3 hs_point;
layout(std430, binding = 1) buffer hs_results_buffer { float hs_results[]; };
void main() { hs_results[gl_VertexID] = hs_transmittance(hs_point); gl_Position = vec4(0.0); }
"""
COMPOSITIONS["capture"] = ("frag", "", ["raster/coverage", "passes/capture"], "")
COMPOSITIONS["depth_range_pass"] = ("frag", "", ["raster/coverage", "passes/depth_range"], "")
COMPOSITIONS["depth_extent_tiles"] = ("comp", "#define HS_EXTENT_TILES\n", ["passes/depth_extent"], "")
COMPOSITIONS["depth_extent"] = ("comp", "", ["passes/depth_extent"], "")
for layers, slabs in ((128, 4), (32, 1), (256, 8)):
    targets = f"#define HS_LAYERS {layers}\n#define HS_SLABS {slabs}\n#define HS_BIT_TARGETS {(layers + 127) // 128}\n" \
              f"#define HS_SLAB_TARGETS {(slabs + 3) // 4}\n"
    occupancy = ["raster/coverage", "accumulation/float", "placement/common", "placement/depth_range", "texel_state/depth_range"]
    COMPOSITIONS[f"occupancy_bits_{layers}"] = ("frag", targets, occupancy + ["passes/occupancy_bits"], "")
    COMPOSITIONS[f"occupancy_slabs_{layers}_{slabs}"] = ("frag", targets, occupancy + ["passes/occupancy_slabs"], "")
    COMPOSITIONS[f"lookup_occupancy_{layers}_{slabs}"] = ("vert", targets, ["accumulation/emulated_8bit", "placement/common",
                                                                          "placement/per_pixel_depth", "texel_state/per_pixel_depth",
                                                                          "reconstruction/occupancy_bitcount", "lookup/light", "lookup/occupancy_texels",
                                                                          "lookup/occupancy"], LOOKUP_MAIN)


for placement, defines in (("planar_slices", "#define HS_LAYERS 64\n#define HS_GAMMA_SPACING\n#define HS_CUMULATIVE\n"),
                          ("per_pixel_depth", "#define HS_LAYERS 3\n#define HS_BEYOND_EXTEND\n#define HS_CUMULATIVE\n"),
                          ("depth_range", "#define HS_LAYERS 16\n"),
                          ("clustered", "#define HS_LAYERS 4\n#define HS_STATE_TARGETS 1\n"),
                          ("clustered", "#define HS_LAYERS 6\n#define HS_STATE_TARGETS 2\n")):
    for accumulation in ("float", "emulated_8bit"):
        base = ["accumulation/" + accumulation, "placement/common", "placement/" + placement, "texel_state/" + placement]
        tag = placement + defines.split()[2]
        COMPOSITIONS[f"layers_{tag}_{accumulation}"] = ("frag", defines + "#define HS_LAYER_TARGETS 8\n",
                                                              ["raster/coverage"] + base + ["passes/layers"], "")
        COMPOSITIONS[f"lookup_layers_{tag}_{accumulation}"] = ("vert", defines, base + ["lookup/layers", "reconstruction/interpolation", "lookup/light",
                                                                                             "lookup/interpolation"], LOOKUP_MAIN)

# Unreal Engine's hair-count deep shadows: power_layers (no texel_state file: z0 is the range's nearest)
# in the layers pass and the compute build, and hair_count's look-up after interpolation's.
POWER = "#define HS_LAYERS 4\n#define HS_CUMULATIVE\n"
for accumulation, eight in (("float", ""), ("emulated_8bit", "#define HS_EIGHT_BIT\n")):
    base = ["accumulation/" + accumulation, "placement/common", "placement/power_layers"]
    COMPOSITIONS[f"layers_power_{accumulation}"] = ("frag", POWER + "#define HS_LAYER_TARGETS 8\n", ["raster/coverage"] + base + ["passes/layers"], "")
    COMPOSITIONS[f"lookup_hair_count_{accumulation}"] = ("vert", POWER + "#define HS_OWN_OPTICAL_DEPTH\n", base + [
        "lookup/layers", "reconstruction/interpolation", "reconstruction/hair_count", "lookup/light", "lookup/interpolation"], LOOKUP_MAIN)
    COMPOSITIONS[f"compute_layers_power_{accumulation}"] = (
        "comp", "#define HS_SUBPIXEL_BITS 8\n" + POWER + eight + "#define HS_LAYER_GROUP 4\n#define HS_SUM_SLOTS 4\n#define HS_LAYERS_FORMAT " +
        ("rgba8" if eight else "rgba32f") + "\n", ["compute/common", "accumulation/" + accumulation, "compute/tile_sums"] + base[1:] + ["compute/layers"], "")

# Approximate deep shadow maps (gl/maps/fibre_density_maps.hpp): the measured density's pass, and both look-ups.
COMPOSITIONS["fibre_count"] = ("frag", "", ["raster/coverage", "passes/fibre_count"], "")
for defines, tag in (("", "fixed"), ("#define HS_MEASURED_DENSITY\n", "measured")):
    COMPOSITIONS[f"lookup_fibre_density_{tag}"] = ("vert", defines, ["placement/common", "lookup/light", "reconstruction/fibre_density"],
                                                  LOOKUP_MAIN)

# The projected methods (gl/maps/projected_maps.hpp): the raster pass, the compute build and the look-up,
# each over its reconstruction's snippet.
PROJECTIONS = {"fourier_series": ("#define HS_HARMONICS 3\n", "#define HS_HARMONICS 7\n"), "power_moments": ("#define HS_MOMENTS 4\n", "#define HS_MOMENTS 6\n", "#define HS_MOMENTS 8\n")}
for reconstruction, variants in PROJECTIONS.items():
    for defines in variants:
        for accumulation, eight in (("float", ""), ("emulated_8bit", "#define HS_EIGHT_BIT\n")):
            if eight and reconstruction != "fourier_series":
                continue  # 8-bit steps: Fourier opacity maps' variant
            tag = reconstruction + "_" + defines.split()[2] + "_" + accumulation
            common = defines + f"#define HS_TERMS_PER_OPTICAL_DEPTH {2 if reconstruction == 'fourier_series' else 1}.0\n"
            projection = ["accumulation/" + accumulation, "placement/common", "reconstruction/" + reconstruction, "reconstruction/depth_projection"]
            COMPOSITIONS[f"projection_pass_{tag}"] = ("frag", common + eight, ["raster/coverage"] + projection + ["passes/projection"], "")
            COMPOSITIONS[f"lookup_projection_{tag}"] = ("vert", common + eight, projection + ["lookup/light", "lookup/projection"], LOOKUP_MAIN)
            COMPOSITIONS[f"compute_projection_{tag}"] = (
                "comp", "#define HS_SUBPIXEL_BITS 8\n" + common + eight + "#define HS_SUM_SLOTS 8\n#define HS_SUMS_FORMAT " + ("rgba8" if eight else "rgba32f") + "\n",
                ["compute/common"] + projection[:1] + ["compute/tile_sums"] + projection[1:] + ["compute/projection"], "")

# Adaptive volumetric shadow maps (gl/maps/node_maps.hpp): the raster and compute list passes, the resolve
# and the look-up, at 4 and 16 nodes.
COMPOSITIONS["list_raster"] = ("frag", "", ["raster/coverage", "passes/fragment_lists", "passes/list_raster"], "")
COMPOSITIONS["compute_fragment_lists"] = ("comp", "#define HS_SUBPIXEL_BITS 8\n", ["compute/common", "passes/fragment_lists", "compute/fragment_lists"], "")
for nodes in (4, 16):
    defines = f"#define HS_NODES {nodes}\n"
    COMPOSITIONS[f"resolve_nodes_{nodes}"] = ("comp", defines, ["passes/fragment_lists", "reconstruction/adaptive_nodes", "compute/resolve_nodes"], "")
    COMPOSITIONS[f"lookup_nodes_{nodes}"] = ("vert", defines, ["placement/common", "reconstruction/adaptive_nodes", "lookup/light", "lookup/nodes"],
                                             LOOKUP_MAIN)

# Density clustering's state passes (cluster_state_pass.hpp).
# The renderer's unshadowed light (scene_renderer.hpp): the light's frustum and no hair.
COMPOSITIONS["lookup_light_alone"] = ("vert", "uniform sampler2D hs_range_map;\n", ["arithmetic/exact_division", "lookup/light"],
                                      "float hs_transmittance(vec3 world_pos) { return 1.0; }\n" + LOOKUP_MAIN)
COMPOSITIONS["fullscreen_vertex"] = ("vert", "", ["passes/fullscreen_vertex"], "")
for clusters in (4, 6):
    defines = f"#define HS_LAYERS {clusters}\n#define HS_STATE_TARGETS {(clusters + 3) // 4}\n"
    clustering = ["placement/common", "placement/clustered", "passes/cluster_common"]
    for name in ("means", "variance"):
        COMPOSITIONS[f"cluster_{name}_{clusters}"] = ("frag", defines, ["raster/coverage"] + clustering + [f"passes/cluster_{name}"], "")
    COMPOSITIONS[f"cluster_resolve_{clusters}"] = ("frag", defines, clustering + ["passes/cluster_resolve"], "")

# The compute build (gl/passes/compute_raster.hpp and each maps' build_compute): the segment passes, then each
# method's tile pass over its placement's snippets, float and 8-bit, as compute_pieces composes them.
COMPUTE = "#define HS_SUBPIXEL_BITS 8\n"
COMPOSITIONS["compute_prepare"] = ("comp", COMPUTE, ["compute/common", "compute/prepare"], "")
COMPOSITIONS["compute_scan"] = ("comp", COMPUTE, ["compute/common", "compute/scan"], "")
COMPOSITIONS["compute_scatter"] = ("comp", COMPUTE, ["compute/common", "compute/scatter"], "")
COMPOSITIONS["compute_range"] = ("comp", COMPUTE + "#define HS_DEPTH_ONLY\n", ["compute/common", "compute/range"], "")
COMPOSITIONS["compute_fibre_count"] = ("comp", COMPUTE + "#define HS_SUM_SLOTS 1\n", ["compute/common", "accumulation/float", "compute/tile_sums",
                                                                                 "compute/fibre_count"], "")
for accumulation, eight in (("float", ""), ("emulated_8bit", "#define HS_EIGHT_BIT\n")):
    form = "rgba8" if eight else "rgba32f"
    for placement, defines in (("planar_slices", "#define HS_LAYERS 16\n#define HS_GAMMA_SPACING\n#define HS_CUMULATIVE\n"),
                               ("per_pixel_depth", "#define HS_LAYERS 3\n#define HS_CUMULATIVE\n"),
                               ("depth_range", "#define HS_LAYERS 16\n#define HS_CUMULATIVE\n")):
        COMPOSITIONS[f"compute_layers_{placement}_{accumulation}"] = (
            "comp", COMPUTE + defines + eight + f"#define HS_LAYER_GROUP 12\n#define HS_SUM_SLOTS 12\n#define HS_LAYERS_FORMAT {form}\n",
            ["compute/common", "accumulation/" + accumulation, "compute/tile_sums", "placement/common", "placement/" + placement,
             "texel_state/" + placement, "compute/layers"], "")
    for clusters, rows in ((4, 16), (8, 8)):
        COMPOSITIONS[f"compute_clusters_{clusters}_{accumulation}"] = (
            "comp", COMPUTE + f"#define HS_LAYERS {clusters}\n" + eight +
            f"#define HS_FIXED_SUMS\n#define HS_SUM_SLOTS {2 * clusters}\n#define HS_STRIP_ROWS {rows}\n#define HS_SUM_TEXELS {16 * rows}\n"
            f"#define HS_LAYERS_FORMAT {form}\n",
            ["compute/common", "accumulation/" + accumulation, "compute/tile_sums", "placement/common", "placement/clustered",
             "arithmetic/exact_square_root", "compute/clusters"], "")
    for layers, slabs in ((128, 4), (256, 8)):
        COMPOSITIONS[f"compute_occupancy_{layers}_{slabs}_{accumulation}"] = (
            "comp", COMPUTE + eight + f"#define HS_LAYERS {layers}\n#define HS_SLABS {slabs}\n#define HS_BIT_TARGETS {(layers + 127) // 128}\n"
            f"#define HS_SLAB_TARGETS {(slabs + 3) // 4}\n#define HS_SUM_SLOTS {slabs}\n#define HS_SLABS_FORMAT {form}\n",
            ["compute/common", "accumulation/" + accumulation, "compute/tile_sums", "placement/common", "placement/depth_range",
             "texel_state/depth_range", "compute/occupancy"], "")

# Each tile pass also in its form for runs whose segments each have one alpha (compute_pass_program).
for name in [n for n in COMPOSITIONS if n.startswith("compute_") and n not in ("compute_prepare", "compute_scan", "compute_scatter", "compute_range")]:
    stage, defines, snippets, main_text = COMPOSITIONS[name]
    COMPOSITIONS[name + "_one_alpha"] = (stage, "#define HS_ONE_ALPHA\n" + defines, snippets, main_text)

# The shaded renderer (gl/render/scene_renderer.hpp), over one method's look-up.
DOM_LOOKUP = ["accumulation/float", "placement/common", "placement/per_pixel_depth", "texel_state/per_pixel_depth", "lookup/layers",
              "reconstruction/interpolation", "lookup/light", "lookup/interpolation"]
DOM_DEFINES = "#define HS_LAYERS 3\n#define HS_CUMULATIVE\n"
COMPOSITIONS["render_hair_vertex"] = ("vert", DOM_DEFINES, DOM_LOOKUP + ["render/light", "render/hair_shading", "render/hair_vertex"], "")
COMPOSITIONS["render_hair_colour"] = ("vert", DOM_DEFINES, DOM_LOOKUP + ["render/light", "render/hair_shading", "render/hair_colour"], "")
COMPOSITIONS["render_mesh_inv_w"] = ("frag", "", ["render/mesh_inv_w"], "")
COMPOSITIONS["render_hair_fragment"] = ("frag", "", ["render/hair_fragment"], "")
COMPOSITIONS["render_mesh_vertex"] = ("vert", "", ["render/mesh_vertex"], "")
COMPOSITIONS["render_mesh_fragment"] = ("frag", DOM_DEFINES, DOM_LOOKUP + ["render/light", "render/mesh_fragment"], "")
COMPOSITIONS["render_mesh_depth"] = ("frag", "", ["render/mesh_depth"], "")
COMPOSITIONS["render_present"] = ("frag", "", ["render/present"], "")

# Transparent hair (gl/render/transparent_hair.hpp): the camera's fragments through the occupancy passes,
# and each mode's blend and resolve.
CAMERA_OCCUPANCY = "#define HS_LAYERS 128\n#define HS_SLABS 4\n#define HS_BIT_TARGETS 1\n#define HS_SLAB_TARGETS 1\n"
CAMERA_SNIPPETS = ["accumulation/float", "placement/common", "placement/depth_range", "texel_state/depth_range", "transparency/camera_fragment"]
COMPOSITIONS["transparency_line_vertex"] = ("vert", "", ["transparency/line_vertex"], "")
COMPOSITIONS["transparency_line_geometry"] = ("geom", "", ["transparency/line_geometry"], "")
for name in ("depth_range", "occupancy_bits", "occupancy_slabs"):
    COMPOSITIONS[f"transparency_{name}"] = ("frag", CAMERA_OCCUPANCY, CAMERA_SNIPPETS + [f"passes/{name}"], "")
COMPOSITIONS["transparency_occupancy_order"] = ("frag", CAMERA_OCCUPANCY, CAMERA_SNIPPETS + [
    "reconstruction/occupancy_bitcount", "lookup/occupancy_texels", "transparency/occupancy_order"], "")
COMPOSITIONS["transparency_weighted_sum"] = ("frag", "", ["transparency/camera_fragment", "transparency/weighted_sum"], "")
COMPOSITIONS["transparency_peel"] = ("frag", "", ["transparency/camera_fragment", "transparency/peel"], "")
for mode in ("OCCUPANCY_ORDER", "WEIGHTED_AVERAGE", "EXACT"):
    COMPOSITIONS[f"transparency_resolve_{mode.lower()}"] = ("frag", f"#define HS_{mode}\n", ["transparency/resolve"], "")

# The exact division (arithmetic/exact_division) goes before compute/common and placement/common, where the
# library puts it (compute_pieces and every composition of placement/common), once: the snippet's guard
# lets the library compose it twice; the two-word integers (arithmetic/fixed_point) go after it in the
# compute programs (compute_pieces).
for name, (stage, defines, snippets, main_text) in COMPOSITIONS.items():
    first = next((i for i, s in enumerate(snippets) if s in ("compute/common", "placement/common")), None)
    if first is not None:
        before = ["arithmetic/exact_division"] + (["arithmetic/fixed_point"] if snippets[first] == "compute/common" else [])
        COMPOSITIONS[name] = (stage, defines, snippets[:first] + before + snippets[first:], main_text)


WIDE = ("Float64", "Int64", "Int64Atomics")


# A program that needs both wide capabilities: the check must find them here, or it could find them nowhere.
WIDE_PROBE = ("#version 430 core\n#extension GL_ARB_gpu_shader_int64 : require\nlayout(local_size_x = 1) in;\n"
              "layout(std430, binding = 0) buffer b { double d; int64_t i; };\nvoid main() { d = d * 3.0lf; i = i * 3L; }\n")


def wide_capabilities(validator: str, path: pathlib.Path) -> tuple:
    """Compiles `path` to SPIR-V for OpenGL; returns (error log or "", the wide capabilities it declares).
    -G comes before -H: -H alone would pick Vulkan's rules."""
    result = subprocess.run([validator, "-G", "--aml", "--amb", "-H", str(path), "-o", str(path) + ".spv"], capture_output=True, text=True)
    if result.returncode != 0:
        return result.stdout + result.stderr, set()
    declared = set(re.findall(r"^\s*Capability (\w+)", result.stdout, re.MULTILINE))
    return "", declared & set(WIDE)


def expand(text: str) -> str:
    """Inlines '#include family/name' lines (our composition shorthand, not GLSL's)."""
    out = []
    for line in text.splitlines():
        if line.startswith("#include "):
            out.append((SHADERS / (line.split()[1] + ".glsl")).read_text(encoding="utf-8"))
        else:
            out.append(line)
    return "\n".join(out) + "\n"


def main() -> int:
    validator = "glslangValidator"
    if "--validator" in sys.argv:
        validator = sys.argv[sys.argv.index("--validator") + 1]
    used = set()
    with tempfile.TemporaryDirectory() as tmp:
        probe = pathlib.Path(tmp) / "wide_probe.comp"
        probe.write_text(WIDE_PROBE, encoding="utf-8")
        log, wide = wide_capabilities(validator, probe)
        if log or wide != {"Float64", "Int64"}:
            print(f"validate_shaders: the probe's doubles and 64-bit integers were not seen as Float64 and Int64 ({sorted(wide)}):\n{log}",
                  file=sys.stderr)
            return 1
        for name, (stage, defines, snippets, main_text) in COMPOSITIONS.items():
            used.update(snippets)
            source = VERSION + ALPHA + defines + "".join(expand(f"#include {s}") for s in snippets) + expand(main_text)
            used.update(line.split()[1] for line in main_text.splitlines() if line.startswith("#include "))
            path = pathlib.Path(tmp) / f"{name}.{stage}"
            path.write_text(source, encoding="utf-8")
            result = subprocess.run([validator, str(path)], capture_output=True, text=True)
            if result.returncode != 0:
                print(f"validate_shaders: {name} failed:\n{result.stdout}{result.stderr}", file=sys.stderr)
                return 1
            log, wide = wide_capabilities(validator, path)
            if log:
                print(f"validate_shaders: {name} failed to compile to SPIR-V:\n{log}", file=sys.stderr)
                return 1
            if wide:
                print(f"validate_shaders: {name} needs {', '.join(sorted(wide))} (SPIR-V capability), which most GPUs "
                      "run slowly or not at all", file=sys.stderr)
                return 1
    every = {str(p.relative_to(SHADERS).with_suffix("")) for p in SHADERS.rglob("*.glsl")}
    unvalidated = sorted(every - used)
    if unvalidated:
        print(f"validate_shaders: not validated by any composition: {', '.join(unvalidated)}", file=sys.stderr)
        return 1
    print(f"validate_shaders: {len(COMPOSITIONS)} compositions of {len(every)} snippets are valid GLSL, and in SPIR-V "
          "none needs Float64 or Int64")
    return 0


if __name__ == "__main__":
    sys.exit(main())
