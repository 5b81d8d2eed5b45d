#!/usr/bin/env python3
"""shadelab's path tracer against Mitsuba 3's (scalar_rgb `path` integrator) on lesson 27's box.

Both render the box at 256 × 256, 16 samples a pixel, paths of up to 16 segments (the
`path` workload of `shadelab bench`; Mitsuba's scene is tools/mitsuba_reference.py's
`path_box_scene` at that size). Rounds alternate A B A B: Mitsuba's render timed in this
process (after one warm-up render, scene loaded once), then `shadelab bench --workload path`
(its median of --frames frames). Prints each round's times and the ratio shadelab / Mitsuba,
then the median and range of the ratios.

Usage:  pip install mitsuba
        python3 tools/bench_vs_mitsuba_path.py --threads 1 --rounds 5   (from the repository root,
        after cargo build --release)
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402

mi.set_variant("scalar_rgb")
from mitsuba_reference import path_box_scene  # noqa: E402


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--frames", type=int, default=3)
    ap.add_argument("--shadelab", default="target/release/shadelab")
    a = ap.parse_args()
    dr.set_thread_count(a.threads)
    params = path_box_scene(size=256, spp=16)
    mi.render(params)  # warm-up
    ratios = []
    for r in range(a.rounds):
        t = time.perf_counter()
        mi.render(params)
        theirs = (time.perf_counter() - t) * 1e3
        out = subprocess.run(
            [a.shadelab, "--threads", str(a.threads), "bench", "--workload", "path", "--frames", str(a.frames), "--format", "jsonl"],
            check=True, capture_output=True, text=True).stdout
        ours = json.loads(out.strip().splitlines()[-1])["median_ms"]
        ratios.append(ours / theirs)
        print(f"round {r + 1}: Mitsuba {theirs:.0f} ms, shadelab {ours:.0f} ms, ratio {ours / theirs:.3f}", flush=True)
    print(f"{a.threads} thread(s): shadelab / Mitsuba median {statistics.median(ratios):.3f}, range {min(ratios):.3f}–{max(ratios):.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
