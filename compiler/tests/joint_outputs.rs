//! Joint values named in `output` (`J.angle`, `J.travel`), solved by the interpreter: each
//! reported value equals the value measured here, with plain vector arithmetic, on the solved
//! markers the same solution reports (the angle from the first marker's x axis to the second's,
//! counter-clockwise about the first's z axis; the travel from the second marker's point to the
//! first's along its sliding axis), and a closed form of the mechanism written here from its
//! sketch's numbers: a slider-crank's stroke, a crank's drive, a collar's height, and a 3R
//! arm's joint angles from the forward kinematics of the pose it is asked to reach.

use gcs_compiler::solution::Solution;
use std::collections::BTreeSet;
use std::f64::consts::PI;

type V = [f64; 3];

fn sub(a: &[f64], b: &[f64]) -> V {
    let c = |i: usize| a.get(i).copied().unwrap_or(0.0) - b.get(i).copied().unwrap_or(0.0);
    [c(0), c(1), c(2)]
}
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}
fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn v3(a: &[f64]) -> V {
    sub(a, &[])
}

/// `a - b` as an angle: in (-pi, pi].
fn turn(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(2.0 * PI);
    if d > PI {
        d - 2.0 * PI
    } else {
        d
    }
}

/// A joint value the test measures: the output's name, and the constraint's two arguments.
struct Joint {
    output: &'static str,
    m1: &'static str,
    m2: &'static str,
}

const fn joint(output: &'static str, m1: &'static str, m2: &'static str) -> Joint {
    Joint { output, m1, m2 }
}

/// The value of `j` measured on the markers of `s`: in 3d, the angle about `m1.z` from `m1.x`
/// to `m2.x`, or the travel `(m1 - m2) . m2.z`; in 2d, the angle from `m1.x` to `m2.x`, or the
/// travel along `m2.x`. An angle of -pi is pi.
fn measured(s: &Solution, j: &Joint, d3: bool) -> f64 {
    let by = s.by_name();
    let p = |n: &str| by.point(n).unwrap_or_else(|| panic!("no point {n}"));
    let v = |n: &str| by.vector(n).unwrap_or_else(|| panic!("no vector {n}"));
    let slide = if d3 { "z" } else { "x" };
    if j.output.ends_with(".travel") {
        let axis = v(&format!("{}.{slide}", j.m2));
        return dot(&sub(p(j.m1), p(j.m2)), axis);
    }
    let (x1, x2) = (v3(v(&format!("{}.x", j.m1))), v3(v(&format!("{}.x", j.m2))));
    let (sin, cos) = if d3 {
        let z1 = v(&format!("{}.z", j.m1));
        (dot(&cross(x1, x2), z1), dot(&x1, &x2))
    } else {
        (x1[0] * x2[1] - x1[1] * x2[0], dot(&x1, &x2))
    };
    let a = sin.atan2(cos);
    if a == -PI {
        PI
    } else {
        a
    }
}

/// A model compiled, its plan pruned to its outputs as `gcs solve` prunes it.
struct Solver {
    compiled: gcs_compiler::pipeline::Compiled,
    plan: gcs_compiler::plan::Plan,
    scope: BTreeSet<gcs_lang::model::GeomId>,
}

impl Solver {
    fn new(text: &str) -> Solver {
        let compiled = gcs_compiler::compile("joints.gcs", text.as_bytes())
            .unwrap_or_else(|e| panic!("{e:?}"));
        let (plan, scope) = gcs_compiler::prune::prune(&compiled.model, &compiled.analysis.plan);
        Solver {
            compiled,
            plan,
            scope,
        }
    }

    /// The params with those named set.
    fn params(&self, set: &[(&str, f64)]) -> Vec<f64> {
        let model = &self.compiled.model;
        let mut params = model.default_params();
        for (name, value) in set {
            let i = (model.params.iter())
                .position(|(_, p)| p.name == *name)
                .unwrap_or_else(|| panic!("no param {name}"));
            params[i] = *value;
        }
        params
    }

    /// The solution on the sketch's branches at the params set.
    fn solve(&self, set: &[(&str, f64)]) -> Solution {
        let branches: Vec<usize> = self.plan.branches.iter().map(|b| b.default).collect();
        let params = self.params(set);
        gcs_compiler::solve_plan(
            &self.compiled.model,
            &self.plan,
            &self.scope,
            &params,
            &branches,
        )
        .unwrap_or_else(|e| panic!("{set:?}: {e}"))
    }
}

