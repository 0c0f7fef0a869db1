#!/usr/bin/env python3
"""Every iterated example swept over its driver: the sketch's assembly followed warm (from the
sample nearest the param's sketch value outward both ways, each sample from the previous one's
defaults and branches, as a sweep does), and each sample solved cold (alone, from the sketch), with
`gcs solve --json`. Prints per example the warm failures (where the assembly followed from the
sketch ends), the cold failures, the cold failures that say the sketch's mode has no assembly
there (`OtherMode`), the samples where the cold solve lands on another assembly than the
warm one (points apart by more than 1e-6 of the model's size), the cold jumps between
neighbouring samples, and of the cold answers where the warm sweep has none (past a fold where
the sketch's assembly ends), how many do not say so (`"sketch_assembly_ended"`). BENCHMARKS.md's
cold-against-warm row; run from the repository's root after `cargo build --release -p gcs-cli`:

    python3 compiler/bench/cold_warm.py [SAMPLES]
"""
import json, subprocess, sys, math, re
G = "target/release/gcs"
def solve(path, param, v, prev=None):
    """Cold without `prev`; warm from `prev`, a solution: its defaults and branches."""
    cmd = [G, "solve", path, "--json", "--set", f"{param}={v!r}"]
    for k, x in ((prev or {}).get("defaults") or {}).items():
        cmd += ["--default", f"{k}={x!r}"]
    for k, x in ((prev or {}).get("branches") or {}).items():
        cmd += ["--branch", f"{k}={x}"]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        return None, r.stderr
    return json.loads(r.stdout), ""
def dist(a, b):
    d = 0.0; s = 1.0
    for k, p in a["points"].items():
        q = b["points"].get(k)
        if q is None: continue
        for x, y in zip(p, q):
            d = max(d, abs(x - y)); s = max(s, abs(x))
    return d / s
def sketch_value(path, param):
    text = open(path).read()
    m = re.search(rf"param\s+{param}\s*=\s*([^;]+);", text)
    v = m.group(1).strip()
    if v.endswith("deg"):
        return math.radians(float(v[:-3]))
    return float(v)
cases_all = [("examples/triad_sixbar.gcs", "theta", 0.0, 2*math.pi),
         ("examples/rpr3.gcs", "leg1", 13.0, 16.0),
         ("examples/cube_graph.gcs", "diagonal", 6.0, 7.8),
         ("examples/stewart.gcs", "l1", 2.76, 3.38),
         ("examples/desk_lamp.gcs", "arm", 3.6, 4.4),
         ("examples/fivebar_one_drive.gcs", "theta1", 0.0, 2*math.pi)]
cases = [c for c in cases_all if (len(sys.argv) < 3 or sys.argv[2] in c[0])]
N = int(sys.argv[1]) if len(sys.argv) > 1 else 60
for path, param, lo, hi in cases:
    values = [lo + (hi - lo) * i / (N - 1) for i in range(N)]
    v0 = sketch_value(path, param)
    first = min(range(N), key=lambda i: abs(values[i] - v0))
    warm = [None] * N
    seed, _ = solve(path, param, v0)
    for order in (range(first, N), range(first - 1, -1, -1)):
        prev = seed
        for i in order:
            # Past a failure the assembly followed has ended: nothing is warm from there.
            w, _ = solve(path, param, values[i], prev) if prev else (None, "")
            warm[i] = w
            prev = w
    warm_fail = cold_fail = other_mode = differ = jumps = unsaid = 0
    last = None
    for i, v in enumerate(values):
        cold, err = solve(path, param, v)
        # A jump: a cold answer far from the last one, beyond what the sample step moves it.
        if cold is not None and last is not None and dist(cold, last) > 0.05: jumps += 1
        last = cold
        if warm[i] is None: warm_fail += 1
        if warm[i] is None and cold is not None and not cold.get("sketch_assembly_ended") and not cold.get("branches_changed"): unsaid += 1
        if cold is None:
            cold_fail += 1
            if "sketch's assembly mode" in err or "sketch's mode" in err: other_mode += 1
        if warm[i] is not None and cold is not None and dist(warm[i], cold) > 1e-6: differ += 1
    print(f"{path.split('/')[-1]:28} {param}: {N} samples; warm failures {warm_fail}, cold failures {cold_fail} ({other_mode} other mode), cold on another assembly than warm {differ}, cold jumps between samples {jumps}, cold past the warm sweep's end not saying so {unsaid}")
