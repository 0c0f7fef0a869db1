//! `weld(m1, m2)`: two markers' frames made one (LANGUAGE.md). A tool welded to a fixed
//! marker sketched elsewhere lands on it, point and axes; a tool welded to a turning arm follows
//! it; in the plane likewise. The plan is the one `coincident` + `offset_x(...) = 0` gives,
//! step for step, but for the sense of the z axes, which a weld does not read from the sketch.
//! Points and markers on two of them are refused.
//!
//! The expected poses are computed here from the models' sketch numbers (Rodrigues' rotation
//! of each body's frame), never read from the compiler's configuration or plan.

use gcs_compiler::plan::Plan;
use gcs_compiler::solution::Solution;
use gcs_compiler::{analyse, solve, verify};
use gcs_lang::model::GeomId;
use gcs_lang::Model;

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn scale(a: V, k: f64) -> V {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}
fn unit(a: V) -> V {
    scale(a, 1.0 / norm(a))
}

/// `v` turned by `angle` about the unit `axis` (Rodrigues).
fn rotate(v: V, axis: V, angle: f64) -> V {
    let k = unit(axis);
    let (s, c) = angle.sin_cos();
    add(
        add(scale(v, c), scale(cross(k, v), s)),
        scale(k, dot(k, v) * (1.0 - c)),
    )
}

fn load(text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load("weld.gcs", text.as_bytes());
    assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}");
    model.expect("a model")
}

fn solved(model: &Model, params: &[f64]) -> Solution {
    let a = analyse(model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}", a.unsolved);
    assert!(a.plan.defaults.is_empty(), "a weld needs no default");
    solve(model, &a, params, &[]).unwrap_or_else(|e| panic!("{e}"))
}

fn point(s: &Solution, name: &str) -> V {
    let p = s
        .by_name()
        .point(name)
        .unwrap_or_else(|| panic!("no point {name}"))
        .to_vec();
    [p[0], p[1], p.get(2).copied().unwrap_or(0.0)]
}

fn vector(s: &Solution, name: &str) -> V {
    let v = s
        .by_name()
        .vector(name)
        .unwrap_or_else(|| panic!("no vector {name}"))
        .to_vec();
    [v[0], v[1], v.get(2).copied().unwrap_or(0.0)]
}

/// Asserts `got` is `want` to 1e-12.
fn near(what: &str, got: V, want: V) {
    let off = norm(sub(got, want));
    assert!(off <= 1e-12, "{what}: {got:?}, not {want:?} ({off:e} off)");
}

/// The residual `verify` measures on the constraint named `name`, which must be at most 1e-12,
/// as must every other.
fn assert_met(model: &Model, s: &Solution, params: &[f64], name: &str) {
    let residuals = verify::residuals(model, s, params);
    let weld = residuals
        .iter()
        .find(|r| model.constraints[r.constraint].name == name)
        .unwrap_or_else(|| panic!("no constraint {name}"));
    assert!(weld.value <= 1e-12, "{name}: residual {:e}", weld.value);
    let max = verify::max_residual(&residuals);
    assert!(max <= 1e-12, "max residual {max:e}");
    assert!(s.max_residual <= 1e-12, "{}", s.max_residual);
}

