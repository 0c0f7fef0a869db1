//! Spatial models solved by their plans (issue 20): Kramer's brick from random starting
//! sketches, the spatial slider-crank against the planar one, and sweeps of the spherical
//! four-bar and the RSSR over the crank's turn in 1-degree steps, each step checked against an
//! independent closed form written here (the rocker's angle where its circle meets the
//! coupler's sphere), with no flip of assembly and every constraint re-measured by `verify`.
//!
//! The closed forms read only the model's sketch numbers given below, never the compiler's
//! configuration or plan.

use gcs_compiler::{analyse, solve};
use gcs_lang::Model;

type V = [f64; 3];

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn norm(a: V) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

fn load_text(name: &str, text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load(name, text.as_bytes());
    assert!(diags.iter().all(|d| !d.is_error()), "{name}: {diags:?}");
    model.unwrap_or_else(|| panic!("{name}: no model"))
}

fn example(name: &str) -> Model {
    let path = format!("{}/../examples/{name}.gcs", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    load_text(&format!("{name}.gcs"), &text)
}

fn param(model: &Model, name: &str) -> usize {
    (model.params.iter())
        .position(|(_, p)| p.name == name)
        .unwrap_or_else(|| panic!("no param {name}"))
}

fn point(s: &gcs_compiler::solution::Solution, name: &str) -> V {
    let p = &(s.points.iter())
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no point {name}"))
        .1;
    [p[0], p[1], p.get(2).copied().unwrap_or(0.0)]
}

/// A tiny deterministic generator (xorshift), so the random sketches are the same each run.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

#[test]
fn the_brick_lands_on_its_three_points_from_random_sketches() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for trial in 0..50 {
        let at = [
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
            rng.range(-20.0, 20.0),
        ];
        let axis = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let angle = rng.range(-180.0, 180.0);
        let text = format!(
            "space 3d;\nfixed point g1 = (0, 0, 0);\nfixed point g2 = (4, 0, 0);\nfixed point g3 = (0, 3, 0);\n\
             body brick at ({}, {}, {}) rotated {angle} deg about ({}, {}, {}) {{\n\
             point b1 = (0, 0, 0);\npoint b2 = (4, 0, 0);\npoint b3 = (0, 3, 0);\n}}\n\
             coincident(brick.b1, g1);\ncoincident(brick.b2, g2);\ncoincident(brick.b3, g3);\n",
            at[0], at[1], at[2], axis[0], axis[1], axis[2]
        );
        let model = load_text("brick.gcs", &text);
        let a = analyse(&model).expect("analysed");
        assert!(a.unsolved.is_empty(), "trial {trial}: {:?}", a.unsolved);
        let s = solve(&model, &a, &[], &[]).unwrap_or_else(|e| panic!("trial {trial}: {e}"));
        for (b, g) in [
            ("brick.b1", [0.0, 0.0, 0.0]),
            ("brick.b2", [4.0, 0.0, 0.0]),
            ("brick.b3", [0.0, 3.0, 0.0]),
        ] {
            let off = norm(sub(point(&s, b), g));
            assert!(off <= 1e-12 * 30.0, "trial {trial}: {b} is {off:e} off");
        }
        assert!(
            s.max_residual <= 1e-12 * 30.0,
            "trial {trial}: {}",
            s.max_residual
        );
    }
}

