//! A body whose last constraint fixes its slide and leaves its turn free, solved from random
//! sketches: a marker on a line with another in a plane square to the axis a joint turns the
//! body about (the height over the plane sets the place on the line), and a planar joint with
//! a helical one about its normal (the joint holds the advance, so the helix sets the turn and
//! the slide in the plane stays free). Each is built from a random target the constraints
//! hold, the sketch that target moved by a small rigid motion; every solution, at the sketch's
//! defaults and at others, is re-measured by `verify`.

use gcs_compiler::{analyse, solve};
use gcs_lang::Model;
use std::collections::BTreeSet;
use std::f64::consts::TAU;

type V = [f64; 3];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn mul(a: V, k: f64) -> V {
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
fn unit(a: V) -> V {
    mul(a, 1.0 / dot(a, a).sqrt())
}
/// `v` turned by `angle` counter-clockwise about unit `axis` (Rodrigues).
fn turn(v: V, axis: V, angle: f64) -> V {
    let (s, c) = angle.sin_cos();
    add(
        add(mul(v, c), mul(cross(axis, v), s)),
        mul(axis, dot(axis, v) * (1.0 - c)),
    )
}
/// `v` less its part along unit `z`.
fn across(v: V, z: V) -> V {
    unit(sub(v, mul(z, dot(v, z))))
}
fn txt(v: V) -> String {
    format!("({}, {}, {})", v[0], v[1], v[2])
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
    fn point(&mut self, s: f64) -> V {
        [self.range(-s, s), self.range(-s, s), self.range(-s, s)]
    }
    fn unit(&mut self) -> V {
        loop {
            let v = self.point(1.0);
            let l = dot(v, v);
            if (0.04..=1.0).contains(&l) {
                return unit(v);
            }
        }
    }
    fn sign(&mut self) -> f64 {
        if self.next() < 0.5 {
            -1.0
        } else {
            1.0
        }
    }
}

/// A body's sketch (its place, its turn about an axis) and the small rigid motion that takes
/// it to the target (a turn about an axis through the origin, then a shift).
struct Pose {
    at: V,
    axis: V,
    angle: f64,
    to_axis: V,
    to_angle: f64,
    shift: V,
}

impl Pose {
    fn random(rng: &mut Rng) -> Pose {
        Pose {
            at: rng.point(5.0),
            axis: rng.unit(),
            angle: rng.range(-3.0, 3.0),
            to_axis: rng.unit(),
            to_angle: rng.range(-0.6, 0.6),
            shift: rng.point(1.0),
        }
    }
    /// The body's declaration line.
    fn decl(&self) -> String {
        format!(
            "body P at {} rotated {} rad about {}",
            txt(self.at),
            self.angle,
            txt(self.axis)
        )
    }
    /// Where local direction `d` points at the target.
    fn dir(&self, d: V) -> V {
        turn(turn(d, self.axis, self.angle), self.to_axis, self.to_angle)
    }
    /// Where local point `p` is at the target.
    fn point(&self, p: V) -> V {
        add(
            self.dir(p),
            add(turn(self.at, self.to_axis, self.to_angle), self.shift),
        )
    }
}

/// A marker of `P`: local origin, z and x (square to z).
fn local_marker(rng: &mut Rng) -> (V, V, V) {
    let z = rng.unit();
    (rng.point(2.0), z, across(rng.unit(), z))
}

fn marker_text(name: &str, (o, z, x): (V, V, V)) -> String {
    format!("marker {name} = {} z {} x {};", txt(o), txt(z), txt(x))
}

fn load(text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load("slide.gcs", text.as_bytes());
    assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}\n{text}");
    model.unwrap_or_else(|| panic!("no model\n{text}"))
}

/// Solves `text` at the sketch's defaults and at three others, on the default branches and
/// then on each other combination until one solves, and checks every answer by `verify`;
/// `free` defaults expected.
fn solves_everywhere(text: &str, free: usize, rng: &mut Rng) {
    let model = load(text);
    let a = analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}\n{text}", a.unsolved);
    assert_eq!(a.free_defaults().len(), free, "{text}");
    let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let sketch = a.plan.sketch_defaults();
    for run in 0..4 {
        let defaults: Vec<f64> = (sketch.iter())
            .map(|&d| {
                if run == 0 {
                    d
                } else {
                    d + rng.range(-1.0, 1.0)
                }
            })
            .collect();
        let s = if run == 0 {
            solve(&model, &a, &[], &branches)
        } else {
            gcs_compiler::solve::solve_plan_with(&model, &a.plan, &all, &[], &branches, &defaults)
        }
        .unwrap_or_else(|e| panic!("run {run}: {e}\n{text}"));
        let worst =
            gcs_compiler::verify::max_residual(&gcs_compiler::verify::residuals(&model, &s, &[]));
        assert!(worst <= 1e-11, "run {run}: residual {worst:e}\n{text}");
    }
}

#[test]
fn a_body_on_a_line_with_a_marker_in_a_plane_across_its_turn_slides_to_the_plane() {
    let mut rng = Rng(0x5bd1_e995_9e37_79b9);
    for _ in 0..40 {
        let pose = Pose::random(&mut rng);
        let (m, n) = (local_marker(&mut rng), local_marker(&mut rng));
        // The line through m's target along a random direction; the plane through n's
        // target square to n's target z, its marker's z in either sense.
        let e = rng.unit();
        let line_at = add(pose.point(m.0), mul(e, rng.range(-2.0, 2.0)));
        let z = mul(pose.dir(n.1), rng.sign());
        let plane_at = add(
            pose.point(n.0),
            mul(across(rng.unit(), z), rng.range(0.0, 2.0)),
        );
        let text = format!(
            "space 3d;\nfixed body ground {{\n{}\n{}\n}}\n{} {{\n{}\n{}\n}}\n\
             a: in_line(P.m, ground.l);\nb: planar(P.n, ground.g);\n",
            marker_text("l", (line_at, e, across(rng.unit(), e))),
            marker_text("g", (plane_at, z, across(rng.unit(), z))),
            pose.decl(),
            marker_text("m", m),
            marker_text("n", n),
        );
        solves_everywhere(&text, 1, &mut rng);
    }
}

#[test]
fn a_planar_joint_with_a_helical_one_turns_to_the_advance_it_holds() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for _ in 0..40 {
        let pose = Pose::random(&mut rng);
        let m = local_marker(&mut rng);
        let (o, z, x) = (pose.point(m.0), pose.dir(m.1), pose.dir(m.2));
        // The joint's plane through m's target square to its z; the helix's marker anywhere
        // on a parallel axis, its x turned back by the advance's share of a turn.
        let zg = mul(z, rng.sign());
        let plane_at = add(o, mul(across(rng.unit(), zg), rng.range(0.0, 2.0)));
        let zh = mul(z, rng.sign());
        let helix_at = add(o, rng.point(2.0));
        let pitch = rng.sign() * rng.range(0.5, 3.0);
        let advance = dot(zh, sub(o, helix_at));
        let xh = turn(across(x, zh), zh, -TAU * advance / pitch);
        let text = format!(
            "space 3d;\nfixed body ground {{\n{}\n{}\n}}\n{} {{\n{}\n}}\n\
             a: planar(P.m, ground.g);\nb: helical(ground.h, P.m) = {pitch};\n",
            marker_text("g", (plane_at, zg, across(rng.unit(), zg))),
            marker_text("h", (helix_at, zh, xh)),
            pose.decl(),
            marker_text("m", m),
        );
        solves_everywhere(&text, 2, &mut rng);
    }
}