/// The value reported as `name`.
fn reported(s: &Solution, name: &str) -> f64 {
    s.by_name()
        .scalar(name)
        .unwrap_or_else(|| panic!("no scalar {name} among {:?}", s.scalars))
}

/// Each joint's reported value equals its value measured on the markers.
fn check_measured(s: &Solution, joints: &[Joint], d3: bool, at: &str) {
    for j in joints {
        let (got, want) = (reported(s, j.output), measured(s, j, d3));
        assert!(
            (got - want).abs() <= 1e-12 * (1.0 + want.abs()),
            "{at}: {} reported {got}, measured {want}",
            j.output
        );
    }
}

/// A 3d slider-crank (the spatial joints of `examples/slider_crank.gcs`, labelled) and a collar
/// on a cylindrical joint whose turn and height params set, with a point on the collar's axis.
const SPATIAL: &str = "space 3d;
fixed body ground { marker o = (0, 0, 0) z (0, 0, 1) x (1, 0, 0);
                    marker rail = (5, 0, 0) z (1, 0, 0) x (0, 1, 0);
                    marker axis = (0, 0, -3) z (0, 0, 1) x (1, 0, 0);
                    marker level = (0, 0, h - 3) z (0, 0, 1) x (1, 0, 0); }
param phi = 20 deg;
param theta = 40 deg;
param h = 0.7;
param d = 1.2;
body arm at (0, 0, 0) { marker o = (0, 0, 0) z (0, 0, 1) x (1, 0, 0);
                        marker tip = (3, 0, 0) z (0, 0, 1) x (1, 0, 0); }
body rod at (3, 0, 0) { marker a = (0, 0, 0) z (0, 0, 1) x (1, 0, 0);
                        marker b = (4, 0, 0) z (0, 0, 1) x (1, 0, 0); }
body slider at (7, 0, 0) { marker s = (0, 0, 0) z (1, 0, 0) x (0, 1, 0);
                           marker pin = (0, 0, 0) z (0, 0, 1) x (1, 0, 0); }
body collar at (0.1, 0.2, -2.7) { marker m = (0, 0, 0) z (0, 0, 1) x (1, 0, 0); }
point P = (0, 0, -1);
crank: revolute(arm.o, ground.o);
drive: offset_x(ground.o, arm.o) = phi;
revolute(arm.tip, rod.a);
pin: revolute(rod.b, slider.pin);
slide: prismatic(slider.s, ground.rail);
cyl: cylindrical(collar.m, ground.axis);
offset_x(ground.axis, collar.m) = theta;
in_plane(collar.m, ground.level);
in_line(P, ground.axis);
distance(P, collar.m) = d;
output crank.angle, drive.angle, pin.angle, slide.travel;
output cyl.angle, cyl.travel, in_line_P_ground_axis.travel;
";

const SPATIAL_JOINTS: [Joint; 7] = [
    joint("crank.angle", "arm.o", "ground.o"),
    joint("drive.angle", "ground.o", "arm.o"),
    joint("pin.angle", "rod.b", "slider.pin"),
    joint("slide.travel", "slider.s", "ground.rail"),
    joint("cyl.angle", "collar.m", "ground.axis"),
    joint("cyl.travel", "collar.m", "ground.axis"),
    joint("in_line_P_ground_axis.travel", "P", "ground.axis"),
];

#[test]
fn spatial_joint_values_are_measured_on_the_solved_markers() {
    let solver = Solver::new(SPATIAL);
    let mut solved = 0;
    for k in -12..12 {
        // Every 15 degrees but the half turn (where the sign of the angle is a rounding's).
        let phi = (f64::from(k) * 15.0 + 7.5).to_radians();
        let (theta, h, d) = (-phi * 1.3, 0.1 * f64::from(k), 1.0 + 0.05 * f64::from(k));
        let s = solver.solve(&[("phi", phi), ("theta", theta), ("h", h), ("d", d)]);
        let at = format!("phi = {phi}");
        check_measured(&s, &SPATIAL_JOINTS, true, &at);
        // The closed forms, from the sketch: a crank of 3 and a rod of 4 from the origin
        // along x, the rail's marker at x = 5; the collar's axis through (0, 0, -3), its
        // level h above, the point d above the collar.
        let stroke = 3.0 * phi.cos() + (16.0 - (3.0 * phi.sin()).powi(2)).sqrt();
        let want = [
            ("crank.angle", turn(-phi, 0.0)),
            ("drive.angle", turn(phi, 0.0)),
            ("pin.angle", (3.0 * phi.sin() / 4.0).asin()),
            ("slide.travel", stroke - 5.0),
            ("cyl.angle", turn(-theta, 0.0)),
            ("cyl.travel", h),
            ("in_line_P_ground_axis.travel", h + d),
        ];
        for (name, want) in want {
            let got = reported(&s, name);
            assert!(
                turn(got, want).abs() <= 1e-12 * (1.0 + want.abs()),
                "{at}: {name} is {got}, the closed form {want}"
            );
        }
        solved += 1;
    }
    assert_eq!(solved, 24);
}