#[test]
fn the_spatial_slider_crank_is_the_planar_one() {
    let spatial = example("slider_crank");
    let a3 = analyse(&spatial).expect("analysed");
    assert!(a3.unsolved.is_empty(), "{:?}", a3.unsolved);
    // The planar example with the spatial one's crank and rod.
    let planar = example("slider_crank_2d");
    let a2 = analyse(&planar).expect("analysed");
    let mut p2 = planar.default_params();
    p2[param(&planar, "crank_len")] = 3.0;
    p2[param(&planar, "rod_len")] = 4.0;
    let b3: Vec<usize> = a3.plan.branches.iter().map(|b| b.default).collect();
    let b2: Vec<usize> = a2.plan.branches.iter().map(|b| b.default).collect();
    let (phi3, phi2) = (param(&spatial, "phi"), param(&planar, "phi"));
    for step in 0..360 {
        let phi = (step as f64).to_radians();
        let mut p3 = spatial.default_params();
        p3[phi3] = phi;
        p2[phi2] = phi;
        let s3 = solve(&spatial, &a3, &p3, &b3).unwrap_or_else(|e| panic!("{step} deg: {e}"));
        let s2 = solve(&planar, &a2, &p2, &b2).unwrap_or_else(|e| panic!("{step} deg, 2d: {e}"));
        let (x3, x2) = (point(&s3, "slider.s"), point(&s2, "slider.s"));
        // The closed form: the slider on the rail at a cos(phi) + sqrt(b^2 - (a sin(phi))^2).
        let x = 3.0 * phi.cos() + (16.0 - (3.0 * phi.sin()).powi(2)).sqrt();
        assert!(
            norm(sub(x3, x2)) <= 1e-12 * 7.0 && (x3[0] - x).abs() <= 1e-12 * 7.0,
            "{step} deg: 3d {x3:?}, 2d {x2:?}, closed form {x}"
        );
        assert!(
            x3[1].abs() + x3[2].abs() <= 1e-12,
            "{step} deg: off the rail {x3:?}"
        );
    }
}

/// A point on the circle about `centre` of radius `r` spanned by unit `e1` and `e2` (at angle
/// `psi` from `e1` towards `e2`) at distance `len` from `p`: the angles `psi` of both roots,
/// from `a cos + b sin = c`.
fn circle_sphere_angles(centre: V, r: f64, e1: V, e2: V, p: V, len: f64) -> [f64; 2] {
    let w = sub(centre, p);
    let dot = |a: V, b: V| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // |w + r (cos e1 + sin e2)|^2 = len^2
    let a = 2.0 * r * dot(w, e1);
    let b = 2.0 * r * dot(w, e2);
    let c = len * len - dot(w, w) - r * r;
    let base = b.atan2(a);
    let spread = (c / a.hypot(b)).clamp(-1.0, 1.0).acos();
    [base + spread, base - spread]
}

fn on_circle(centre: V, r: f64, e1: V, e2: V, psi: f64) -> V {
    let (s, c) = psi.sin_cos();
    [
        centre[0] + r * (c * e1[0] + s * e2[0]),
        centre[1] + r * (c * e1[1] + s * e2[1]),
        centre[2] + r * (c * e1[2] + s * e2[2]),
    ]
}

/// Sweeps `input` over a turn in 1-degree steps on each branch: where the linkage assembles,
/// the rocker's tip is one of the two closed-form roots, the same one all along (no flip), and
/// every constraint holds to 1e-12 of the model's size. Returns the steps that assembled.
#[allow(clippy::too_many_arguments)]
fn sweep(
    name: &str,
    input: &str,
    crank_tip: impl Fn(f64) -> V,
    rocker: (V, f64, V, V),
    coupler_len: f64,
    tip: &str,
    size: f64,
) -> usize {
    let model = example(name);
    let a = analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{name}: {:?}", a.unsolved);
    assert_eq!(
        a.plan.branches.iter().filter(|b| b.count == 2).count(),
        1,
        "{name}"
    );
    let k = param(&model, input);
    let (centre, r, e1, e2) = rocker;
    let mut assembled = 0;
    for branch in 0..2 {
        let mut root: Option<usize> = None;
        for step in 0..360 {
            let theta = (step as f64).to_radians();
            let mut params = model.default_params();
            params[k] = theta;
            let branches: Vec<usize> = a
                .plan
                .branches
                .iter()
                .map(|b| if b.count == 2 { branch } else { 0 })
                .collect();
            let Ok(s) = solve(&model, &a, &params, &branches) else {
                continue;
            };
            assembled += 1;
            assert!(
                s.max_residual <= 1e-12 * size,
                "{name} {step} deg: residual {:e}",
                s.max_residual
            );
            let got = point(&s, tip);
            let roots = circle_sphere_angles(centre, r, e1, e2, crank_tip(theta), coupler_len)
                .map(|psi| on_circle(centre, r, e1, e2, psi));
            let (i, off) = (0..2)
                .map(|i| (i, norm(sub(got, roots[i]))))
                .min_by(|x, y| x.1.total_cmp(&y.1))
                .expect("two roots");
            assert!(off <= 1e-11 * size, "{name} branch {branch}, {step} deg: {tip} {got:?} is {off:e} from both roots {roots:?}");
            // Away from the dead points (roots apart), the branch keeps its root.
            if norm(sub(roots[0], roots[1])) > 1e-3 * size {
                match root {
                    None => root = Some(i),
                    Some(j) => assert_eq!(i, j, "{name} branch {branch} flipped at {step} deg"),
                }
            }
        }
    }
    assembled
}

