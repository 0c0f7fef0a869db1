//! Families of models of any size, written as `.gcs` text: the workloads of the scaling
//! measurements, the benchmarks and the stress tests (issue 7).
//!
//! Each generator returns a well-constrained model whose sketch is close to an assembly, so
//! that the sketch's branches are the natural ones: 2d but for [`rssr_chain`], the spatial
//! counterpart of the chain of four-bars. Every family is a chain of local problems repeated
//! `n` times, so analysis and solve time should grow linearly in `n`: the same problem, or for
//! [`mixed`] three kinds woven in a fixed pseudo-random order, so that a large model's pieces
//! mostly differ.
//!
//! `gcs-bench` re-exports this module; `cargo run -p gcs-bench --example family -- FAMILY N`
//! prints a member of any size, and `examples/families/` keeps members at the sizes the
//! benches use (`compiler/bench/tests/family_files.rs` checks each file against its
//! generator).
//!
//! [`params`] and [`points`] stress the front end rather than the analysis (issue 17, item 7):
//! many params, half of them warned about, for `gcs check`; many points in one JSON answer
//! verified by name, for `gcs solve --json`.

use std::fmt::Write as _;

/// One of the generated families.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// [`four_bar_chain`]: Kramer's chain of four-bars (paper 000, Fig. 10).
    FourBarChain,
    /// [`sketch_profile`]: segments joined by tangent arcs, as in a CAD sketch.
    SketchProfile,
    /// [`closed_profile`]: a closed profile of segments and tangent fillet arcs.
    ClosedProfile,
    /// [`truss`]: a planar truss of triangles.
    Truss,
    /// [`params`]: many params, half of them never used.
    Params,
    /// [`points`]: a row of points along a fixed line.
    Points,
    /// [`rssr_chain`]: spatial four-bars in series.
    RssrChain,
    /// [`mixed`]: stages of three kinds woven together, whose pieces mostly differ.
    Mixed,
    /// [`hung_chain`]: a crank and free points hung on it by distances only.
    HungChain,
    /// [`strip`]: a triangulated strip of points, its rungs set by a param.
    Strip,
    /// [`circle_sketch`]: a long sketch of segments, each with a circle tangent to it.
    CircleSketch,
    /// [`random_mix`]: stages of every planar family, picked at random.
    RandomMix,
    /// [`stair_profile`]: a closed stair-step profile of horizontal and vertical segments,
    /// every corner filleted, closed by two free lengths (a linear stage).
    StairProfile,
}

impl Family {
    /// Every family, in a fixed order.
    pub const ALL: [Family; 13] = [
        Family::FourBarChain,
        Family::SketchProfile,
        Family::ClosedProfile,
        Family::Truss,
        Family::Params,
        Family::Points,
        Family::RssrChain,
        Family::Mixed,
        Family::HungChain,
        Family::Strip,
        Family::CircleSketch,
        Family::RandomMix,
        Family::StairProfile,
    ];

    /// The family's short name, as the command line and the reports spell it.
    pub fn name(self) -> &'static str {
        match self {
            Family::FourBarChain => "fourbar_chain",
            Family::SketchProfile => "sketch_profile",
            Family::ClosedProfile => "closed_profile",
            Family::Truss => "truss",
            Family::Params => "params",
            Family::Points => "points",
            Family::RssrChain => "rssr_chain",
            Family::Mixed => "mixed",
            Family::HungChain => "hung_chain",
            Family::Strip => "strip",
            Family::CircleSketch => "circle_sketch",
            Family::RandomMix => "random_mix",
            Family::StairProfile => "stair_profile",
        }
    }

    /// The family with that short name.
    pub fn named(name: &str) -> Option<Family> {
        Family::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The model of size `n`.
    pub fn model(self, n: usize) -> String {
        match self {
            Family::FourBarChain => four_bar_chain(n),
            Family::SketchProfile => sketch_profile(n),
            Family::ClosedProfile => closed_profile(n),
            Family::Truss => truss(n),
            Family::Params => params(n),
            Family::Points => points(n),
            Family::RssrChain => rssr_chain(n),
            Family::Mixed => mixed(n),
            Family::HungChain => hung_chain(n),
            Family::Strip => strip(n),
            Family::CircleSketch => circle_sketch(n),
            Family::RandomMix => random_mix(n),
            Family::StairProfile => stair_profile(n),
        }
    }

    /// The param the family's sweeps drive, and its range (radians or length).
    pub fn driver(self) -> (&'static str, f64, f64) {
        match self {
            Family::FourBarChain => ("theta", 0.0, std::f64::consts::TAU),
            Family::SketchProfile => ("len", 8.0, 12.0),
            Family::ClosedProfile => ("len", 8.0, 12.0),
            Family::Truss => ("bar", 1.5, 2.5),
            Family::Params => ("p0", 0.5, 1.5),
            Family::Points => ("gap", 0.5, 1.5),
            Family::RssrChain => ("theta", 0.0, std::f64::consts::TAU),
            Family::Mixed => ("theta", 0.0, std::f64::consts::TAU),
            Family::HungChain => ("theta", 0.0, std::f64::consts::TAU),
            Family::Strip => ("w", 0.9, 1.1),
            Family::CircleSketch => ("r", 0.8, 1.2),
            Family::RandomMix => ("theta", 0.0, std::f64::consts::TAU),
            Family::StairProfile => ("r", 0.3, 0.7),
        }
    }
}

