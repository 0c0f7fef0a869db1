#!/usr/bin/env bash
# Compiles each FAMILY at N stages (default 100,000), builds the module in debug in a scratch
# crate that depends on gcs-runtime alone, solves it at its defaults, and compares every point
# with `gcs solve --json`. Prints one line per family: module lines, debug build time, and the
# largest difference. BENCHMARKS.md's "Large models" method; run from the repository's root:
#
#   compiler/bench/large.sh strip circle_sketch random_mix rssr_chain
#   N=10000 compiler/bench/large.sh hung_chain
set -euo pipefail
root=$(pwd)
n=${N:-100000}
cargo build -q --release -p gcs-cli -p gcs-bench --examples
gcs="$root/target/release/gcs"
family="$root/target/release/examples/family"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/scratch/src"
cat > "$work/scratch/Cargo.toml" <<TOML
[package]
name = "scratch"
version = "0.1.0"
edition = "2021"

[dependencies]
gcs-runtime = { path = "$root/runtime" }

[workspace]
TOML
cat > "$work/scratch/src/main.rs" <<'RUST'
#[allow(dead_code, clippy::all)]
mod solver {
    include!("../m.rs");
}
fn main() {
    let s = solver::solve(&Default::default(), &Default::default(), &Default::default())
        .expect("solves");
    for (name, p) in s.points() {
        let c: Vec<String> = p.iter().map(|x| format!("{x:?}")).collect();
        println!("{name} {}", c.join(" "));
    }
}
RUST
# The runtime built once, so that each timed build is the module's alone.
"$family" "${1:-truss}" 1 > "$work/m.gcs"
"$gcs" compile "$work/m.gcs" -o "$work/scratch/m.rs" 2>/dev/null
(cd "$work/scratch" && cargo build -q)
for fam in "$@"; do
  "$family" "$fam" "$n" > "$work/m.gcs"
  "$gcs" compile "$work/m.gcs" -o "$work/scratch/m.rs" 2>/dev/null
  lines=$(wc -l < "$work/scratch/m.rs")
  start=$(date +%s.%N)
  (cd "$work/scratch" && touch src/main.rs && cargo build -q)
  end=$(date +%s.%N)
  (cd "$work/scratch" && ./target/debug/scratch) > "$work/generated.txt"
  "$gcs" solve "$work/m.gcs" --json 2>/dev/null > "$work/interpreted.json"
  compared=$(python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
points = json.load(open(f"{work}/interpreted.json")).get("points", {})
n, worst = 0, 0.0
for line in open(f"{work}/generated.txt"):
    name, *xs = line.split()
    if name in points:
        n += 1
        worst = max([worst] + [abs(float(a) - b) for a, b in zip(xs, points[name])])
print(f"{n} points compared, largest difference {worst:.3e}")
PY
)
  printf '%s N=%s: %s lines, debug build %.1f s, %s\n' "$fam" "$n" "$lines" "$(echo "$end - $start" | bc)" "$compared"
done