#[test]
fn the_rssr_sweeps_its_crank_on_both_branches_without_a_flip() {
    let assembled = sweep(
        "rssr",
        "theta",
        |t| [t.cos(), t.sin(), 0.0],
        // The rocker turns about the y axis through (4, 1, 1); its tip 2 from it.
        ([4.0, 1.0, 1.0], 2.0, [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        19f64.sqrt(),
        "rocker.tip",
        8.0,
    );
    assert_eq!(
        assembled, 720,
        "the RSSR is a crank-rocker: it assembles at every angle"
    );
}

#[test]
fn the_spherical_fourbar_sweeps_its_crank_on_both_branches_without_a_flip() {
    let h = 0.5f64.sqrt();
    let sketch_b = [h, 0.5, 0.5];
    let coupler = norm(sub(sketch_b, [0.6, 0.0, 0.8]));
    let assembled = sweep(
        "spherical_fourbar",
        "theta",
        |t| [0.6 * t.cos(), 0.6 * t.sin(), 0.8],
        // The rocker turns about the x axis: its tip on the circle at x = h, radius h.
        ([h, 0.0, 0.0], h, [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
        coupler,
        "rocker.tip",
        2.0,
    );
    assert!(assembled > 0, "the spherical four-bar never assembles");
}

fn vector(s: &gcs_compiler::solution::Solution, name: &str) -> V {
    let v = &(s.vectors.iter())
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no vector {name}"))
        .1;
    [v[0], v[1], v[2]]
}

/// The angle from `u` to `v` about `axis`, counter-clockwise.
fn angle_about(u: V, v: V, axis: V) -> f64 {
    let c = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    let dot = |a: V, b: V| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    dot(c, axis).atan2(dot(u, v))
}

fn wrapped(a: f64) -> f64 {
    let t = a.rem_euclid(std::f64::consts::TAU);
    if t > std::f64::consts::PI {
        t - std::f64::consts::TAU
    } else {
        t
    }
}

#[test]
fn the_bennett_linkage_moves_by_its_closed_form_with_its_redundant_constraints_held() {
    let model = example("bennett");
    let a = analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}", a.unsolved);
    let k = param(&model, "theta");
    let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let (alpha, beta) = (30f64.to_radians(), 60f64.to_radians());
    let ratio = ((beta + alpha) / 2.0).sin() / ((beta - alpha) / 2.0).sin();
    let mut solved = 0;
    for step in 1..360 {
        let theta1 = (step as f64).to_radians();
        let mut params = model.default_params();
        params[k] = theta1;
        let s = solve(&model, &a, &params, &branches).unwrap_or_else(|e| panic!("{step} deg: {e}"));
        solved += 1;
        assert!(
            s.max_residual <= 1e-12 * 4.0,
            "{step} deg: residual {:e}",
            s.max_residual
        );
        // The joint angles, measured on the solution, against Bennett's closed form.
        let angle = |from: &str, to: &str, axis: &str| {
            angle_about(vector(&s, from), vector(&s, to), vector(&s, axis))
        };
        let theta2 = angle("crank.end.x", "coupler.start.x", "coupler.start.z");
        let theta3 = angle("coupler.end.x", "rocker.start.x", "rocker.start.z");
        let theta4 = angle("rocker.end.x", "ground.j4.x", "ground.j4.z");
        let expected2 = 2.0 * (ratio / (theta1 / 2.0).tan()).atan();
        for (what, got, want) in [
            ("theta2", theta2, expected2),
            ("theta3", theta3, -theta1),
            ("theta4", theta4, -expected2),
        ] {
            let off = wrapped(got - want).abs();
            assert!(
                off <= 1e-12,
                "{step} deg: {what} {got} against {want} ({off:e})"
            );
        }
    }
    assert_eq!(solved, 359);
}

#[test]
fn the_screw_jack_turns_its_screw_by_its_lift() {
    let model = example("screw_jack");
    let a = analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}", a.unsolved);
    assert!(
        a.plan.iterations.is_empty(),
        "the screw jack is in closed form"
    );
    let (k, pitch) = (param(&model, "lift"), 0.5);
    let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    for step in 0..=100 {
        let lift = 2.05 + 0.005 * step as f64;
        let mut params = model.default_params();
        params[k] = lift;
        let s =
            solve(&model, &a, &params, &branches).unwrap_or_else(|e| panic!("lift {lift}: {e}"));
        assert!(
            s.max_residual <= 1e-12 * 4.0,
            "lift {lift}: residual {:e}",
            s.max_residual
        );
        // The screw's top at the lift, its thread 2 below, turned by the advance's share of
        // a turn from the nut's x axis; the platform on top, not turning.
        let thread = point(&s, "screw.thread");
        let advance = lift - 2.0;
        assert!(
            norm(sub(thread, [0.0, 0.0, advance])) <= 1e-12 * 4.0,
            "lift {lift}: {thread:?}"
        );
        let turn = angle_about(
            [1.0, 0.0, 0.0],
            vector(&s, "screw.thread.x"),
            [0.0, 0.0, 1.0],
        );
        let want = std::f64::consts::TAU * advance / pitch;
        assert!(
            wrapped(turn - want).abs() <= 1e-12,
            "lift {lift}: turned {turn}, want {want}"
        );
        let corner = point(&s, "platform.corner");
        assert!(
            norm(sub(corner, [1.0, 1.0, lift + 0.2])) <= 1e-12 * 4.0,
            "lift {lift}: {corner:?}"
        );
    }
}

#[test]
fn the_door_swings_to_its_angle_on_either_side_of_the_wall_normal() {
    let model = example("door");
    let a = analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}", a.unsolved);
    let k = param(&model, "open");
    for branch in 0..2 {
        let mut side = None;
        for step in 5..=175 {
            let open = (step as f64).to_radians();
            let mut params = model.default_params();
            params[k] = open;
            let s =
                solve(&model, &a, &params, &[branch]).unwrap_or_else(|e| panic!("{step} deg: {e}"));
            assert!(
                s.max_residual <= 1e-12,
                "{step} deg: residual {:e}",
                s.max_residual
            );
            let n = vector(&s, "door.normal.z");
            // The face's normal at the angle from the wall's x axis, in the hinge's plane.
            assert!(
                (n[0] - open.cos()).abs() <= 1e-13 && n[2].abs() <= 1e-13,
                "{step} deg: {n:?}"
            );
            // One side of the wall's normal on each branch, all along.
            let this = n[1] > 0.0;
            assert_eq!(
                *side.get_or_insert(this),
                this,
                "branch {branch} flipped at {step} deg"
            );
            // The knob keeps its height and its distance from the hinge.
            let knob = point(&s, "door.knob");
            assert!(
                (knob[2] - 1.0).abs() <= 1e-13
                    && (knob[0].hypot(knob[1]) - 0.65f64.sqrt()).abs() <= 1e-13
            );
        }
        assert_eq!(
            side,
            Some(branch == 0),
            "branch 0 turns counter-clockwise about z"
        );
    }
}

/// The rotation by `angle` about unit `axis` applied to `p` (Rodrigues), for target poses.
fn rotate(axis: V, angle: f64, p: V) -> V {
    let n = norm(axis);
    let k = [axis[0] / n, axis[1] / n, axis[2] / n];
    let (s, c) = angle.sin_cos();
    let kxp = [
        k[1] * p[2] - k[2] * p[1],
        k[2] * p[0] - k[0] * p[2],
        k[0] * p[1] - k[1] * p[0],
    ];
    let kp = k[0] * p[0] + k[1] * p[1] + k[2] * p[2];
    [0, 1, 2].map(|i| p[i] * c + kxp[i] * s + k[i] * kp * (1.0 - c))
}

#[test]
fn the_stewart_platform_iterates_to_the_pose_its_legs_measure() {
    let model = example("stewart");
    let a = analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}", a.unsolved);
    assert_eq!(
        a.plan.iterations.len(),
        1,
        "no closed form: one outer iteration"
    );
    let base = [
        [2.0, 0.0, 0.0],
        [1.0, 1.732, 0.0],
        [-1.0, 1.732, 0.0],
        [-2.0, 0.0, 0.0],
        [-1.0, -1.732, 0.0],
        [1.0, -1.732, 0.0],
    ];
    let local = [
        [1.0, 0.2, 0.0],
        [0.3, 1.0, 0.0],
        [-0.3, 1.0, 0.0],
        [-1.0, 0.2, 0.0],
        [-0.7, -0.8, 0.0],
        [0.7, -0.8, 0.0],
    ];
    let legs: Vec<usize> = (1..=6).map(|i| param(&model, &format!("l{i}"))).collect();
    let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    // Poses near the sketch's (at (0, 0, 3), unturned): their legs' lengths, then the solve.
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for trial in 0..20 {
        let axis = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let angle = rng.range(-12.0, 12.0).to_radians();
        let t = [
            rng.range(-0.3, 0.3),
            rng.range(-0.3, 0.3),
            3.0 + rng.range(-0.3, 0.3),
        ];
        let at: Vec<V> = local
            .iter()
            .map(|&p| {
                let q = rotate(axis, angle, p);
                [q[0] + t[0], q[1] + t[1], q[2] + t[2]]
            })
            .collect();
        let mut params = model.default_params();
        for i in 0..6 {
            params[legs[i]] = norm(sub(at[i], base[i]));
        }
        let s =
            solve(&model, &a, &params, &branches).unwrap_or_else(|e| panic!("trial {trial}: {e}"));
        assert!(
            s.max_residual <= 1e-12 * 4.0,
            "trial {trial}: residual {:e}",
            s.max_residual
        );
        for (i, want) in at.iter().enumerate() {
            let got = point(&s, &format!("platform.p{}", i + 1));
            assert!(
                norm(sub(got, *want)) <= 1e-11,
                "trial {trial}: p{} at {got:?}, the pose has it at {want:?}",
                i + 1
            );
        }
    }
}