/// `n` four-bars in series, each one's rocker the next one's crank (paper 000, Fig. 10).
///
/// Stage `k` has a fixed pivot `P{k}` at `(4k, 0)`, a coupler of length 4 and a rocker of length
/// 3 whose point `b`, 1.5 below its pivot, drives stage `k + 1`: every stage is a Grashof
/// crank-rocker (1.5 + 4 < 3 + 4), so it assembles at every input angle. The first crank turns
/// by `theta`; the output is the last rocker's `b`. One branch variable `elbow{k}` per stage.
pub fn four_bar_chain(n: usize) -> String {
    let n = n.max(1);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// {n} four-bars in series: each rocker is the next stage's crank (paper 000, Fig. 10)."
    );
    s.push_str("space 2d;\n\nparam theta = 30 deg;\n\n");
    s.push_str("fixed vector X = (1, 0);\nfixed point P0 = (0, 0);\n");
    s.push_str(FOUR_BAR_HEAD);
    for k in 1..=n {
        four_bar_stage(&mut s, k, "crank");
    }
    let _ = writeln!(s, "\noutput rocker{n}.b;");
    s
}

/// The chain of four-bars' ground and crank, turned by `theta` about `P0`.
const FOUR_BAR_HEAD: &str = "body crank at (0, 0) { point a = (0, 0); point b = (1.5, 0); \
                             vector u = (1, 0); }\n\
                             coincident(crank.a, P0);\ndrive: angle(X, crank.u) = theta;\n";

/// Stage `k` (from 1) of the chain of four-bars, driven by the rocker before it (the body
/// `crank` for the first).
fn four_bar_stage(s: &mut String, k: usize, crank: &str) {
    let prev = if k == 1 {
        crank.to_string()
    } else {
        format!("rocker{}", k - 1)
    };
    let x = 4 * k;
    let _ = writeln!(s, "\nfixed point P{k} = ({x}, 0);");
    let _ = writeln!(
        s,
        "body coupler{k} at ({}, 0) {{ point b = (0, 0); point c = (4, 0); }}",
        x - 3
    );
    let _ = writeln!(
        s,
        "body rocker{k} at ({x}, 0) {{ point d = (0, 0); point c = (0, 3); point b = (0, -1.5); }}"
    );
    let _ = writeln!(s, "coincident({prev}.b, coupler{k}.b);");
    let _ = writeln!(s, "elbow{k}: coincident(coupler{k}.c, rocker{k}.c);");
    let _ = writeln!(s, "coincident(rocker{k}.d, P{k});");
}