/// Two slider-cranks on one crank in the plane: a point on a rail (`in_line`), and a slider
/// body on a second rail whose axis points the other way (`prismatic`).
const PLANAR: &str = "space 2d;
param phi = 30 deg;
param r = 1.5;
param l = 4;
fixed body ground {
    marker o = (0, 0) x (1, 0);
    marker rail = (0, 0) x (1, 0);
    marker back = (0, -1) x (-1, 0);
}
body crank { marker o = (0, 0) x (1, 0); marker tip = (r, 0) x (1, 0); }
point P = (5.2, 0);
body slider at (-3, -1) { marker s = (0, 0) x (-1, 0); }
pivot: revolute(crank.o, ground.o);
drive: offset_x(ground.o, crank.o) = phi;
in_line(P, ground.rail);
distance(crank.tip, P) = l;
slide: prismatic(slider.s, ground.back);
distance(crank.tip, slider.s) = l;
output pivot.angle, drive.angle, in_line_P_ground_rail.travel, slide.travel;
";

const PLANAR_JOINTS: [Joint; 4] = [
    joint("pivot.angle", "crank.o", "ground.o"),
    joint("drive.angle", "ground.o", "crank.o"),
    joint("in_line_P_ground_rail.travel", "P", "ground.rail"),
    joint("slide.travel", "slider.s", "ground.back"),
];

#[test]
fn planar_joint_values_are_measured_on_the_solved_markers() {
    let solver = Solver::new(PLANAR);
    for k in -12..12 {
        let phi = (f64::from(k) * 15.0 + 7.5).to_radians();
        let (r, l) = (1.5 + 0.02 * f64::from(k), 4.0);
        let s = solver.solve(&[("phi", phi), ("r", r), ("l", l)]);
        let at = format!("phi = {phi}");
        check_measured(&s, &PLANAR_JOINTS, false, &at);
        // The point slider right of the crank on the rail through the origin; the slider body
        // left of it on the rail one below, whose axis points to -x.
        let (c, sn) = (r * phi.cos(), r * phi.sin());
        let want = [
            ("pivot.angle", turn(-phi, 0.0)),
            ("drive.angle", turn(phi, 0.0)),
            ("in_line_P_ground_rail.travel", c + (l * l - sn * sn).sqrt()),
            ("slide.travel", -(c - (l * l - (sn + 1.0).powi(2)).sqrt())),
        ];
        for (name, want) in want {
            let got = reported(&s, name);
            assert!(
                turn(got, want).abs() <= 1e-12 * (1.0 + want.abs()),
                "{at}: {name} is {got}, the closed form {want}"
            );
        }
    }
}

/// The 3R arm of `examples/arm_3r.gcs` asked to reach the tip of its own forward kinematics
/// at joint angles `q`: one of its assemblies reports those angles. The yaw and shoulder are
/// written child marker first (their value is the parent's x axis seen from the child's:
/// minus the joint's turn), the elbow parent first (the turn itself).
const ARM: &str = "space 3d;
param tx = 0.7;
param ty = 0.2;
param tz = 0.6;
fixed body ground {
    marker base = (0, 0, 0) z (0, 0, 1) x (1, 0, 0);
    point target = (tx, ty, tz);
}
body base_link {
    marker yaw = (0, 0, 0) z (0, 0, 1) x (1, 0, 0);
    marker shoulder = (0, 0, 0.5) z (0, 1, 0) x (1, 0, 0);
}
body upper_arm {
    marker shoulder = (0, 0, 0.5) z (0, 1, 0) x (1, 0, 0);
    marker elbow = (0.3, 0, 0.9) z (0, 1, 0) x (1, 0, 0);
}
body forearm {
    marker elbow = (0.3, 0, 0.9) z (0, 1, 0) x (1, 0, 0);
    point tip = (0.7, 0, 0.6);
}
yaw: revolute(base_link.yaw, ground.base);
shoulder: revolute(upper_arm.shoulder, base_link.shoulder);
elbow: revolute(upper_arm.elbow, forearm.elbow);
coincident(forearm.tip, ground.target);
output yaw.angle, shoulder.angle, elbow.angle;
";