#[test]
fn a_free_tetrahedron_is_solved_up_to_a_rigid_motion_by_its_edges() {
    let model = example("tetrahedron");
    let a = analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}", a.unsolved);
    assert!(a.plan.grounded.is_some() && a.plan.grounded_plane.is_some());
    let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    // The constraints' values are numbers: the tetrahedron is regular, of edge 3. Its solve
    // keeps a where sketched, b on the sketched ray from a, c in the sketched plane.
    let s = solve(&model, &a, &[], &branches).expect("solves");
    assert!(s.max_residual <= 1e-12 * 3.0, "{}", s.max_residual);
    let (pa, pb, pc, pd) = (
        point(&s, "a"),
        point(&s, "b"),
        point(&s, "c"),
        point(&s, "d"),
    );
    assert_eq!(pa, [0.0, 0.0, 0.0]);
    let ray = [3.0, 0.2, 0.1];
    let along = norm(ray);
    for i in 0..3 {
        assert!((pb[i] - 3.0 * ray[i] / along).abs() <= 1e-13, "b {pb:?}");
    }
    let n = [
        ray[1] * -0.2 - 0.1 * 2.6,
        0.1 * 1.2 - 3.0 * -0.2,
        3.0 * 2.6 - 0.2 * 1.2,
    ];
    let off = (n[0] * pc[0] + n[1] * pc[1] + n[2] * pc[2]) / norm(n);
    assert!(off.abs() <= 1e-13, "c is {off:e} off the sketched plane");
    // d on the sketch's side of that plane.
    assert!(n[0] * pd[0] + n[1] * pd[1] + n[2] * pd[2] > 0.0);
}