/// `n` spatial four-bars (RSSR: revolute, spherical, spherical, revolute) in series, each
/// rocker the next stage's crank: the spatial counterpart of [`four_bar_chain`].
///
/// Every stage is the RSSR of `examples/rssr.gcs` in its own frame: the input turns about its
/// frame's z axis with a point at 1 from it; a coupler of length `sqrt(19)` with a ball joint
/// at each end; a rocker turning about an axis along the frame's y through `(4, 1, 1)`, its tip
/// 2 above the axis and a drive point 1 beside it, which is the next stage's input point. The
/// next stage's frame is at the rocker's axis, its z axis the rocker's, its x axis towards
/// the drive point; so the stages alternate between two orientations and climb along the
/// diagonal. Each coupler may spin about its own line: an idle freedom, one default per stage
/// at its sketch value. One branch variable per stage.
pub fn rssr_chain(n: usize) -> String {
    type V = [i64; 3];
    // The stage frame's axes as columns: x, y, z (a rotation of integers).
    type R = [V; 3];
    fn apply(r: &R, v: V) -> V {
        let mut out = [0; 3];
        for (k, column) in r.iter().enumerate() {
            for i in 0..3 {
                out[i] += column[i] * v[k];
            }
        }
        out
    }
    fn add(a: V, b: V) -> V {
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    }
    fn t(v: V) -> String {
        format!("({}, {}, {})", v[0], v[1], v[2])
    }
    let n = n.max(1);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// {n} spatial four-bars (RSSR) in series: each rocker is the next stage's crank."
    );
    s.push_str(
        "space 3d;

param theta = 30 deg;

",
    );
    // Stage k's frame: origin and axes; the next one's at the rocker's axis.
    let mut frames: Vec<(V, R)> = vec![([0; 3], [[1, 0, 0], [0, 1, 0], [0, 0, 1]])];
    for k in 0..n {
        let (o, r) = frames[k];
        let next_o = add(o, apply(&r, [4, 1, 1]));
        let next_r = [
            apply(&r, [-1, 0, 0]),
            apply(&r, [0, 0, 1]),
            apply(&r, [0, 1, 0]),
        ];
        frames.push((next_o, next_r));
    }
    s.push_str(
        "fixed body ground {
",
    );
    for (k, (o, r)) in frames.iter().take(n + 1).enumerate() {
        let _ = writeln!(
            s,
            "    marker axis{k} = {} z {} x {};",
            t(*o),
            t(r[2]),
            t(r[0])
        );
    }
    s.push_str(
        "}
",
    );
    s.push_str(
        "body crank {
    marker base = (0, 0, 0) z (0, 0, 1) x (1, 0, 0);
    point drive = (1, 0, 0);
}
",
    );
    s.push_str(
        "revolute(crank.base, ground.axis0);
input: offset_x(ground.axis0, crank.base) = theta;
",
    );
    let mut prev = "crank".to_string();
    for k in 1..=n {
        let (o, r) = frames[k - 1];
        let at = |v: V| t(add(o, apply(&r, v)));
        let (next_o, next_r) = frames[k];
        let _ = writeln!(
            s,
            "
body coupler{k} {{ point a = {}; point b = {}; }}",
            at([1, 0, 0]),
            at([4, 1, 3])
        );
        let _ = writeln!(
            s,
            "body rocker{k} {{
    marker base = {} z {} x {};
    point tip = {};
    point drive = {};
}}",
            t(next_o),
            t(next_r[2]),
            t(next_r[0]),
            at([4, 1, 3]),
            at([3, 1, 1])
        );
        let _ = writeln!(s, "spherical(coupler{k}.a, {prev}.drive);");
        let _ = writeln!(s, "revolute(rocker{k}.base, ground.axis{k});");
        let _ = writeln!(s, "ball{k}: spherical(coupler{k}.b, rocker{k}.tip);");
        prev = format!("rocker{k}");
    }
    let _ = writeln!(
        s,
        "
output {prev}.drive;"
    );
    s
}

/// A profile of `n` segments of length `len`, alternately at +20 and -20 degrees, each joined
/// to the next by a fillet arc of radius `r` tangent to both (and a last arc after the last
/// segment): `n` lines and `n` tangent arcs, dimensioned as a CAD sketch is.
pub fn sketch_profile(n: usize) -> String {
    let n = n.max(1);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// A sketch profile: {n} segments joined by {n} tangent fillet arcs."
    );
    s.push_str("space 2d;\n\nparam len = 10;\nparam r = 2;\n\n");
    s.push_str("fixed point origin = (0, 0);\nfixed vector X = (1, 0);\n");
    let mut at = (0.0f64, 0.0f64);
    for k in 0..n {
        sketch_stage(&mut s, k, &mut at);
    }
    let _ = writeln!(s, "\noutput f{};", n - 1);
    s
}

/// Segment `k` of the sketch profile and its fillet, starting at `at` (moved past the arc):
/// at 20 degrees up or down in turn, tangent to the fillet before it.
fn sketch_stage(s: &mut String, k: usize, at: &mut (f64, f64)) {
    let (x, y) = *at;
    let deg: f64 = if k.is_multiple_of(2) { 20.0 } else { -20.0 };
    let (dy, dx) = deg.to_radians().sin_cos();
    let (ex, ey) = (x + 10.0 * dx, y + 10.0 * dy);
    let _ = writeln!(
        s,
        "\nsegment s{k} = ({x:.3}, {y:.3}) -> ({ex:.3}, {ey:.3});"
    );
    if k == 0 {
        s.push_str("coincident(s0.start, origin);\n");
    }
    let _ = writeln!(s, "angle(X, s{k}) = {deg} deg;");
    let _ = writeln!(s, "length(s{k}) = len;");
    // The fillet's centre: on the inside of the turn, 2 from the segment's end.
    let side = if deg > 0.0 { -1.0 } else { 1.0 };
    let (cx, cy) = (ex - side * 2.0 * dy, ey + side * 2.0 * dx);
    fillet(s, k, (cx, cy));
    // The next segment starts past the arc.
    *at = (ex + 1.0, ey);
}

