#!/usr/bin/env python3
"""Alternate shadelab and the llvmpipe peer (A B A B ...) on one workload and compare medians.

The machine's speed drifts by up to 40% over minutes, so figures are only compared within
one run: each round runs the peer once (20 frames after 3 warm-ups, its frame_ms_median)
and `shadelab bench` once (the same frame counts); the report is the median over rounds of
each side's per-round median, and their ratio.

    tools/bench_vs_llvmpipe.py sphere [--rounds 5] [--bin target/release/shadelab]
    tools/bench_vs_llvmpipe.py shadow        # ../shared/bench/llvmpipe_shadow.py against `bench --workload shadow`

The peer's frame is clear + draw + readback of the 8-bit image; the comparable shadelab
figure is `median_ms` (render + develop to 8-bit sRGB). `float_frame_median_ms` (the other
path, a linear float frame) and `png_median_ms` (+ PNG encoding) are printed beside it.

A figure others can reproduce (docs/performance.md, "Quoting a speed figure"): several runs,
each of alternating rounds, the ratio of each run, their range and the median of the runs'
ratios, with the CPU model and the load beside them:

    tools/bench_vs_llvmpipe.py sphere --runs 3 --rounds 7    # one JSON line per run, then the summary
"""
import argparse
import platform
import time
import json
import os
import statistics
import subprocess
import sys

PEER = {"sphere": "W-a", "sphere-gouraud": "W-b", "dense": "W2", "shadow": "W-shadow"}
# The shadow-mapping peer is its own script (it takes no workload argument).
SHADOW_PEER = "llvmpipe_shadow.py"
HERE = os.path.dirname(os.path.abspath(__file__))


def cpu_model():
    """The CPU's model name and whether it has AVX-512F and AVX2, from /proc/cpuinfo."""
    try:
        with open("/proc/cpuinfo") as f:
            info = f.read()
    except OSError:
        return platform.processor() or "unknown CPU", ""
    model = next((l.split(":", 1)[1].strip() for l in info.splitlines() if l.startswith("model name")), "unknown CPU")
    flags = next((l.split(":", 1)[1].split() for l in info.splitlines() if l.startswith("flags")), [])
    isa = "AVX-512" if "avx512f" in flags else "AVX2" if "avx2" in flags else "SSE2"
    return model, isa


def one_run(a):
    """One run of `a.rounds` alternating rounds: the peer's and our medians over rounds."""
    peer, ours = [], {"median_ms": [], "float_frame_median_ms": [], "png_median_ms": []}
    threads = None
    for r in range(a.rounds):
        if a.workload == "shadow":
            peer_cmd = [a.python, os.path.join(os.path.dirname(a.peer), SHADOW_PEER)]
        else:
            peer_cmd = [a.python, a.peer, PEER[a.workload]]
        out = subprocess.run(peer_cmd, check=True, capture_output=True, text=True).stdout
        peer.append(json.loads(out.strip().splitlines()[-1])["frame_ms_median"])
        cmd = [a.bin, "bench", "--workload", a.workload, "--format", "json"]
        if a.threads:
            cmd[1:1] = ["--threads", str(a.threads)]
        j = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout.strip().splitlines()[-1])
        threads = j["threads"]
        for k in ours:
            ours[k].append(j.get(k, float("nan")))
        print(f"round {r + 1}: llvmpipe {peer[-1]:.2f} ms, shadelab {j['median_ms']:.2f} ms "
              f"(float {j.get('float_frame_median_ms', float('nan')):.2f}, +png {j.get('png_median_ms', float('nan')):.2f})",
              file=sys.stderr)
    p = statistics.median(peer)
    o = {k: statistics.median(v) for k, v in ours.items()}
    return {
        "workload": a.workload,
        "rounds": a.rounds,
        "threads": threads,
        "llvmpipe_median_ms": round(p, 2),
        "shadelab_median_ms": round(o["median_ms"], 2),
        "shadelab_float_frame_median_ms": round(o["float_frame_median_ms"], 2),
        "shadelab_png_median_ms": round(o["png_median_ms"], 2),
        "ratio_shadelab_over_llvmpipe": round(o["median_ms"] / p, 3),
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("workload", choices=sorted(PEER))
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--runs", type=int, default=1, help="separate runs of alternating rounds (the range is over runs)")
    ap.add_argument("--pause", type=float, default=10.0, help="seconds between runs")
    ap.add_argument("--bin", default=os.path.join(HERE, "..", "target", "release", "shadelab"))
    ap.add_argument("--python", default=os.path.expanduser("~/.cache/peer-venv/bin/python"))
    ap.add_argument("--peer", default=os.path.join(HERE, "..", "..", "shared", "bench", "llvmpipe_moderngl.py"))
    ap.add_argument("--threads", type=int, default=0, help="shadelab --threads (0: all cores)")
    a = ap.parse_args()

    model, isa = cpu_model()
    runs, loads = [], []
    for k in range(a.runs):
        if k:
            time.sleep(a.pause)
        load = os.getloadavg()[0]
        run = one_run(a)
        run["load_1min"] = round(load, 2)
        run["cpu"] = model
        runs.append(run)
        loads.append(load)
        print(json.dumps(run))
    if a.runs > 1:
        ratios = [r["ratio_shadelab_over_llvmpipe"] for r in runs]
        print(json.dumps({
            "workload": a.workload,
            "cpu": model,
            "isa": isa,
            "threads": runs[0]["threads"],
            "runs": a.runs,
            "rounds_per_run": a.rounds,
            "ratios": ratios,
            "ratio_min": min(ratios),
            "ratio_max": max(ratios),
            "ratio_median_of_runs": round(statistics.median(ratios), 3),
            "load_1min_min": round(min(loads), 2),
            "load_1min_max": round(max(loads), 2),
            "quote": f"{a.workload}: {min(ratios):.2f}–{max(ratios):.2f} (median {statistics.median(ratios):.2f}, "
                     f"{a.runs} runs × {a.rounds} rounds), {model} ({isa}), {runs[0]['threads']} threads, load {min(loads):.1f}–{max(loads):.1f}",
        }))


if __name__ == "__main__":
    main()
