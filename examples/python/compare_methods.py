#!/usr/bin/env python3
"""Four methods on the Sintel hair against the exact deep shadow map, from Python: the transmittance
along one light ray, and each method's error against its memory, drawn with matplotlib into a PNG.

    PYTHONPATH=build/python python3 examples/python/compare_methods.py [--model FILE] [--res N] [--out FILE.png]
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import hairshadow as hs  # noqa: E402

HERE = pathlib.Path(__file__).resolve()
METHODS = ["osm:16", "dom:3", "occ:128:4", "fom:7"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", default=str(HERE.parents[3] / "shared" / "data" / "sintel" / "sintel_hair.16points.tfx"))
    parser.add_argument("--res", type=int, default=512)
    parser.add_argument("--light", default="dir:0,-1,-1")
    parser.add_argument("--out", default="compare_methods.png")
    args = parser.parse_args()

    model = hs.load(args.model)
    exact = hs.ShadowMap("dsm")
    exact.build(model, args.light, args.res)
    maps = {}
    for spec in METHODS:
        maps[spec] = hs.ShadowMap(spec)
        maps[spec].build(model, args.light, args.res)

    # The light ray through the hair's darkest point: the densest hair, where methods differ most.
    reference = exact.transmittance(model.points)
    x, y = (int(v) for v in exact.light_space.project(model.points[np.argmin(reference)][None])[0, :2])
    depths, _ = exact.fragments(x, y)
    span = np.linspace(max(0.0, depths[0] - 0.02), min(1.0, depths[-1] + 0.02), 400, dtype=np.float32)

    # Each method's mean error at the hair's own points against its bytes.
    errors = {spec: float(np.mean(np.abs(m.transmittance(model.points) - reference))) for spec, m in maps.items()}

    figure, (ray, memory) = plt.subplots(1, 2, figsize=(11, 4.2))
    ray.plot(span, exact.transmittance_at(x, y, span), "k", lw=2, label="exact (dsm)")
    for spec, m in maps.items():
        ray.plot(span, m.transmittance_at(x, y, span), label=spec)
    ray.set(xlabel="linear depth from the light", ylabel="transmittance", title=f"texel ({x}, {y}): {len(depths)} fragments")
    ray.legend()
    for spec, m in maps.items():
        memory.scatter(m.memory_bytes / 2**20, errors[spec])
        memory.annotate(spec, (m.memory_bytes / 2**20, errors[spec]), textcoords="offset points", xytext=(4, 4))
    memory.set(xlabel="maps (MiB)", ylabel="mean |T - T_exact| at the hair's points", title=f"{model.strand_count} strands, {args.res}x{args.res}")
    figure.tight_layout()
    figure.savefig(args.out, dpi=110)
    for spec in METHODS:
        print(f"{spec:10s} {maps[spec].memory_bytes / 2**20:7.2f} MiB  mean error {errors[spec]:.4f}")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