/// Fillet `f{k}` of a profile, sketched at centre `(cx, cy)`, of radius `r`: tangent to
/// segment `s{k}` through its end; and `s{k}` (but the first) tangent to the fillet before it
/// through its start.
fn fillet(s: &mut String, k: usize, (cx, cy): (f64, f64)) {
    let _ = writeln!(s, "circle f{k} = center ({cx:.3}, {cy:.3}) radius 2;");
    let _ = writeln!(s, "radius(f{k}) = r;");
    let _ = writeln!(s, "tangent(s{k}, f{k});");
    let _ = writeln!(s, "on(s{k}.end, f{k});");
    if k > 0 {
        let _ = writeln!(s, "tangent(s{k}, f{});", k - 1);
        let _ = writeln!(s, "on(s{k}.start, f{});", k - 1);
    }
}

/// A closed profile of `n` segments (at least 3), each turned `360 / n` degrees from the last,
/// joined by `n` tangent fillet arcs of radius `r` (each with `on` and `tangent` at both of its
/// segments), every edge of length `len` but the last two, which the loop closes: issue 19's
/// closed sketch, solved in closed form (the two free lengths where the last sides' lines
/// meet).
pub fn closed_profile(n: usize) -> String {
    let n = n.max(3);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// A closed profile: {n} segments turning by 360/{n} degrees, joined by {n} tangent fillet\n\
         // arcs; the last two edge lengths are left free: the loop closes them."
    );
    s.push_str("space 2d;\n\nparam len = 10;\nparam r = 2;\n\n");
    s.push_str("fixed point origin = (0, 0);\nfixed vector X = (1, 0);\n");
    let turn = 360.0 / n as f64;
    let (mut x, mut y) = (0.0f64, 0.0f64);
    for k in 0..n {
        let (dy, dx) = (k as f64 * turn).to_radians().sin_cos();
        let (ex, ey) = (x + 10.0 * dx, y + 10.0 * dy);
        let _ = writeln!(
            s,
            "\nsegment s{k} = ({x:.3}, {y:.3}) -> ({ex:.3}, {ey:.3});"
        );
        if k == 0 {
            s.push_str("coincident(s0.start, origin);\n");
        }
        let _ = writeln!(s, "angle(X, s{k}) = {} deg;", k as f64 * turn);
        if k + 2 < n {
            let _ = writeln!(s, "length(s{k}) = len;");
        }
        // The fillet's centre: to the left of the segment's end (the profile turns left).
        let (cx, cy) = (ex - 2.0 * dy, ey + 2.0 * dx);
        fillet(&mut s, k, (cx, cy));
        // The next segment starts where the arc ends.
        let (ny, nx) = ((k + 1) as f64 * turn).to_radians().sin_cos();
        x = cx + 2.0 * ny;
        y = cy - 2.0 * nx;
    }
    let _ = writeln!(s, "tangent(s0, f{});", n - 1);
    let _ = writeln!(s, "on(s0.start, f{});", n - 1);
    s
}

/// A Warren truss of `n` triangles: joints `p0`, `p1` fixed, and each later joint `p{k}` held
/// by two bars of length `bar` to the two joints before it. One branch variable per joint
/// (which side of the previous bar it lies on).
pub fn truss(n: usize) -> String {
    let n = n.max(1);
    let h = 3f64.sqrt();
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// A Warren truss of {n} triangles, every bar of length `bar`."
    );
    s.push_str("space 2d;\n\nparam bar = 2;\n\n");
    s.push_str("fixed point p0 = (0, 0);\n");
    let _ = writeln!(s, "fixed point p1 = (1, {h:.17});");
    for k in 2..n + 2 {
        truss_stage(&mut s, "p", k);
    }
    let _ = writeln!(s, "\noutput p{};", n + 1);
    s
}

/// Point `{p}{k}` of the truss (from 2), at `bar` from the two before it: a triangle.
fn truss_stage(s: &mut String, p: &str, k: usize) {
    let h = 3f64.sqrt();
    let y = if k % 2 == 1 { h } else { 0.0 };
    // The sketch is off the assembly by a little, as a user's drawing would be.
    let _ = writeln!(
        s,
        "\npoint {p}{k} = ({:.3}, {:.3});",
        k as f64 + 0.05,
        y - 0.04
    );
    let _ = writeln!(s, "distance({p}{}, {p}{k}) = bar;", k - 2);
    let _ = writeln!(s, "distance({p}{}, {p}{k}) = bar;", k - 1);
}