/// Hoffmann and Vermeer's points and planes (004), counted independently: with `P3` the plane
/// z = 0 and `p1` its origin (a rigid motion), `p2` = (3, 0, 4) (the turn about `P3`'s
/// normal), `p5` on its circle x² + y² = 8 at z = 2 by an angle `theta`; `P4`'s normal `n`
/// from `n . p2 = 9/5`, `n . p5 = 14/5`, `|n| = 1` (two or none); `p6` at z = 1 with
/// `n . p6 = 22/5` and `|p6 - p2|² = 19` (two or none); and the last constraint's error
/// `|p6 - p5|² - 18` scanned over a turn of `theta` on each of the four branches. Its sign
/// changes are the real solutions, up to a rigid motion (mirror images counted apart).
fn points_planes_count() -> usize {
    type W = [f64; 3];
    let dot = |a: W, b: W| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let cross = |a: W, b: W| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let p2 = [3.0, 0.0, 4.0];
    // The error on branch (i, j) at theta, if the construction exists there.
    let error = |theta: f64, i: usize, j: usize| -> Option<f64> {
        let p5 = [8f64.sqrt() * theta.cos(), 8f64.sqrt() * theta.sin(), 2.0];
        // n = a p2 + b p5 + t (p2 x p5), the first two from the two dot products.
        let (g11, g12, g22) = (dot(p2, p2), dot(p2, p5), dot(p5, p5));
        let det = g11 * g22 - g12 * g12;
        let (c1, c2) = (9.0 / 5.0, 14.0 / 5.0);
        let a = (c1 * g22 - c2 * g12) / det;
        let b = (c2 * g11 - c1 * g12) / det;
        let base = [0, 1, 2].map(|k| a * p2[k] + b * p5[k]);
        let w = cross(p2, p5);
        let t2 = (1.0 - dot(base, base)) / dot(w, w);
        if t2 < 0.0 {
            return None;
        }
        let t = if i == 0 { t2.sqrt() } else { -t2.sqrt() };
        let n = [0, 1, 2].map(|k| base[k] + t * w[k]);
        // p6 = (x, y, 1): n0 x + n1 y = 22/5 - n2, and (x - 3)² + y² = 19 - 9.
        let rhs = 22.0 / 5.0 - n[2];
        let h = n[0].hypot(n[1]);
        let (u0, u1) = (n[0] / h, n[1] / h);
        // The line: foot f = u rhs / h, direction (-u1, u0); its distance to (3, 0).
        let f = [u0 * rhs / h, u1 * rhs / h];
        let s = (f[0] - 3.0) * -u1 + f[1] * u0;
        let perp2 = (f[0] - 3.0).powi(2) + f[1].powi(2) - s * s;
        let along2 = 10.0 - perp2;
        if along2 < 0.0 {
            return None;
        }
        let tt = -s
            + if j == 0 {
                along2.sqrt()
            } else {
                -along2.sqrt()
            };
        let p6 = [f[0] - u1 * tt, f[1] + u0 * tt, 1.0];
        let d = [p6[0] - p5[0], p6[1] - p5[1], p6[2] - p5[2]];
        Some(dot(d, d) - 18.0)
    };
    let steps = 200_000;
    let mut roots = 0;
    for i in 0..2 {
        for j in 0..2 {
            let mut last: Option<f64> = None;
            for k in 0..=steps {
                let theta = std::f64::consts::TAU * k as f64 / steps as f64;
                let e = error(theta, i, j);
                if let (Some(a), Some(b)) = (last, e) {
                    if a == 0.0 || (a < 0.0) != (b < 0.0) {
                        roots += 1;
                    }
                }
                last = e;
            }
        }
    }
    roots
}