/// Checks that the model `with` (a weld) and `without` (its coincidence and offset_x(0)) get
/// the same plan: the same features measured and the same geoms moved, by the same kinds of
/// action, in the same order, with no default, branch or redundancy; `without` has `more`
/// steps. And that the weld nominally removes as much as the two.
fn same_plan(with: &Model, without: &Model, more: usize) {
    let (a, b) = (
        analyse(with).expect("analysed"),
        analyse(without).expect("analysed"),
    );
    assert_eq!(a.plan.steps.len() + more, b.plan.steps.len(), "steps");
    let name = |m: &Model, g: GeomId| m.geoms[g].name.clone();
    let measured = |m: &Model, p: &Plan| -> Vec<String> {
        (p.steps.iter())
            .filter_map(|s| s.op.measures().map(|g| name(m, g)))
            .collect()
    };
    assert_eq!(measured(with, &a.plan), measured(without, &b.plan));
    let moved = |m: &Model, p: &Plan| -> Vec<(String, Vec<String>)> {
        (p.steps.iter())
            .filter(|s| !s.op.moves().is_empty())
            .map(|s| {
                let kind = format!("{:?}", s.op);
                let kind = kind.split([' ', '(', '{']).next().unwrap_or("").to_string();
                (kind, s.op.moves().iter().map(|&g| name(m, g)).collect())
            })
            .collect()
    };
    assert_eq!(moved(with, &a.plan), moved(without, &b.plan));
    for plan in [&a.plan, &b.plan] {
        assert!(plan.defaults.is_empty() && plan.iterations.is_empty());
        assert!(plan.branches.is_empty());
    }
    assert!(a.redundant.is_empty() && b.redundant.is_empty());
    let nominal = |m: &Model| -> usize {
        (m.constraints.iter())
            .map(|(id, _)| m.nominal_dof_removed(id))
            .sum()
    };
    assert_eq!(nominal(with), nominal(without));
}

/// A cell fixed at a pose turned 35 degrees about a skew axis and moved, its target marker
/// turned again in the cell; a tool sketched elsewhere, its marker's z axis along the tool's y
/// axis, in the sense `sense` (+1: the sketch has it in the target's z axis' sense, within 17
/// degrees; -1 opposite), welded (or, in `joint`, held otherwise) by it to the target.
fn tool_model(sense: f64, joint: &str) -> String {
    format!(
        "space 3d;
         fixed body cell at (1, -2, 0.5) rotated 35 deg about (1, 2, 3) {{
             marker target = (0.4, 1.2, -0.7) z (1, 1, 0) x (1, -1, 2);
         }}
         body tool at (5, 3, -1) rotated -20 deg about (0, 1, 0) {{
             marker m = (0.1, 0.2, 0.3) z (0, {sense}, 0) x (1, 0, 0);
             point tip = (0.5, 0, 1.5);
         }}
         {joint}"
    )
}

/// The target marker's point, z and x axes, from the cell's sketch numbers.
fn target() -> (V, V, V) {
    let (axis, angle) = ([1.0, 2.0, 3.0], 35f64.to_radians());
    let p = add([1.0, -2.0, 0.5], rotate([0.4, 1.2, -0.7], axis, angle));
    let z = rotate(unit([1.0, 1.0, 0.0]), axis, angle);
    let x = rotate(unit([1.0, -1.0, 2.0]), axis, angle);
    (p, z, x)
}

/// Checks that the tool of `tool_model(sense, ...)` sits on the target: its marker's point and
/// axes are the target's, and its tip where the target's frame takes the tip's offset from the
/// marker, (0.4, -0.2, 1.2) in the tool's frame: 0.4 along the marker's x axis (the tool's x),
/// `-1.2 sense` along its y axis (the tool's `-sense` z) and `-0.2 sense` along its z axis (the
/// tool's `sense` y). The whole tool has moved with its marker.
fn on_target(s: &Solution, sense: f64) {
    let (p, z, x) = target();
    near("tool.m", point(s, "tool.m"), p);
    near("tool.m.z", vector(s, "tool.m.z"), z);
    near("tool.m.x", vector(s, "tool.m.x"), x);
    let y = cross(z, x);
    let tip = add(
        add(add(p, scale(x, 0.4)), scale(y, -1.2 * sense)),
        scale(z, -0.2 * sense),
    );
    near("tool.tip", point(s, "tool.tip"), tip);
}

#[test]
fn a_tool_welded_to_a_marker_lands_on_its_frame() {
    let model = load(&tool_model(1.0, "weld(tool.m, cell.target);"));
    let s = solved(&model, &[]);
    on_target(&s, 1.0);
    assert_met(&model, &s, &[], "weld_tool_m_cell_target");
}