/// `n` stages of three kinds woven into one model: a chain of four-bars, a truss and a sketch
/// profile, each stage of a kind picked by a fixed pseudo-random sequence. The three are
/// independent (no constraint joins them), but the plan takes their stages in the order
/// written, so its runs of step groups seldom repeat: a large model whose pieces mostly
/// differ, where every other family repeats one (issue 22).
pub fn mixed(n: usize) -> String {
    let n = n.max(3);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// {n} stages of a chain of four-bars, a truss and a sketch profile, woven together."
    );
    s.push_str(
        "space 2d;\n\nparam theta = 30 deg;\nparam bar = 2;\nparam len = 10;\nparam r = 2;\n\n",
    );
    s.push_str("fixed vector X = (1, 0);\nfixed point P0 = (0, 0);\n");
    s.push_str(FOUR_BAR_HEAD);
    let _ = writeln!(
        s,
        "fixed point t0 = (0, 0);\nfixed point t1 = (1, {:.17});",
        3f64.sqrt()
    );
    s.push_str("fixed point origin = (0, 0);\n");
    let (mut bars, mut truss, mut sketch) = (0, 2, 0);
    let mut at = (0.0f64, 0.0f64);
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    for k in 0..n {
        let next = xorshift(&mut seed);
        // Each kind at least once.
        let kind = if k < 3 { k as u64 } else { next % 3 };
        match kind {
            0 => {
                bars += 1;
                four_bar_stage(&mut s, bars, "crank");
            }
            1 => {
                truss_stage(&mut s, "t", truss);
                truss += 1;
            }
            _ => {
                sketch_stage(&mut s, sketch, &mut at);
                sketch += 1;
            }
        }
    }
    let _ = writeln!(
        s,
        "\noutput rocker{bars}.b, t{}, f{};",
        truss - 1,
        sketch - 1
    );
    s
}

/// A chain of `n` four-bars hung on each other as SolveSpace and PlaneGCS pose Kramer's Fig. 10
/// family: no bodies, only points and distances. A crank `crank` turned by `theta` about the
/// fixed `O`, the fixed `C0`, then free points `B1, C1, …, Bn, Cn`, each stage a pair of
/// triangles: `Bk` at fixed distances from `B{k-1}` and `C{k-1}`, `Ck` from `Bk` and `C{k-1}`
/// (with `B0` the crank's end). One `output`, the last two points.
pub fn hung_chain(n: usize) -> String {
    let n = n.max(1);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// A chain of {n} four-bars of points hung on a crank by distances only."
    );
    s.push_str("space 2d;\n\nparam theta = 90 deg;\n\n");
    s.push_str(HUNG_HEAD);
    for k in 1..=n {
        hung_stage(&mut s, k);
    }
    let _ = writeln!(s, "\noutput B{n}, C{n};");
    s
}

/// The hung chain's ground and crank: `B0` is the crank's end.
const HUNG_HEAD: &str = "fixed vector X = (1, 0);\nfixed point O = (0, 0);\n\
                         fixed point C0 = (1, 0);\n\
                         segment crank = (0, 0) -> (0, 1.5);\n\
                         coincident(crank.start, O);\nlength(crank) = 1.5;\n\
                         drive: angle(X, crank) = theta;\npoint B0 = (0.02, 1.49);\n\
                         coincident(B0, crank.end);\n";

/// Stage `k` (from 1) of the hung chain: `Bk` and `Ck`, sketched a little off the assembly.
fn hung_stage(s: &mut String, k: usize) {
    let x = 2.0 * k as f64;
    let _ = writeln!(s, "\npoint B{k} = ({:.2}, 1.52);", x + 0.03);
    let _ = writeln!(s, "point C{k} = ({:.2}, -0.02);", x + 1.0);
    let j = k - 1;
    let diagonal = 3.25f64.sqrt();
    let _ = writeln!(s, "distance(B{j}, B{k}) = 2;");
    let _ = writeln!(s, "distance(C{j}, B{k}) = {diagonal:.17};");
    let _ = writeln!(s, "distance(B{k}, C{k}) = {diagonal:.17};");
    let _ = writeln!(s, "distance(C{j}, C{k}) = 2;");
}

/// A triangulated strip of `n` quads between two rails of points, `a0` and `b0` fixed: each
/// quad's rail edges of lengths that vary along the strip (a fixed pseudo-random sequence, so
/// that no two stages share their constants), its rung `distance(ak, bk) = w` and its diagonal
/// `distance(a{k-1}, bk)`. One branch variable per point.
pub fn strip(n: usize) -> String {
    let n = n.max(1);
    let mut s = String::new();
    let _ = writeln!(s, "// A triangulated strip of {n} quads, its rungs `w`.");
    s.push_str("space 2d;\n\nparam w = 1;\n\n");
    s.push_str("fixed point a0 = (0, 0);\nfixed point b0 = (0, 1);\n");
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut x = 0.0f64;
    for k in 1..=n {
        // A rail edge between 0.9 and 1.1.
        let step = 0.9 + 0.2 * (xorshift(&mut seed) % 1000) as f64 / 1000.0;
        x += step;
        let j = k - 1;
        let _ = writeln!(s, "\npoint a{k} = ({:.3}, 0.02);", x + 0.03);
        let _ = writeln!(s, "point b{k} = ({:.3}, 0.97);", x - 0.02);
        let _ = writeln!(s, "distance(a{j}, a{k}) = {step:.3};");
        let _ = writeln!(
            s,
            "distance(a{j}, b{k}) = {:.17};",
            (step * step + 1.0).sqrt()
        );
        let _ = writeln!(s, "distance(a{k}, b{k}) = w;");
        let _ = writeln!(s, "distance(b{j}, b{k}) = {step:.3};");
    }
    let _ = writeln!(s, "\noutput a{n}, b{n};");
    s
}