#[test]
fn points_and_planes_have_every_real_solution_and_no_other() {
    let model = example("points_planes");
    let a = analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}", a.unsolved);
    // One angle is iterated: the search scans it over a turn, and is complete.
    assert_eq!(a.plan.iterations.len(), 1);
    let all: std::collections::BTreeSet<_> = model.top_level().map(|(g, _)| g).collect();
    let found = gcs_compiler::all::solve_all(
        &model,
        &a.plan,
        &all,
        &model.default_params(),
        &a.plan.sketch_defaults(),
    );
    assert!(found.complete);
    for s in &found.solutions {
        assert!(
            s.max_residual <= 1e-12 * 10.0,
            "residual {:e}",
            s.max_residual
        );
    }
    assert_eq!(found.solutions.len(), points_planes_count());
}

/// A segment with one end on a plane and the other on the same plane or a parallel one (a
/// signed distance from it), from random sketches: the second end is reached by turning the
/// segment about the first, which keeps its plane, and the segment is then left free to slide
/// on the plane and turn about its normal, its defaults (length, that turn, the held end's two
/// coordinates) the four DOF the two constraints leave. Before, the turn was left to defaults
/// and the second end's locus, the first's plane moved with it, met the other plane only in
/// itself: refused as degenerate. Every solve, at the sketch's defaults and at random others,
/// is judged by `verify`, and by each end's signed distance from the plane computed here.
#[test]
fn a_segment_with_both_ends_on_parallel_planes_turns_about_their_normal() {
    let mut rng = Rng(0x1f83_d9ab_fb41_bd6b);
    for trial in 0..60 {
        let n = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        let offset = rng.range(-5.0, 5.0);
        // Every third on the plane itself, the others at a distance from it.
        let p: Vec<f64> = (0..6).map(|_| rng.range(-8.0, 8.0)).collect();
        // Within the sketch's length, which the length default starts from.
        let reach = 0.8 * norm(sub([p[0], p[1], p[2]], [p[3], p[4], p[5]]));
        let h = if trial % 3 == 0 {
            0.0
        } else {
            rng.range(-reach, reach)
        };
        let (first, second) = if trial % 2 == 0 {
            ("start", "end")
        } else {
            ("end", "start")
        };
        let text = format!(
            "space 3d;\nfixed plane P = normal ({}, {}, {}) offset {offset};\n\
             segment S = ({}, {}, {}) -> ({}, {}, {});\n\
             on(S.{first}, P);\ndistance(S.{second}, P) = {h};\n",
            n[0], n[1], n[2], p[0], p[1], p[2], p[3], p[4], p[5]
        );
        let model = load_text("parallel.gcs", &text);
        let a = analyse(&model).expect("analysed");
        assert!(
            a.unsolved.is_empty(),
            "trial {trial}: {:?}\n{text}",
            a.unsolved
        );
        assert_eq!(a.free_defaults().len(), 4, "trial {trial}\n{text}");
        let unit = {
            let l = norm(n);
            [n[0] / l, n[1] / l, n[2] / l]
        };
        let height = |x: V| x[0] * unit[0] + x[1] * unit[1] + x[2] * unit[2] - offset;
        let all: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        let sketch = a.plan.sketch_defaults();
        for run in 0..4 {
            // The sketch's defaults, then others: a longer length, a turn and place.
            let defaults: Vec<f64> = (sketch.iter().zip(&a.plan.defaults))
                .map(|(&d, var)| match run {
                    0 => d,
                    _ if var.name.ends_with("_length") => d * rng.range(1.0, 2.0),
                    _ => d + rng.range(-3.0, 3.0),
                })
                .collect();
            let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
            let s = gcs_compiler::solve::solve_plan_with(
                &model,
                &a.plan,
                &all,
                &[],
                &branches,
                &defaults,
            )
            .unwrap_or_else(|e| panic!("trial {trial}, run {run}: {e}\n{text}"));
            assert!(
                s.max_residual <= 1e-12 * 30.0,
                "trial {trial}, run {run}: residual {:e}\n{text}",
                s.max_residual
            );
            let (h1, h2) = (
                height(point(&s, &format!("S.{first}"))),
                height(point(&s, &format!("S.{second}"))),
            );
            assert!(
                h1.abs() <= 1e-12 * 30.0 && (h2 - h).abs() <= 1e-12 * 30.0,
                "trial {trial}, run {run}: the ends at {h1:e} and {h2} from the plane\n{text}"
            );
        }
    }
}

fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn unit(a: V) -> V {
    let l = norm(a);
    [a[0] / l, a[1] / l, a[2] / l]
}

/// SolveSpace's skew-angle sketch, at random: a segment on each of two perpendicular planes
/// (each end `on` its plane), at 90 deg to each other, one drawn along the other plane's
/// normal. Each segment turns about its plane's normal, and one turn takes a default: given to
/// the segment drawn along the other's normal, the other's turn cannot change the angle there
/// (every turn keeps 90 deg), so the default goes to the other segment's turn, whichever is
/// named first. Before, it went to the first by name and the sketch was refused as degenerate
/// when that was the segment along the normal. Solved at the sketch's defaults and at others,
/// each judged by the angle and the ends' heights computed here.
#[test]
fn two_turns_about_known_axes_default_the_one_that_leaves_the_angle_regular() {
    let mut rng = Rng(0x5bd1_e995_0d2a_7c41);
    let random = |rng: &mut Rng| [0; 3].map(|_| rng.range(-1.0, 1.0));
    for trial in 0..40 {
        let n1 = unit(random(&mut rng));
        let n2 = unit(cross(n1, random(&mut rng)));
        let (o1, o2) = (rng.range(-3.0, 3.0), rng.range(-3.0, 3.0));
        // A point on both planes, and the planes' own directions.
        let base = {
            let line = cross(n1, n2);
            let c = cross(line, n1);
            // base = o1 n1 + t c, with base . n2 = o2.
            let t = (o2 - o1 * dot(n1, n2)) / dot(c, n2);
            [0, 1, 2].map(|i| o1 * n1[i] + t * c[i])
        };
        let along = |p: V, d: V, s: f64| [0, 1, 2].map(|i| p[i] + s * d[i]);
        // One on plane P along Q's normal, the other on Q at a random turn; the first named
        // (`a`) on even trials.
        let a0 = along(base, cross(n1, n2), rng.range(-3.0, 3.0));
        let a1 = along(a0, n2, rng.range(2.0, 6.0));
        let in_q = unit(cross(n2, random(&mut rng)));
        let b0 = along(along(base, n1, rng.range(-3.0, 3.0)), cross(n1, n2), 1.0);
        let b1 = along(b0, in_q, rng.range(2.0, 6.0));
        let (first, second) = if trial % 2 == 0 {
            ("a", "b")
        } else {
            ("b", "a")
        };
        let f = |p: V| format!("({}, {}, {})", p[0], p[1], p[2]);
        let text = format!(
            "space 3d;\nfixed plane P = normal {} offset {o1};\nfixed plane Q = normal {} offset {o2};\n\
             segment {first} = {} -> {};\nsegment {second} = {} -> {};\n\
             on({first}.start, P);\non({first}.end, P);\non({second}.start, Q);\non({second}.end, Q);\n\
             k: angle({second}, {first}) = 90 deg;\n",
            f(n1),
            f(n2),
            f(a0),
            f(a1),
            f(b0),
            f(b1)
        );
        let model = load_text("skew.gcs", &text);
        let an = analyse(&model).expect("analysed");
        assert!(
            an.unsolved.is_empty(),
            "trial {trial}: {:?}\n{text}",
            an.unsolved
        );
        assert_eq!(an.free_defaults().len(), 7, "trial {trial}\n{text}");
        let all: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        let sketch = an.plan.sketch_defaults();
        for run in 0..4 {
            let defaults: Vec<f64> = (sketch.iter().zip(&an.plan.defaults))
                .map(|(&d, var)| match run {
                    0 => d,
                    _ if var.name.ends_with("_length") => d * rng.range(0.5, 2.0),
                    _ => d + rng.range(-2.0, 2.0),
                })
                .collect();
            let branches: Vec<usize> = an.plan.branches.iter().map(|b| b.default).collect();
            let s = gcs_compiler::solve::solve_plan_with(
                &model,
                &an.plan,
                &all,
                &[],
                &branches,
                &defaults,
            )
            .unwrap_or_else(|e| panic!("trial {trial}, run {run}: {e}\n{text}"));
            assert!(
                s.max_residual <= 1e-12 * 30.0,
                "trial {trial}, run {run}: residual {:e}\n{text}",
                s.max_residual
            );
            let (a0, a1) = (
                point(&s, &format!("{first}.start")),
                point(&s, &format!("{first}.end")),
            );
            let (b0, b1) = (
                point(&s, &format!("{second}.start")),
                point(&s, &format!("{second}.end")),
            );
            let (da, db) = (unit(sub(a1, a0)), unit(sub(b1, b0)));
            assert!(
                dot(da, db).abs() <= 1e-12,
                "trial {trial}, run {run}: cos {:e}\n{text}",
                dot(da, db)
            );
            for (p, n, o) in [(a0, n1, o1), (a1, n1, o1), (b0, n2, o2), (b1, n2, o2)] {
                let h = dot(p, n) - o;
                assert!(
                    h.abs() <= 1e-12 * 30.0,
                    "trial {trial}, run {run}: height {h:e}\n{text}"
                );
            }
        }
    }
}