/// `p` turned by `angle` about the axis through `c` along the unit `axis` (Rodrigues).
fn turned(p: V, c: V, axis: V, angle: f64) -> V {
    let r = sub(&p, &c);
    let (s, co) = angle.sin_cos();
    let k = cross(axis, r);
    let along = dot(&axis, &r) * (1.0 - co);
    [0, 1, 2].map(|i| c[i] + r[i] * co + k[i] * s + axis[i] * along)
}

#[test]
fn an_arm_reports_the_joint_angles_of_the_pose_it_reaches() {
    let solver = Solver::new(ARM);
    let (model, plan) = (&solver.compiled.model, &solver.plan);
    let joints = [
        joint("yaw.angle", "base_link.yaw", "ground.base"),
        joint("shoulder.angle", "upper_arm.shoulder", "base_link.shoulder"),
        joint("elbow.angle", "upper_arm.elbow", "forearm.elbow"),
    ];
    let mut state = 0x5eed_1234_u64;
    let mut angle = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        ((state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * PI
    };
    for _ in 0..50 {
        let q = [angle(), angle(), angle()];
        // The forward kinematics of the sketch's joints: the elbow about y through
        // (0.3, 0, 0.9) turns the tip, the shoulder about y through (0, 0, 0.5) turns that,
        // the yaw about z through the origin turns that.
        let y = [0.0, 1.0, 0.0];
        let tip = turned([0.7, 0.0, 0.6], [0.3, 0.0, 0.9], y, q[2]);
        let tip = turned(tip, [0.0, 0.0, 0.5], y, q[1]);
        let tip = turned(tip, [0.0; 3], [0.0, 0.0, 1.0], q[0]);
        let params = solver.params(&[("tx", tip[0]), ("ty", tip[1]), ("tz", tip[2])]);
        let all = gcs_compiler::all::solve_all(model, plan, &solver.scope, &params, &[]);
        assert!(!all.solutions.is_empty(), "q = {q:?}: no solution");
        for s in &all.solutions {
            check_measured(s, &joints, true, &format!("q = {q:?}"));
        }
        let want = [turn(-q[0], 0.0), turn(-q[1], 0.0), turn(q[2], 0.0)];
        let found = all.solutions.iter().any(|s| {
            (joints.iter().zip(want)).all(|(j, w)| turn(reported(s, j.output), w).abs() < 1e-9)
        });
        assert!(
            found,
            "q = {q:?}: no assembly reports {want:?}; they report {:?}",
            (all.solutions.iter())
                .map(|s| joints.iter().map(|j| reported(s, j.output)).collect())
                .collect::<Vec<Vec<f64>>>()
        );
    }
}

/// A joint value is computed only when an output names it: the same mechanism without joint
/// outputs reports no joint scalar; one named twice is reported once; and `gcs solve --all`'s
/// whole plan reports the same value as the pruned one.
#[test]
fn joint_values_are_reported_only_when_named_and_once() {
    let without = PLANAR.replace(
        "output pivot.angle, drive.angle, in_line_P_ground_rail.travel, slide.travel;",
        "output slider.s;",
    );
    let s = Solver::new(&without).solve(&[]);
    assert!(
        s.scalars
            .iter()
            .all(|(n, _)| !n.ends_with(".angle") && !n.ends_with(".travel")),
        "{:?}",
        s.scalars
    );
    let twice = PLANAR.replace(
        "output pivot.angle,",
        "output slide.travel, pivot.angle, pivot.angle,",
    );
    let solver = Solver::new(&twice);
    let s = solver.solve(&[]);
    let names: Vec<&str> = s.scalars.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(
        names,
        [
            "slide.travel",
            "pivot.angle",
            "drive.angle",
            "in_line_P_ground_rail.travel"
        ]
    );
    let c = &solver.compiled;
    let whole = gcs_compiler::solve(&c.model, &c.analysis, &c.model.default_params(), &{
        (c.analysis.plan.branches.iter())
            .map(|b| b.default)
            .collect::<Vec<_>>()
    })
    .expect("solves");
    for (name, value) in &s.scalars {
        assert_eq!(reported(&whole, name), *value, "{name}");
    }
}