/// A long sketch of `n` segments end to end, each turned up or down from the last, and a circle
/// of radius `r` tangent to each, its centre at a given distance from the segment's start: the
/// centre where a line beside the segment meets a circle about its start (a branch variable
/// per circle).
pub fn circle_sketch(n: usize) -> String {
    let n = n.max(1);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// A sketch of {n} segments end to end, each with a tangent circle."
    );
    s.push_str("space 2d;\n\nparam r = 1;\n\n");
    s.push_str("fixed point origin = (0, 0);\nfixed vector X = (1, 0);\n");
    let mut at = (0.0f64, 0.0f64);
    for k in 0..n {
        circle_sketch_stage(&mut s, "s", k, &mut at);
    }
    let _ = writeln!(s, "\noutput s{}.end, c{};", n - 1, n - 1);
    s
}

/// Segment `{seg}{k}` of the circle sketch from `at` (moved to its end) and its circle `c{k}`.
fn circle_sketch_stage(s: &mut String, seg: &str, k: usize, at: &mut (f64, f64)) {
    let (x, y) = *at;
    let deg: f64 = if k.is_multiple_of(2) { 15.0 } else { -15.0 };
    let (dy, dx) = deg.to_radians().sin_cos();
    let (ex, ey) = (x + 4.0 * dx, y + 4.0 * dy);
    let _ = writeln!(
        s,
        "\nsegment {seg}{k} = ({x:.3}, {y:.3}) -> ({ex:.3}, {ey:.3});"
    );
    match k {
        0 => {
            let _ = writeln!(s, "coincident({seg}0.start, origin);");
        }
        _ => {
            let _ = writeln!(s, "coincident({seg}{k}.start, {seg}{}.end);", k - 1);
        }
    }
    let _ = writeln!(s, "angle(X, {seg}{k}) = {deg} deg;");
    let _ = writeln!(s, "length({seg}{k}) = 4;");
    // The circle above the segment, its centre 2 along and 1 beside it: at sqrt(5) from the
    // start.
    let (cx, cy) = (x + 2.0 * dx - dy, y + 2.0 * dy + dx);
    let _ = writeln!(
        s,
        "circle c{k} = center ({:.3}, {:.3}) radius 1.05;",
        cx + 0.02,
        cy - 0.03
    );
    let _ = writeln!(s, "radius(c{k}) = r;");
    let _ = writeln!(s, "tangent({seg}{k}, c{k});");
    let _ = writeln!(
        s,
        "distance(c{k}.center, {seg}{k}.start) = {:.17};",
        5f64.sqrt()
    );
    *at = (ex, ey);
}

/// `n` stages of every planar family (the chain of four-bars, the hung chain, the strip, the
/// truss, the sketch profile and the circle sketch), each stage's kind picked by a fixed
/// pseudo-random sequence and every kind's stages chained to its own: a large model no
/// generator's order repeats.
pub fn random_mix(n: usize) -> String {
    let n = n.max(6);
    let mut s = String::new();
    let _ = writeln!(s, "// {n} stages of six planar families, picked at random.");
    s.push_str(
        "space 2d;\n\nparam theta = 90 deg;\nparam bar = 2;\nparam len = 10;\nparam r = 2;\n\n",
    );
    // The chain of four-bars' crank turns by theta as the hung chain's does: one drive, two
    // cranks, and the four-bars' ground its own.
    s.push_str("fixed point P0 = (0, 0);\n");
    s.push_str(HUNG_HEAD);
    s.push_str(
        "body crank4 at (0, 0) { point a = (0, 0); point b = (1.5, 0); vector u = (1, 0); }\n\
         coincident(crank4.a, P0);\ndrive4: angle(X, crank4.u) = theta;\n",
    );
    let _ = writeln!(
        s,
        "fixed point t0 = (0, 0);\nfixed point t1 = (1, {:.17});",
        3f64.sqrt()
    );
    s.push_str("fixed point origin = (0, 0);\n");
    let (mut bars, mut hung, mut truss, mut sketch, mut circles) = (0, 0, 2, 0, 0);
    let mut at = (0.0f64, 0.0f64);
    let mut circle_at = (0.0f64, 0.0f64);
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    for k in 0..n {
        let kind = if k < 5 {
            k as u64
        } else {
            xorshift(&mut seed) % 5
        };
        match kind {
            0 => {
                bars += 1;
                // The four-bars hang on their own crank.
                four_bar_stage(&mut s, bars, "crank4");
            }
            1 => {
                hung += 1;
                hung_stage(&mut s, hung);
            }
            2 => {
                truss_stage(&mut s, "t", truss);
                truss += 1;
            }
            3 => {
                sketch_stage(&mut s, sketch, &mut at);
                sketch += 1;
            }
            _ => {
                // The circle sketch starts where the profile's origin is, its segments named
                // apart from the profile's.
                circle_sketch_stage(&mut s, "g", circles, &mut circle_at);
                circles += 1;
            }
        }
    }
    let _ = writeln!(
        s,
        "\noutput rocker{bars}.b, B{hung}, t{}, f{}, c{};",
        truss - 1,
        sketch - 1,
        circles - 1
    );
    s
}