#[test]
fn a_weld_plans_as_its_coincidence_and_offset_x_0() {
    let weld = load(&tool_model(1.0, "weld(tool.m, cell.target);"));
    let spelt = load(&tool_model(
        1.0,
        "coincident(tool.m, cell.target);\n offset_x(tool.m, cell.target) = 0;",
    ));
    same_plan(&weld, &spelt, 0);
    // And they solve alike.
    let (a, b) = (solved(&weld, &[]), solved(&spelt, &[]));
    for name in ["tool.m", "tool.tip"] {
        near(name, point(&a, name), point(&b, name));
    }
    for name in ["tool.m.z", "tool.m.x"] {
        near(name, vector(&a, name), vector(&b, name));
    }
}

#[test]
fn a_weld_turns_z_axes_sketched_opposite_into_the_same_sense() {
    let model = load(&tool_model(-1.0, "weld(tool.m, cell.target);"));
    let s = solved(&model, &[]);
    on_target(&s, -1.0);
    assert_met(&model, &s, &[], "weld_tool_m_cell_target");
}

/// The welded tool of LANGUAGE.md, word for word: on an arm turning by `yaw` about the base's
/// z axis.
const ARM: &str =
    "// A tool welded to an arm's flange: their frames are one, and the tool turns with the arm.
space 3d;
fixed body base { marker m = (0, 0, 0) z (0, 0, 1) x (1, 0, 0); }
body arm { marker m = (0, 0, 0) z (0, 0, 1) x (1, 0, 0);
           marker flange = (2, 0, 1) z (1, 0, 0) x (0, 1, 0); }
body tool at (2.5, 0.4, 1) rotated 10 deg { marker m = (0, 0, 0) z (1, 0, 0) x (0, 1, 0);
                                            point tip = (0.3, 0, 0); }
param yaw = 30 deg;
revolute(arm.m, base.m);
offset_x(base.m, arm.m) = yaw;
weld(tool.m, arm.flange);
output tool.tip;
";

#[test]
fn a_tool_welded_to_a_turning_arm_follows_its_flange() {
    let docs = include_str!("../../docs/LANGUAGE.md");
    assert!(
        docs.contains(&format!("```gcs\n{ARM}```")),
        "LANGUAGE.md's block differs"
    );
    let model = load(ARM);
    for deg in [-170.0, -90.0, -30.0, 0.0, 30.0, 75.0, 180.0] {
        let yaw = f64::to_radians(deg);
        let s = solved(&model, &[yaw]);
        let turn = |v: V| rotate(v, [0.0, 0.0, 1.0], yaw);
        let (p, z, x) = (
            turn([2.0, 0.0, 1.0]),
            turn([1.0, 0.0, 0.0]),
            turn([0.0, 1.0, 0.0]),
        );
        near("tool.m", point(&s, "tool.m"), p);
        near("tool.m.z", vector(&s, "tool.m.z"), z);
        near("tool.m.x", vector(&s, "tool.m.x"), x);
        near("tool.tip", point(&s, "tool.tip"), add(p, scale(z, 0.3)));
        assert_met(&model, &s, &[yaw], "weld_tool_m_arm_flange");
    }
}

/// A ground whose seat is turned 30 degrees and moved, a part sketched elsewhere, welded (or
/// held otherwise) to it.
fn planar_model(joint: &str) -> String {
    format!(
        "space 2d;
         fixed body ground at (1, 2) rotated 30 deg {{ marker seat = (0.5, -0.3) x (0.6, 0.8); }}
         body part at (-3, 4) rotated -70 deg {{ marker m = (0.2, 0.1) x (1, 0);
                                                 point tip = (1.2, 0.6); }}
         {joint}"
    )
}

