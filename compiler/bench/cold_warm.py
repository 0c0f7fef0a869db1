#!/usr/bin/env python3
"""Every iterated example swept over its driver: each sample solved warm (from the previous
sample's defaults, as a sweep does) and cold (alone, from the sketch), with `gcs solve --json`.
Prints per example the warm failures, the cold failures, and the samples where the cold solve
lands on another assembly than the warm one (points apart by more than 1e-6 of the model's
size). BENCHMARKS.md's cold-against-warm row; run from the repository's root after
`cargo build --release -p gcs-cli`:

    python3 compiler/bench/cold_warm.py [SAMPLES]
"""
import json, subprocess, sys, math
G = "target/release/gcs"
def solve(path, param, v, defaults=None):
    cmd = [G, "solve", path, "--json", "--set", f"{param}={v!r}"]
    for k, x in (defaults or {}).items():
        cmd += ["--default", f"{k}={x!r}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        return None
    return json.loads(r.stdout)
def dist(a, b):
    d = 0.0; s = 1.0
    for k, p in a["points"].items():
        q = b["points"].get(k)
        if q is None: continue
        for x, y in zip(p, q):
            d = max(d, abs(x - y)); s = max(s, abs(x))
    return d / s
cases = [("examples/triad_sixbar.gcs", "theta", 0.0, 2*math.pi),
         ("examples/rpr3.gcs", "leg1", 13.0, 16.0),
         ("examples/cube_graph.gcs", "diagonal", 6.0, 7.8),
         ("examples/stewart.gcs", "l1", 2.76, 3.38),
         ("examples/desk_lamp.gcs", "arm", 3.6, 4.4),
         ("examples/fivebar_one_drive.gcs", "theta1", 0.0, 2*math.pi)]
N = int(sys.argv[1]) if len(sys.argv) > 1 else 60
for path, param, lo, hi in cases:
    pass
    prev = None; warm_fail = cold_fail = differ = 0; warm_ok = 0
    for i in range(N):
        v = lo + (hi - lo) * i / (N - 1)
        cold = solve(path, param, v)
        warm = solve(path, param, v, prev["defaults"] if prev else None)
        if warm is None: warm_fail += 1
        else: warm_ok += 1
        if cold is None: cold_fail += 1
        if warm is not None and cold is not None and dist(warm, cold) > 1e-6: differ += 1
        if warm is not None: prev = warm
    print(f"{path.split('/')[-1]:28} {param}: {N} samples; warm failures {warm_fail}, cold failures {cold_fail}, cold on another assembly than warm {differ}")