/// The next of a fixed pseudo-random sequence (xorshift64): the same on every machine.
pub(crate) fn xorshift(seed: &mut u64) -> u64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    *seed
}

/// `n` params in groups of four, as a large model's table of inputs is (`n` rounded up to a
/// multiple of four): `p{4j}` sets the distance from point `q{j}` to `q{j+1}` along a fixed line,
/// `p{4j+1}` is read by the default of `p{4j+2}`, and `p{4j+2}` and `p{4j+3}` are never used,
/// so `gcs check` warns about half of them.
pub fn params(n: usize) -> String {
    let groups = n.max(1).div_ceil(4);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// {} params: a quarter set distances, a quarter feed other params, half are unused.",
        4 * groups
    );
    s.push_str("space 2d;\n\nfixed line axis = (0, 0) -> (1, 0);\nfixed point q0 = (0, 0);\n");
    for j in 0..groups {
        let k = 4 * j;
        let _ = writeln!(s, "\nparam p{k} = 1;");
        let _ = writeln!(s, "param p{} = 2;", k + 1);
        let _ = writeln!(s, "param p{} = p{} * 2;", k + 2, k + 1);
        let _ = writeln!(s, "param p{} = 3;", k + 3);
        let _ = writeln!(s, "point q{} = ({}.1, 0.1);", j + 1, j + 1);
        let _ = writeln!(s, "on(q{}, axis);", j + 1);
        let _ = writeln!(s, "distance(q{j}, q{}) = p{k};", j + 1);
    }
    s
}

/// `n` points in a row: `q0` fixed at the origin and each later point on a fixed line at
/// distance `gap` from the one before (the sketch a little off, on the far side). No `output`
/// statement, so `gcs solve --json` prints every point and verifies every constraint.
pub fn points(n: usize) -> String {
    let n = n.max(2);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// {n} points in a row along a fixed line, each `gap` from the one before."
    );
    s.push_str("space 2d;\n\nparam gap = 1;\n\nfixed line axis = (0, 0) -> (1, 0);\n");
    s.push_str("fixed point q0 = (0, 0);\n");
    for k in 1..n {
        let _ = writeln!(s, "\npoint q{k} = ({k}.1, 0.1);");
        let _ = writeln!(s, "on(q{k}, axis);");
        let _ = writeln!(s, "distance(q{}, q{k}) = gap;", k - 1);
    }
    s
}

/// A closed stair-step profile of `n` edges (at least 4, rounded up to even): from `P` it
/// climbs `(n - 2) / 2` steps (right 4, up 3), then runs left and down back to `P`. Every
/// segment is `horizontal` or `vertical`, every corner filleted by a circle of radius `r`
/// (`radius`, `on` both segments' ends, `tangent` to both), `L0.start` on the fixed point `P`,
/// and every edge's length given but the first's and the last's: the profile of SolveSpace's
/// and PlaneGCS's sketch benchmark. Its directions are all known once the segments are
/// turned, so its closure is linear in the slides and the two free lengths: one linear stage.
pub fn stair_profile(n: usize) -> String {
    stair_profile_sketched(n, &StairSketch::default())
}

/// How [`stair_profile_sketched`] writes its sketch and dimensions.
#[derive(Clone, Copy, Debug, Default)]
pub struct StairSketch {
    /// Every sketched point is moved by up to this much in x and in y (pseudo-randomly).
    pub jitter: f64,
    /// The seed of the moves.
    pub seed: u64,
    /// Whether the first and last edges' lengths are given too (consistent): two redundant
    /// constraints.
    pub closed: bool,
}

