#!/usr/bin/env python3
"""The cost of crossing from Python: transmittance at 1M points through hairshadow.ShadowMap against
the same query timed inside C++ (hairshadow._query_ms_in_cpp: the same maps and points, no array
checks, no output array), alternated in one process; medians of the runs.

    PYTHONPATH=build/python python3 bench/python_crossing.py [--model FILE] [--methods dom:3,occ:128:4] [--repeat 15]
"""
import argparse
import pathlib
import statistics
import time

import numpy as np

import hairshadow as hs

HERE = pathlib.Path(__file__).resolve()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--model", default=str(HERE.parents[2] / "shared" / "data" / "sintel" / "sintel_hair.16points.tfx"))
    parser.add_argument("--methods", default="dom:3,occ:128:4,fom:7")
    parser.add_argument("--res", type=int, default=512)
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--repeat", type=int, default=15)
    args = parser.parse_args()
    model = hs.load(args.model)
    rng = np.random.default_rng(1)
    i, j = rng.integers(0, model.point_count, (2, args.points))
    t = rng.random((args.points, 1), dtype=np.float32)
    points = np.ascontiguousarray(model.points[i] * (1 - t) + model.points[j] * t, dtype=np.float32)
    print(f"{args.points} points in {model.strand_count} strands' hair, {args.res}x{args.res}, medians of {args.repeat} runs each, alternated")
    print("| method | C++ query (ms) | from Python (ms) | ratio |")
    print("|---|---|---|---|")
    for spec in args.methods.split(","):
        m = hs.ShadowMap(spec)
        m.build(model, resolution=args.res)
        cpp, python = [], []
        for _ in range(args.repeat):
            cpp += hs._query_ms_in_cpp(m, points, 1)
            start = time.perf_counter()
            m.transmittance(points)
            python.append((time.perf_counter() - start) * 1e3)
        a, b = statistics.median(cpp), statistics.median(python)
        print(f"| {spec} | {a:.2f} | {b:.2f} | {b / a:.3f} |")


if __name__ == "__main__":
    main()