#[test]
fn a_part_welded_in_the_plane_lands_on_the_seat() {
    let model = load(&planar_model("weld(part.m, ground.seat);"));
    let s = solved(&model, &[]);
    let z = [0.0, 0.0, 1.0];
    let turn = |v: V| rotate(v, z, 30f64.to_radians());
    let p = add([1.0, 2.0, 0.0], turn([0.5, -0.3, 0.0]));
    let x = turn([0.6, 0.8, 0.0]);
    near("part.m", point(&s, "part.m"), p);
    near("part.m.x", vector(&s, "part.m.x"), x);
    // The tip's offset from the marker, (1, 0.5), along the seat's x and y.
    let tip = add(add(p, x), scale(cross(z, x), 0.5));
    near("part.tip", point(&s, "part.tip"), tip);
    assert_met(&model, &s, &[], "weld_part_m_ground_seat");
    // The weld's angle 0 is its own constant, where offset_x's is an expression: it turns the
    // part's x axis straight onto the seat's, not onto the seat's turned by minus the value.
    let spelt = load(&planar_model(
        "coincident(part.m, ground.seat);\n offset_x(part.m, ground.seat) = 0;",
    ));
    same_plan(&model, &spelt, 2);
}

#[test]
fn a_weld_of_points_is_refused() {
    for (text, noun) in [
        (
            "space 3d;\npoint p = (0, 0, 0);\npoint q = (1, 0, 0);\nweld(p, q);\n",
            "`p` is a point",
        ),
        (
            "space 2d;\nbody B { marker m = (0, 0) x (1, 0); }\npoint q = (1, 0);\nweld(B.m, q);\n",
            "`q` is a point",
        ),
    ] {
        let (source, model, diags) = gcs_lang::load("weld.gcs", text.as_bytes());
        assert!(model.is_none(), "{text}");
        let shown = gcs_lang::diagnostic::render_plain(&source, &diags);
        assert!(
            shown.contains("error: expected a marker, found a point") && shown.contains(noun),
            "{shown}"
        );
        assert!(
            shown.contains("`weld` accepts a marker and a marker"),
            "{shown}"
        );
    }
}

#[test]
fn the_verifier_measures_a_planar_weld_by_its_worst_condition() {
    let model = load(&planar_model("w: weld(part.m, ground.seat);"));
    let frame = |m: [f64; 2], x: f64| Solution {
        points: vec![
            ("ground.seat".into(), vec![1.0, 2.0]),
            ("part.m".into(), m.to_vec()),
        ],
        vectors: vec![
            ("ground.seat.x".into(), vec![0.6, 0.8]),
            (
                "part.m.x".into(),
                vec![x.cos() * 0.6 - x.sin() * 0.8, x.sin() * 0.6 + x.cos() * 0.8],
            ),
        ],
        ..Default::default()
    };
    let wd = |s: &Solution| {
        let r = verify::residuals(&model, s, &[]);
        let w = r
            .iter()
            .find(|r| model.constraints[r.constraint].name == "w");
        w.expect("w").value
    };
    let close = |got: f64, want: f64| assert!((got - want).abs() <= 1e-12, "{got} not {want}");
    close(wd(&frame([1.0, 2.0], 0.0)), 0.0);
    close(wd(&frame([1.3, 2.4], 0.0)), 0.5);
    close(wd(&frame([1.0, 2.0], -0.25)), 0.25);
    close(wd(&frame([1.3, 2.4], 0.7)), 0.7);
    close(
        wd(&frame([1.0, 2.0], std::f64::consts::PI)),
        std::f64::consts::PI,
    );
    let mut s = frame([1.0, 2.0], 0.0);
    s.vectors.pop();
    assert!(wd(&s).is_nan(), "a missing axis fails");
    let mut s = frame([1.0, 2.0], 0.0);
    s.points.pop();
    assert!(wd(&s).is_nan(), "a missing point fails");
}