/// [`stair_profile`] with its sketch moved (as a user's drag leaves it) and, if asked, both
/// closing lengths given.
pub fn stair_profile_sketched(n: usize, how: &StairSketch) -> String {
    let steps = n.max(4).div_ceil(2) - 1;
    let (a, b, r) = (4.0, 3.0, 0.5);
    let mut corners = vec![(0.0f64, 0.0f64)];
    let (mut x, mut y) = (0.0, 0.0);
    for _ in 0..steps {
        x += a;
        corners.push((x, y));
        y += b;
        corners.push((x, y));
    }
    corners.push((0.0, y));
    let m = corners.len();
    let dir = |i: usize| {
        let (p, q) = (corners[i % m], corners[(i + 1) % m]);
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        let l = (dx * dx + dy * dy).sqrt();
        (dx / l, dy / l)
    };
    let mut seed = how.seed.wrapping_mul(2).wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut moved = |p: (f64, f64)| {
        let mut jitter = || {
            let u = (xorshift(&mut seed) >> 11) as f64 / (1u64 << 53) as f64;
            (2.0 * u - 1.0) * how.jitter
        };
        (p.0 + jitter(), p.1 + jitter())
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "// A closed stair-step profile of {m} edges, every corner filleted; its first and last\n\
         // lengths {}.",
        if how.closed {
            "given too (two redundant constraints)"
        } else {
            "left free: the profile closes them"
        }
    );
    s.push_str("space 2d;\n\nparam r = 0.5;\n");
    let start = (corners[0].0 + r * dir(0).0, corners[0].1 + r * dir(0).1);
    let _ = writeln!(s, "fixed point P = ({}, {});", start.0, start.1);
    for i in 0..m {
        let d = dir(i);
        let (p, q) = (corners[i], corners[(i + 1) % m]);
        let from = moved((p.0 + r * d.0, p.1 + r * d.1));
        let to = moved((q.0 - r * d.0, q.1 - r * d.1));
        let _ = writeln!(
            s,
            "segment L{i} = ({:.6}, {:.6}) -> ({:.6}, {:.6});",
            from.0, from.1, to.0, to.1
        );
    }
    for (i, corner) in corners.iter().enumerate() {
        // The fillet at corner i, between edge i - 1 and edge i.
        let (d0, d1) = (dir(i + m - 1), dir(i));
        let c = moved((
            corner.0 - r * d0.0 + r * d1.0,
            corner.1 - r * d0.1 + r * d1.1,
        ));
        let _ = writeln!(
            s,
            "circle F{i} = center ({:.6}, {:.6}) radius {r};",
            c.0, c.1
        );
    }
    s.push_str("coincident(L0.start, P);\n");
    for i in 0..m {
        let across = dir(i).1.abs() < 0.5;
        let p = (i + m - 1) % m;
        let _ = writeln!(
            s,
            "{}(L{i});\nradius(F{i}) = r;\non(L{p}.end, F{i}); on(L{i}.start, F{i}); \
             tangent(L{p}, F{i}); tangent(L{i}, F{i});",
            if across { "horizontal" } else { "vertical" }
        );
    }
    for i in 0..m {
        if (i == 0 || i + 1 == m) && !how.closed {
            continue;
        }
        let (p, q) = (corners[i], corners[(i + 1) % m]);
        let l = ((q.0 - p.0).powi(2) + (q.1 - p.1).powi(2)).sqrt() - 2.0 * r;
        let _ = writeln!(s, "length(L{i}) = {l};");
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn solve(text: &str) -> f64 {
        let (diags, model, _) = gcs_lang::load("family.gcs", text.as_bytes());
        let model = model.unwrap_or_else(|| panic!("{diags:?}\n{text}"));
        let analysis = crate::analyse(&model).expect("analysis");
        assert!(analysis.unsolved.is_empty(), "{text}");
        assert!(analysis.free_geoms().is_empty(), "{text}");
        let branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
        let s = crate::solve(&model, &analysis, &model.default_params(), &branches)
            .unwrap_or_else(|e| panic!("{e}\n{text}"));
        s.max_residual
    }

    #[test]
    fn every_family_is_well_constrained_and_solves_exactly() {
        for family in Family::ALL {
            for n in [1, 2, 5, 20] {
                let r = solve(&family.model(n));
                assert!(
                    r <= 1e-12 * (4.0 * n as f64 + 10.0),
                    "{} {n}: {r}",
                    family.name()
                );
            }
        }
    }

    #[test]
    fn names_round_trip() {
        for family in Family::ALL {
            assert_eq!(Family::named(family.name()), Some(family));
        }
        assert_eq!(Family::named("nope"), None);
    }
}
