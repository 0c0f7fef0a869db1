//! Serial arms solved in closed form with every solution (issue 38): the 3R positioning arm of
//! `examples/arm_3r.gcs`, the PUMA-like 6R of `examples/puma.gcs`, UR5, IRB 6640, a 7-joint
//! arm, a SCARA, a Delta robot, and ik-geo's test arms.
//!
//! Each pose comes from random joint angles through forward kinematics written here, apart
//! from the plan: the product of exponentials of the joints' screws, read from the numbers of
//! the model's sketch below (each joint's point and axis), never from the compiler. Every
//! solution the plan returns must reach the pose, be a distinct assembly, and one of them must
//! be the arm the pose came from (each body's frame equal to the forward kinematics' at the
//! random angles). How many solutions there are is counted here too, by the arm's geometry: the
//! base's two turns that put the wrist centre in the plane of the shoulder and elbow (none
//! when it is inside the cylinder of the shoulder's offset), the elbow's two (none beyond
//! reach), and the wrist's two.
//!
//! Near singularities (`check_near_singularities`), every arm is posed where its Jacobian loses
//! rank, found by the determinant's sign along one joint's turn rather than by naming the
//! singularity, and next to it: no solution returned may be wrong.

use gcs_compiler::all::solve_all;
use gcs_compiler::solution::Solution;
use nalgebra::{Rotation3, Unit, Vector3};
use std::collections::BTreeSet;

/// A revolute joint in the sketch: a point of its axis and its direction.
struct Joint {
    point: [f64; 3],
    axis: [f64; 3],
}

/// A serial arm as its sketch has it: the joints from the base, the bodies they turn (body
/// `i` turned by joints `0..=i`), and the tool marker (point, z, x) on the last body.
struct Arm {
    file: &'static str,
    joints: Vec<Joint>,
    bodies: Vec<&'static str>,
    tool: ([f64; 3], [f64; 3], [f64; 3]),
    /// The params of the tool's target: its point, then (if any) its z and x axes.
    params: Vec<&'static str>,
    /// The arm's count of solutions by its geometry, where it has one written here.
    count: Option<Count>,
    /// Joints whose angle is a param (a 7-joint arm's redundancy): the joint and the param.
    joint_params: Vec<(usize, &'static str)>,
}

/// What a count of solutions reads of an arm with a shoulder on the base's axis (module docs).
struct Count {
    /// The shoulder's point, the offset along the shoulder's axis to the wrist centre, and the
    /// upper arm's and the forearm's lengths (shoulder to elbow, elbow to wrist centre).
    shoulder: ([f64; 3], f64, f64, f64),
    /// The wrist centre's offset back from the tool's point along the tool's z axis, and
    /// whether a wrist doubles the solutions.
    wrist: (f64, bool),
}

fn v(a: [f64; 3]) -> Vector3<f64> {
    Vector3::new(a[0], a[1], a[2])
}

/// The rigid motion of each body at joint angles `q`: rotation and translation.
fn forward(arm: &Arm, q: &[f64]) -> Vec<(Rotation3<f64>, Vector3<f64>)> {
    let mut out = Vec::new();
    let (mut r, mut t) = (Rotation3::identity(), Vector3::zeros());
    for (j, &angle) in arm.joints.iter().zip(q) {
        // exp(xi q): a turn about the joint's sketch axis, composed after the joints before.
        let c = v(j.point);
        let turn = Rotation3::from_axis_angle(&Unit::new_normalize(v(j.axis)), angle);
        let tj = c - turn * c;
        // (r, t) . (turn, tj)
        t += r * tj;
        r *= turn;
        out.push((r, t));
    }
    out
}

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn angle(&mut self) -> f64 {
        (2.0 * self.next() - 1.0) * std::f64::consts::PI
    }
}

fn frame<'s>(s: &'s Solution, body: &str) -> (&'s [f64], &'s [Vec<f64>]) {
    let (_, o, axes) = (s.frames.iter())
        .find(|(n, _, _)| n == body)
        .unwrap_or_else(|| panic!("no frame {body}"));
    (o, axes)
}

/// Whether solution `s` has every body where the motions `fk` put it.
fn is_arm(arm: &Arm, s: &Solution, fk: &[(Rotation3<f64>, Vector3<f64>)], tol: f64) -> bool {
    arm.bodies.iter().zip(fk).all(|(body, (r, t))| {
        let (o, axes) = frame(s, body);
        (v([o[0], o[1], o[2]]) - t).norm() <= tol
            && (0..3).all(|k| {
                let e = r * Vector3::ith(k, 1.0);
                (v([axes[k][0], axes[k][1], axes[k][2]]) - e).norm() <= tol
            })
    })
}

/// How many solutions the arm has for the tool's pose, by its geometry (module docs).
fn count(arm: &Count, tool_point: Vector3<f64>, tool_z: Vector3<f64>) -> usize {
    let w = tool_point - arm.wrist.0 * tool_z;
    let (s, offset, a, b) = arm.shoulder;
    // The base turns about z through the origin; the shoulder is on that axis.
    let rho = w.x.hypot(w.y);
    if rho < offset.abs() {
        return 0;
    }
    let reach = (rho * rho - offset * offset).sqrt();
    let mut n = 0;
    for side in [1.0, -1.0] {
        // The wrist centre in the arm's plane: `side * reach` out, its height above the shoulder.
        let d = (side * reach).hypot(w.z - s[2]);
        if d < a + b && d > (a - b).abs() {
            n += 2;
        }
    }
    if arm.wrist.1 {
        n * 2
    } else {
        n
    }
}

/// The model, its plan and the params of a pose.
struct Loaded {
    compiled: gcs_compiler::pipeline::Compiled,
    scope: BTreeSet<gcs_lang::model::GeomId>,
}

fn load(arm: &Arm) -> Loaded {
    // An example, or (a path with a directory) a file of the repository.
    let dir = if arm.file.contains('/') {
        ""
    } else {
        "examples/"
    };
    let path = format!("{}/../{dir}{}", env!("CARGO_MANIFEST_DIR"), arm.file);
    let text = std::fs::read_to_string(&path).expect("the example");
    let compiled = gcs_compiler::compile(arm.file, text.as_bytes()).expect("compiles");
    assert!(!compiled.has_errors(), "{:?}", compiled.diagnostics);
    let scope = compiled.model.top_level().map(|(id, _)| id).collect();
    Loaded { compiled, scope }
}

/// The params of the tool's pose at joint angles `q`, and that pose (point, z).
fn pose_params(arm: &Arm, l: &Loaded, q: &[f64]) -> (Vec<f64>, Vector3<f64>, Vector3<f64>) {
    let model = &l.compiled.model;
    let fk = forward(arm, q);
    let (r, t) = fk.last().expect("a body");
    let (p0, z0, x0) = arm.tool;
    let (p, z, x) = (r * v(p0) + t, r * v(z0), r * v(x0));
    let mut params = model.default_params();
    let values = [p.x, p.y, p.z, z.x, z.y, z.z, x.x, x.y, x.z];
    let joints = arm.joint_params.iter().map(|&(j, name)| (name, q[j]));
    for (name, value) in arm.params.iter().copied().zip(values).chain(joints) {
        let i = (model.params.iter())
            .position(|(_, p)| p.name == name)
            .unwrap_or_else(|| panic!("no param {name}"));
        params[i] = value;
    }
    (params, p, z)
}

/// Solution `s`'s body motions, read from its frames.
fn motions(arm: &Arm, s: &Solution) -> Vec<(Rotation3<f64>, Vector3<f64>)> {
    (arm.bodies.iter())
        .map(|n| {
            let (o, axes) = frame(s, n);
            let col = |k: usize| v([axes[k][0], axes[k][1], axes[k][2]]);
            (
                Rotation3::from_matrix_unchecked(nalgebra::Matrix3::from_columns(&[
                    col(0),
                    col(1),
                    col(2),
                ])),
                v([o[0], o[1], o[2]]),
            )
        })
        .collect()
}

/// The tool's pose error at joint angles `q` (its point, and its z and x axes where the pose
/// fixes them).
fn pose_error(arm: &Arm, q: &[f64], target: &[Vector3<f64>; 3]) -> Vec<f64> {
    let fk = forward(arm, q);
    let (r, t) = fk.last().expect("a body");
    let (p0, z0, x0) = arm.tool;
    let mut e: Vec<f64> = (r * v(p0) + t - target[0]).iter().copied().collect();
    if arm.params.len() == 9 {
        e.extend((r * v(z0) - target[1]).iter());
        e.extend((r * v(x0) - target[2]).iter());
    }
    e
}

/// Inverse kinematics by Gauss-Newton from `starts` random joint angles, sharing nothing with
/// the plan: the distinct solutions it converges to (each as the arm's joint angles). The
/// joints whose angle is a param keep theirs from `given`.
fn newton_solutions(
    arm: &Arm,
    target: &[Vector3<f64>; 3],
    given: &[f64],
    starts: usize,
    rng: &mut Rng,
) -> Vec<Vec<f64>> {
    let n = arm.joints.len();
    let free: Vec<usize> = (0..n)
        .filter(|j| !arm.joint_params.iter().any(|(k, _)| k == j))
        .collect();
    let mut found: Vec<Vec<f64>> = Vec::new();
    for _ in 0..starts {
        let mut q: Vec<f64> = given.to_vec();
        for &k in &free {
            q[k] = rng.angle();
        }
        for _ in 0..60 {
            let e = pose_error(arm, &q, target);
            let m = e.len();
            let mut j = nalgebra::DMatrix::zeros(m, free.len());
            for (c, &k) in free.iter().enumerate() {
                let h = 1e-7;
                let mut qp = q.clone();
                qp[k] += h;
                let ep = pose_error(arm, &qp, target);
                for i in 0..m {
                    j[(i, c)] = (ep[i] - e[i]) / h;
                }
            }
            let step = j
                .svd(true, true)
                .solve(&nalgebra::DVector::from_vec(e.clone()), 1e-12);
            let Ok(step) = step else { break };
            for (c, &k) in free.iter().enumerate() {
                q[k] -= step[c];
            }
            if step.norm() < 1e-13 {
                break;
            }
        }
        let e = pose_error(arm, &q, target);
        if e.iter().map(|x| x * x).sum::<f64>().sqrt() > 1e-11 {
            continue;
        }
        let same = |a: &Vec<f64>| {
            a.iter().zip(&q).all(|(x, y)| {
                let d = (x - y).rem_euclid(std::f64::consts::TAU);
                d.min(std::f64::consts::TAU - d) < 1e-6
            })
        };
        if !found.iter().any(same) {
            found.push(q);
        }
    }
    found
}

/// Checks the arm at `poses` random poses: every solution reaches the pose, none twice, the
/// arm the pose came from among them, as many as the geometric count says (where the arm has
/// one), and every solution a Newton search from random starts finds (the first `searched`
/// poses) among them.
fn check_arm(arm: &Arm, poses: usize, searched: usize, seed: u64) {
    let l = load(arm);
    let plan = &l.compiled.analysis.plan;
    assert!(
        plan.defaults.is_empty() && plan.iterations.is_empty(),
        "{}: closed form, no default",
        arm.file
    );
    check_solutions(arm, &l, poses, searched, seed);
}

fn check_solutions(arm: &Arm, l: &Loaded, poses: usize, searched: usize, seed: u64) {
    let (model, plan) = (&l.compiled.model, &l.compiled.analysis.plan);
    let mut rng = Rng(seed);
    let mut solved = 0;
    let mut by_newton = 0;
    for pose in 0..poses {
        let q: Vec<f64> = arm.joints.iter().map(|_| rng.angle()).collect();
        let fk = forward(arm, &q);
        let (params, p, z) = pose_params(arm, l, &q);
        let found = solve_all(model, plan, &l.scope, &params, &plan.sketch_defaults());
        assert!(
            found.complete,
            "{}: q = {q:?}: a list not complete",
            arm.file
        );
        let reach = 2.0;
        for s in &found.solutions {
            assert!(
                s.max_residual <= 1e-12 * reach,
                "{}: q = {q:?}: a solution off by {}",
                arm.file,
                s.max_residual
            );
        }
        for (i, a) in found.solutions.iter().enumerate() {
            for b in &found.solutions[..i] {
                assert!(
                    !is_arm(arm, a, &motions(arm, b), 1e-9),
                    "{}: q = {q:?}: a solution twice",
                    arm.file
                );
            }
        }
        assert!(
            found.solutions.iter().any(|s| is_arm(arm, s, &fk, 1e-8)),
            "{}: q = {q:?}: the arm the pose came from is not among {} solutions",
            arm.file,
            found.solutions.len()
        );
        if let Some(c) = &arm.count {
            assert_eq!(
                found.solutions.len(),
                count(c, p, z),
                "{}: q = {q:?}",
                arm.file
            );
        }
        if pose < searched {
            let (r, _) = fk.last().expect("a body");
            let target = [p, r * v(arm.tool.1), r * v(arm.tool.2)];
            for qn in newton_solutions(arm, &target, &q, 40, &mut rng) {
                by_newton += 1;
                assert!(
                    found
                        .solutions
                        .iter()
                        .any(|s| is_arm(arm, s, &forward(arm, &qn), 1e-6)),
                    "{}: q = {q:?}: Newton's solution {qn:?} is not among the plan's {}",
                    arm.file,
                    found.solutions.len()
                );
            }
        }
        solved += found.solutions.len();
    }
    eprintln!(
        "{}: {solved} solutions over {poses} poses; Newton found {by_newton} over {searched}",
        arm.file
    );
    // Every pose is reachable (it came from the arm): at least the arm it came from.
    assert!(solved >= poses && by_newton >= searched);
}

fn arm_3r() -> Arm {
    Arm {
        file: "arm_3r.gcs",
        joints: vec![
            Joint {
                point: [0.0, 0.0, 0.0],
                axis: [0.0, 0.0, 1.0],
            },
            Joint {
                point: [0.0, 0.0, 0.5],
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: [0.3, 0.0, 0.9],
                axis: [0.0, 1.0, 0.0],
            },
        ],
        bodies: vec!["base_link", "upper_arm", "forearm"],
        tool: ([0.7, 0.0, 0.6], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
        params: vec!["tx", "ty", "tz"],
        count: Some(Count {
            shoulder: ([0.0, 0.0, 0.5], 0.0, 0.5, (0.4f64 * 0.4 + 0.3 * 0.3).sqrt()),
            wrist: (0.0, false),
        }),
        joint_params: Vec::new(),
    }
}

fn puma() -> Arm {
    let w = [0.4521, 0.15, 0.2282];
    Arm {
        file: "puma.gcs",
        joints: vec![
            Joint {
                point: [0.0, 0.0, 0.0],
                axis: [0.0, 0.0, 1.0],
            },
            Joint {
                point: [0.0, 0.0, 0.66],
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: [0.4318, 0.15, 0.66],
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: w,
                axis: [0.0, 0.0, -1.0],
            },
            Joint {
                point: w,
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: w,
                axis: [1.0, 0.0, 0.0],
            },
        ],
        bodies: vec![
            "trunk",
            "upper_arm",
            "forearm",
            "wrist_roll",
            "wrist_bend",
            "tool",
        ],
        tool: ([0.5521, 0.15, 0.2282], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
        params: vec!["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"],
        count: Some(Count {
            shoulder: (
                [0.0, 0.0, 0.66],
                0.15,
                0.4318,
                (0.0203f64 * 0.0203 + 0.4318 * 0.4318).sqrt(),
            ),
            wrist: (0.1, true),
        }),
        joint_params: Vec::new(),
    }
}

#[test]
fn the_3r_arm_has_every_solution_in_closed_form_at_random_poses() {
    check_arm(&arm_3r(), 1000, 50, 0x3a3a_5eed);
}

#[test]
fn the_puma_arm_has_every_solution_in_closed_form_at_random_poses() {
    check_arm(&puma(), 1000, 30, 0x9a9a_5eed);
}

/// Poses at and next to the PUMA's singularities: the wrist straight (q5 = 0), the elbow
/// stretched, the wrist centre on the base's axis. Every solution returned must reach the
/// pose; an error is an answer too, a wrong solution never is.
#[test]
fn the_puma_arm_gives_no_wrong_answer_near_its_singularities() {
    let arm = puma();
    let l = load(&arm);
    let (model, plan) = (&l.compiled.model, &l.compiled.analysis.plan);
    let mut rng = Rng(0x516a_5eed);
    // The elbow's angle at which the forearm's wrist centre is furthest from the shoulder.
    let stretched = (0.0203f64).atan2(0.4318) - std::f64::consts::FRAC_PI_2;
    let (mut answered, mut refused) = (0, 0);
    for i in 0..1000 {
        let mut q: Vec<f64> = (0..6).map(|_| rng.angle()).collect();
        let near = [0.0, 1e-13, -1e-10, 1e-7, 1e-4][i % 5];
        match (i / 5) % 3 {
            0 => q[4] = near,
            1 => q[2] = stretched + near,
            _ => {
                // The wrist centre on the base's axis: the arm folded over the base.
                q[4] = 0.7;
            }
        }
        let (params, p, _) = pose_params(&arm, &l, &q);
        let found = solve_all(model, plan, &l.scope, &params, &[]);
        if found.solutions.is_empty() {
            refused += 1;
        } else {
            answered += 1;
        }
        for s in &found.solutions {
            let tcp = (s.points.iter())
                .find(|(n, _)| n == "tool.tcp")
                .expect("tcp");
            let miss = (v([tcp.1[0], tcp.1[1], tcp.1[2]]) - p).norm();
            assert!(
                s.max_residual <= 1e-9 && miss <= 1e-9,
                "q = {q:?}: a wrong answer, off by {} (tool {miss})",
                s.max_residual
            );
        }
    }
    eprintln!("near singularities: {answered} answered, {refused} refused");
}

fn ur5() -> Arm {
    // The sketch's elbow bent (shoulder -0.5, elbow 1.0, first wrist joint -0.5 rad from the
    // arm stretched along x).
    let w1 = [0.717204348704907, 0.10915, 0.104860186389288];
    let w2 = [0.717204348704907, 0.10915, 0.010210186389288];
    Arm {
        file: "ur5.gcs",
        joints: vec![
            Joint {
                point: [0.0, 0.0, 0.0],
                axis: [0.0, 0.0, 1.0],
            },
            Joint {
                point: [0.0, 0.0, 0.089159],
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: [0.372972588803408, 0.0, 0.292914853906786],
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: w1,
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: w2,
                axis: [0.0, 0.0, -1.0],
            },
            Joint {
                point: w2,
                axis: [1.0, 0.0, 0.0],
            },
        ],
        bodies: vec![
            "trunk",
            "upper_arm",
            "forearm",
            "wrist_1",
            "wrist_2",
            "wrist_3",
        ],
        tool: (
            [0.799504348704907, 0.10915, 0.010210186389288],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
        ),
        params: vec!["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"],
        count: None,
        joint_params: Vec::new(),
    }
}

fn irb6640() -> Arm {
    let w = [1.4625, 0.0, 2.055];
    Arm {
        file: "irb6640.gcs",
        joints: vec![
            Joint {
                point: [0.0, 0.0, 0.0],
                axis: [0.0, 0.0, 1.0],
            },
            Joint {
                point: [0.32, 0.0, 0.78],
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: [0.32, 0.0, 1.855],
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: w,
                axis: [1.0, 0.0, 0.0],
            },
            Joint {
                point: w,
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: w,
                axis: [0.0, 0.0, -1.0],
            },
        ],
        bodies: vec![
            "trunk",
            "upper_arm",
            "forearm",
            "wrist_roll",
            "wrist_bend",
            "tool",
        ],
        tool: ([1.4625, 0.0, 1.855], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
        params: vec!["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"],
        count: None,
        joint_params: Vec::new(),
    }
}

/// ik-geo's `spherical_bot`: three joints in general position, then a spherical wrist
/// (`ikgeo/models/`, written from ik-geo's kinematics by `ikgeo/src/model.rs`).
fn spherical_bot() -> Arm {
    let w = [3.0140918058755215, 0.6044084883852824, 2.6160971379033464];
    Arm {
        file: "ikgeo/models/ikgeo_spherical_bot.gcs",
        joints: vec![
            Joint {
                point: [0.0, 0.0, 0.0],
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: [1.2508566957869456, 0.0, 0.6598162824642664],
                axis: [0.29552020666133955, 0.0, 0.955336489125606],
            },
            Joint {
                point: [2.384763546042489, 0.479425538604203, 1.3558093915376417],
                axis: [-0.45801271084729195, 0.8775825618903728, 0.1416799342470381],
            },
            Joint {
                point: w,
                axis: [0.8588136164503541, 0.3956869717073036, 0.3253782300962491],
            },
            Joint {
                point: w,
                axis: [-0.5119651088617578, 0.6403687314197659, 0.5725553380486538],
            },
            Joint {
                point: w,
                axis: [0.5195978843864277, 0.761627557357866, -0.38722280719792224],
            },
        ],
        bodies: vec!["link_1", "link_2", "link_3", "link_4", "link_5", "tool"],
        tool: (
            [3.533689690261949, 1.3660360457431486, 2.2288743307054237],
            [0.502191669841866, 0.09442095516838785, 0.8595860689695519],
            [0.5195978843864277, 0.761627557357866, -0.38722280719792224],
        ),
        params: vec!["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"],
        count: None,
        joint_params: Vec::new(),
    }
}

/// ik-geo's `three_parallel_bot`: a base that yaws, three parallel axes, then two joints; no
/// two axes meet.
fn three_parallel_bot() -> Arm {
    let x = [0.955336489125606, 0.29552020666133955, 0.0];
    Arm {
        file: "ikgeo/models/ikgeo_three_parallel_bot.gcs",
        joints: vec![
            Joint {
                point: [0.0, 0.0, 1.0],
                axis: [0.0, 0.0, 1.0],
            },
            Joint {
                point: [-0.29552020666133955, 0.955336489125606, 1.0],
                axis: x,
            },
            Joint {
                point: [-0.5215465279109626, 1.6860181390611182, 0.355782312762309],
                axis: x,
            },
            Joint {
                point: [-0.7937386632063939, 2.5659413153423762, 0.7452006550709593],
                axis: x,
            },
            Joint {
                point: [-1.0877824997582497, 3.5165051012644395, 0.6453672384241314],
                axis: [
                    -0.029502791919178206,
                    0.09537450575679446,
                    0.9950041652780259,
                ],
            },
            Joint {
                point: [-1.5233060583428908, 4.854559680694705, 0.5041965177223234],
                axis: [
                    0.45465520451603747,
                    0.8877836323483186,
                    -0.07161610950691187,
                ],
            },
        ],
        bodies: vec!["link_1", "link_2", "link_3", "link_4", "link_5", "tool"],
        tool: (
            [-1.0686508538268533, 5.742343313043024, 0.4325804082154112],
            [0.3194780674340925, -0.08749802872751081, 0.9435453668994287],
            [
                0.45465520451603747,
                0.8877836323483186,
                -0.07161610950691187,
            ],
        ),
        params: vec!["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"],
        count: None,
        joint_params: Vec::new(),
    }
}

/// ik-geo's `two_parallel_bot`: two parallel axes, the others in general position (no closed
/// form; `ikgeo/models/`).
fn two_parallel_bot() -> Arm {
    Arm {
        file: "ikgeo/models/ikgeo_two_parallel_bot.gcs",
        joints: vec![
            Joint {
                point: [0.0, 0.0, 1.0],
                axis: [0.0, 0.0, 1.0],
            },
            Joint {
                point: [-0.29552020666133955, 0.955336489125606, 1.0],
                axis: [0.955336489125606, 0.29552020666133955, 0.0],
            },
            Joint {
                point: [-0.5215465279109626, 1.6860181390611182, 0.355782312762309],
                axis: [0.955336489125606, 0.29552020666133955, 0.0],
            },
            Joint {
                point: [-0.7937386632063939, 2.5659413153423762, 0.7452006550709593],
                axis: [0.11508098899676873, -0.3720255519422598, 0.9210609940028851],
            },
            Joint {
                point: [-0.5745970237780779, 3.4798264848970337, 1.0869474015612877],
                axis: [
                    0.9688825046620438,
                    -0.16251426266673197,
                    -0.18669709850368074,
                ],
            },
            Joint {
                point: [-0.33936552488745964, 3.8496616184425987, 1.9857733668766029],
                axis: [0.6306385652985995, -0.7617576879326065, 0.14839213198041903],
            },
        ],
        bodies: vec!["link_1", "link_2", "link_3", "link_4", "link_5", "tool"],
        tool: (
            [-0.4398824003922688, 2.8627412052720587, 2.111806917195721],
            [-0.10051687550480903, -0.98692041317054, 0.12603355031911828],
            [0.9923744875055992, -0.09036764034572371, 0.0838246152770486],
        ),
        params: vec!["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"],
        count: None,
        joint_params: Vec::new(),
    }
}

/// A general arm is well-constrained, not "mobility 2": the analysis defaults the tool end's
/// last turn (its look-ahead: at the base end three defaults would be needed), closes the
/// planar sub-chain's ends by subproblem 6 and the shoulder on a signed error, and `solve_all`
/// scans that turn. Every solution reaches its pose to 1e-12 and none is listed twice; the
/// list does not claim to be complete (the quartic's roots, in the order of their first angle,
/// swap along the scan), and the arm the pose came from is among the solutions at nearly every
/// pose (996 of ikgeo's 1,000).
#[test]
fn the_two_parallel_bot_is_searched_over_one_turn_and_its_solutions_reach_the_pose() {
    let arm = two_parallel_bot();
    let l = load(&arm);
    let (model, plan) = (&l.compiled.model, &l.compiled.analysis.plan);
    assert!(
        plan.iterations.len() == 1 && plan.iterations[0].defaults.len() == 1,
        "one iteration over one default"
    );
    assert_eq!(plan.defaults.len(), 1, "no free default: well-constrained");
    let mut rng = Rng(0x2b07_5eed);
    let (mut drawn, mut solved) = (0, 0);
    let poses = 40;
    for _ in 0..poses {
        let q: Vec<f64> = arm.joints.iter().map(|_| rng.angle()).collect();
        let fk = forward(&arm, &q);
        let (params, _, _) = pose_params(&arm, &l, &q);
        let found = solve_all(model, plan, &l.scope, &params, &plan.sketch_defaults());
        assert!(
            !found.complete,
            "q = {q:?}: a scan of sorted roots claims completeness"
        );
        for s in &found.solutions {
            assert!(
                s.max_residual <= 1e-12 * 2.0,
                "q = {q:?}: a solution off by {}",
                s.max_residual
            );
        }
        for (i, a) in found.solutions.iter().enumerate() {
            for b in &found.solutions[..i] {
                assert!(
                    !is_arm(&arm, a, &motions(&arm, b), 1e-9),
                    "q = {q:?}: a solution twice"
                );
            }
        }
        drawn += usize::from(found.solutions.iter().any(|s| is_arm(&arm, s, &fk, 1e-8)));
        solved += found.solutions.len();
    }
    eprintln!("two_parallel_bot: {solved} solutions over {poses} poses, the drawn arm at {drawn}");
    assert!(
        drawn >= poses - 2,
        "the drawn arm found at {drawn} of {poses} poses"
    );
}

/// The three-circle problem (the base's turn, the second and third joints closing on the
/// wrist centre) gives every solution in closed form, each reaching the pose to 1e-12, the arm
/// the pose came from among them, and every solution a Newton search finds.
#[test]
fn the_spherical_bot_has_every_solution_in_closed_form_at_random_poses() {
    check_arm(&spherical_bot(), 120, 8, 0x5b07_5eed);
}

/// The planar sub-chain's ends closed by SP6 (the base's turn and the fifth joint's angle), then
/// the elbow, give every solution in closed form, each reaching the pose to 1e-12, the arm the
/// pose came from among them, and every solution a Newton search finds.
#[test]
fn the_three_parallel_bot_has_every_solution_in_closed_form_at_random_poses() {
    check_arm(&three_parallel_bot(), 120, 8, 0x3b07_5eed);
}

#[test]
fn the_ur5_arm_has_every_solution_in_closed_form_at_random_poses() {
    check_arm(&ur5(), 1000, 30, 0x0405_5eed);
}

#[test]
fn the_irb6640_arm_has_every_solution_in_closed_form_at_random_poses() {
    check_arm(&irb6640(), 1000, 30, 0x6640_5eed);
}

fn iiwa() -> Arm {
    let (s, w) = ([0.0, 0.0, 0.36], [0.4, 0.0, 0.78]);
    Arm {
        file: "iiwa.gcs",
        joints: vec![
            Joint {
                point: [0.0, 0.0, 0.0],
                axis: [0.0, 0.0, 1.0],
            },
            Joint {
                point: s,
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: s,
                axis: [0.0, 0.0, 1.0],
            },
            Joint {
                point: [0.0, 0.0, 0.78],
                axis: [0.0, -1.0, 0.0],
            },
            Joint {
                point: w,
                axis: [1.0, 0.0, 0.0],
            },
            Joint {
                point: w,
                axis: [0.0, 1.0, 0.0],
            },
            Joint {
                point: w,
                axis: [0.0, 0.0, -1.0],
            },
        ],
        bodies: vec!["l1", "l2", "l3", "l4", "l5", "l6", "l7"],
        tool: ([0.4, 0.0, 0.594], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
        params: vec!["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"],
        count: None,
        joint_params: vec![(2, "q3")],
    }
}

#[test]
fn the_7_joint_arm_with_its_third_angle_given_has_every_solution_in_closed_form() {
    check_arm(&iiwa(), 1000, 30, 0x0007_5eed);
}

/// The Delta robot's geometry as `examples/delta.gcs` sketches it: base and platform radii,
/// upper arm and forearm lengths.
const DELTA: (f64, f64, f64, f64) = (0.2, 0.05, 0.3, 0.8);

fn delta_model(name: &str) -> (gcs_lang::Model, gcs_compiler::analysis::Analysis) {
    let path = format!("{}/../examples/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("the example");
    let (_, model, diags) = gcs_lang::load(name, text.as_bytes());
    assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}");
    let model = model.expect("a model");
    let a = gcs_compiler::analyse(&model).expect("analysed");
    assert!(a.unsolved.is_empty(), "{:?}", a.unsolved);
    assert!(
        a.plan.defaults.is_empty() && a.plan.iterations.is_empty(),
        "{name}: closed form"
    );
    (model, a)
}

fn point_of(s: &Solution, name: &str) -> Vector3<f64> {
    let p = &(s.points.iter())
        .find(|(n, _)| n == name)
        .expect("a point")
        .1;
    v([p[0], p[1], p[2]])
}

/// Arm `i`'s angle below the base's plane, read from its elbow.
fn delta_angle(i: usize, elbow: Vector3<f64>) -> f64 {
    let (r, _, a, _) = DELTA;
    let phi = std::f64::consts::TAU * i as f64 / 3.0;
    let radial = v([phi.cos(), phi.sin(), 0.0]);
    let out = (elbow - r * radial).dot(&radial);
    (-elbow.z / a).atan2(out / a)
}

/// The Delta robot's platform follows a closed path (a tilted circle) in 1-degree steps, each
/// solved on its own on the sketch's branches: every forearm is its length from its elbow to
/// the bit, each arm's angle moves by less than a degree a step (no flip), and the angles solve
/// the forward model (`examples/delta_forward.gcs`) back to the same platform.
#[test]
fn the_delta_robot_follows_a_path_without_flips_inverse_and_forward() {
    let (ik, a_ik) = delta_model("delta.gcs");
    let (fk, a_fk) = delta_model("delta_forward.gcs");
    let (_, rp, _, b) = DELTA;
    let index = |m: &gcs_lang::Model, n: &str| {
        (m.params.iter())
            .position(|(_, p)| p.name == n)
            .expect("a param")
    };
    let branches = |a: &gcs_compiler::analysis::Analysis| -> Vec<usize> {
        a.plan.branches.iter().map(|b| b.default).collect()
    };
    let z0 = ik.default_params()[index(&ik, "z")];
    let mut previous: Option<[f64; 3]> = None;
    for step in 0..=360 {
        let t = (step as f64).to_radians();
        let centre = v([0.1 * t.cos(), 0.1 * t.sin(), z0 + 0.05 * (2.0 * t).sin()]);
        let mut params = ik.default_params();
        for (n, x) in ["x", "y", "z"].iter().zip(centre.iter()) {
            params[index(&ik, n)] = *x;
        }
        let s = gcs_compiler::solve(&ik, &a_ik, &params, &branches(&a_ik))
            .unwrap_or_else(|e| panic!("{step} deg: {e}"));
        assert!(
            s.max_residual <= 1e-12,
            "{step} deg: off by {}",
            s.max_residual
        );
        let mut angles = [0.0; 3];
        for (i, angle) in angles.iter_mut().enumerate() {
            let phi = std::f64::consts::TAU * i as f64 / 3.0;
            let p = centre + rp * v([phi.cos(), phi.sin(), 0.0]);
            let elbow = point_of(&s, &format!("arm{}.elbow", i + 1));
            assert!(
                ((elbow - p).norm() - b).abs() <= 1e-12,
                "{step} deg: forearm {i}"
            );
            *angle = delta_angle(i, elbow);
        }
        if let Some(before) = previous {
            for i in 0..3 {
                assert!(
                    (angles[i] - before[i]).abs() < 1f64.to_radians(),
                    "{step} deg: arm {} flips from {} to {}",
                    i + 1,
                    before[i],
                    angles[i]
                );
            }
        }
        previous = Some(angles);
        // Forward: the arms' angles (the turn from the sketch's) give the platform back.
        let mut forward = fk.default_params();
        let sketch = [0.5; 3];
        for i in 0..3 {
            // offset_x is the turn about the hinge's axis from the sketch's elbow, which the
            // sketch puts 0.5 rad below the base's plane; the hinge turns the arm down for a
            // positive angle about its axis (-sin, cos, 0).
            forward[index(&fk, &format!("t{}", i + 1))] = angles[i] - sketch[i];
        }
        let f = gcs_compiler::solve(&fk, &a_fk, &forward, &branches(&a_fk))
            .unwrap_or_else(|e| panic!("{step} deg, forward: {e}"));
        let c = point_of(&f, "platform.centre");
        assert!(
            (c - centre).norm() <= 1e-10,
            "{step} deg: forward kinematics gives {c} for {centre}"
        );
    }
}

/// Pruned to an output, an arm's plan renumbers every branch it keeps, those of the turns onto
/// a plane or a cone as well as the intersections: the pruned plan is valid and, on each of its
/// branch combinations, places the tip where the whole plan does.
#[test]
fn an_arm_pruned_to_its_tip_keeps_its_branches_apart() {
    let arm = arm_3r();
    let path = format!("{}/../examples/{}", env!("CARGO_MANIFEST_DIR"), arm.file);
    let text = std::fs::read_to_string(&path).expect("the example") + "output forearm.tip;\n";
    let c = gcs_compiler::compile(arm.file, text.as_bytes()).expect("compiles");
    let (model, whole) = (&c.model, &c.analysis.plan);
    let (pruned, scope) = gcs_compiler::prune::prune(model, whole);
    assert_eq!(pruned.validate(model), Ok(()));
    assert!(pruned.branches.len() >= 2, "{:?}", pruned.branches);
    let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let tip = |s: &Solution| {
        let p = s.by_name().point("forearm.tip").map(<[f64]>::to_vec);
        p.expect("forearm.tip")
    };
    let params = model.default_params();
    let start: Vec<usize> = pruned.branches.iter().map(|b| b.default).collect();
    let varied: Vec<usize> = (0..start.len()).collect();
    let combinations = gcs_compiler::all::Combinations::new(&pruned, &start, &varied);
    assert_eq!(combinations.len(), 4);
    for k in 0..combinations.len() {
        let kept = combinations.nth(k);
        // The same branches, by name, in the whole plan; the others at the sketch's.
        let branches: Vec<usize> = (whole.branches.iter())
            .map(|b| {
                (pruned.branches.iter().zip(&kept))
                    .find(|(p, _)| p.name == b.name)
                    .map_or(b.default, |(_, &i)| i)
            })
            .collect();
        let a = gcs_compiler::solve_plan(model, &pruned, &scope, &params, &kept);
        let b = gcs_compiler::solve_plan(model, whole, &all, &params, &branches);
        match (a, b) {
            (Ok(a), Ok(b)) => assert_eq!(tip(&a), tip(&b), "branches {kept:?}"),
            (a, b) => assert_eq!(a.err(), b.err(), "branches {kept:?}"),
        }
    }
}

/// A SCARA arm at 1,000 random poses from random joint values, through its forward kinematics
/// written in the test (`forward`: the turns of the shoulder, the elbow and the roll and the
/// lift, to the tool's point and heading, sharing nothing with the plan). Both solutions (elbow
/// left and right) reach the pose to 1e-12, the joint values each reports (`joints`: two
/// turns, the travel and the roll, by their output names) give the pose back through the same
/// forward kinematics, and the arm the pose came from is among them (its elbow, `elbow` at the
/// shoulder's turn). Closed form: no default.
fn check_scara(
    path: &str,
    joints: [&str; 4],
    forward: impl Fn(f64, f64, f64, f64) -> (Vector3<f64>, f64),
    elbow: impl Fn(f64, f64) -> Vector3<f64>,
) {
    let text = std::fs::read_to_string(path).expect("the model");
    let compiled = gcs_compiler::compile(path, text.as_bytes()).expect("compiles");
    assert!(!compiled.has_errors(), "{:?}", compiled.diagnostics);
    let (model, plan) = (&compiled.model, &compiled.analysis.plan);
    assert!(
        plan.defaults.is_empty() && plan.iterations.is_empty(),
        "{path}"
    );
    let scope: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let param = |name: &str| {
        (model.params.iter())
            .position(|(_, p)| p.name == name)
            .unwrap_or_else(|| panic!("no param {name}"))
    };
    let (ipx, ipy, ipz, ih) = (param("px"), param("py"), param("pz"), param("heading"));
    let scalar = |s: &Solution, name: &str| {
        (s.scalars.iter())
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no {name}"))
            .1
    };
    let mut rng = Rng(0x5ca2_a5ee);
    let mut solutions = 0;
    for _ in 0..1000 {
        let (qa, qb, qc) = (rng.angle(), rng.angle(), rng.angle());
        let rise = 0.2 * rng.angle() / std::f64::consts::PI;
        let (p, heading) = forward(qa, qb, rise, qc);
        let mut params = model.default_params();
        (params[ipx], params[ipy], params[ipz], params[ih]) = (p.x, p.y, p.z, heading);
        let found = solve_all(model, plan, &scope, &params, &[]);
        assert_eq!(found.solutions.len(), 2, "{path}: {qa}, {qb}, {rise}, {qc}");
        let mut from = false;
        for sol in &found.solutions {
            assert!(sol.max_residual <= 1e-12, "{path}: {}", sol.max_residual);
            let tcp = point_of(sol, "tool.tcp");
            assert!(
                (tcp - p).norm() <= 1e-12,
                "{path}: tcp {tcp:?}, target {p:?}"
            );
            // The joint values reported give the pose back; a travel is measured from the
            // child's marker to the parent's, so the rise is its negative.
            let [a, b, t, c] = joints.map(|j| scalar(sol, j));
            let (back, h) = forward(a, b, -t, c);
            let turn = (h - heading + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                - std::f64::consts::PI;
            assert!(
                (back - p).norm() <= 1e-12 && turn.abs() <= 1e-12,
                "{path}: joints {a} {b} {t} {c} give {back:?} at {h}, not {p:?} at {heading}"
            );
            from |= (point_of(sol, "upper_arm.elbow") - elbow(qa, rise)).norm() <= 1e-9;
        }
        assert!(
            from,
            "{path}: {qa}, {qb}: the arm the pose came from is not a solution"
        );
        solutions += found.solutions.len();
    }
    eprintln!("{path}: {solutions} solutions over 1000 poses");
}

/// The tool's point and heading of a SCARA whose shoulder's axis is the z axis, with an upper
/// arm of 0.35 and a forearm of 0.30, the tool's point at height `tcp` raised by `rise`, at
/// turns `qa`, `qb`, `qc`.
fn scara_forward(tcp: f64) -> impl Fn(f64, f64, f64, f64) -> (Vector3<f64>, f64) {
    move |qa, qb, rise, qc| {
        let x = 0.35 * qa.cos() + 0.30 * (qa + qb).cos();
        let y = 0.35 * qa.sin() + 0.30 * (qa + qb).sin();
        (Vector3::new(x, y, tcp + rise), qa + qb + qc)
    }
}

/// The SCARA of `examples/scara.gcs`: the quill slides at the forearm's end (the tool's point
/// 0.1 high at the sketch), the upper arm at height 0.35.
#[test]
fn the_scara_arm_has_both_solutions_in_closed_form_at_random_poses() {
    check_scara(
        &format!("{}/../examples/scara.gcs", env!("CARGO_MANIFEST_DIR")),
        ["q1.angle", "q2.angle", "d3.travel", "q4.angle"],
        scara_forward(0.1),
        |qa, _| Vector3::new(0.35 * qa.cos(), 0.35 * qa.sin(), 0.35),
    );
}

/// A SCARA lifted at its base (`tests/models/scara_lift.gcs`): the column slides, carrying the
/// arm at height 0.4 (the tool's point 0.3 high at the sketch); the column's travel is the
/// first joint value.
#[test]
fn a_scara_lifted_at_its_base_has_both_solutions_in_closed_form_at_random_poses() {
    check_scara(
        &format!("{}/tests/models/scara_lift.gcs", env!("CARGO_MANIFEST_DIR")),
        ["q2.angle", "q3.angle", "d1.travel", "q4.angle"],
        scara_forward(0.3),
        |qa, rise| Vector3::new(0.35 * qa.cos(), 0.35 * qa.sin(), 0.4 + rise),
    );
}

/// The PUMA-like arm with its tool's pose from six params (`tests/models/puma_rotation_vector.gcs`):
/// the point, and the orientation as a rotation vector on the target body's `rotated` (the
/// angle its length, the axis its direction). At 1,000 random poses from random joint angles
/// (the rotation vector of the tool's frame read by nalgebra, apart from the plan): as many
/// solutions as the geometric count, each with the tool's point and axes on the target's to
/// 1e-12 (the target on the pose to 1e-9, the rotation vector's round trip), and the arm the
/// pose came from among them.
#[test]
fn a_pose_from_a_point_and_a_rotation_vector_has_every_solution() {
    let arm = puma();
    let path = format!(
        "{}/tests/models/puma_rotation_vector.gcs",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("the model");
    let compiled = gcs_compiler::compile(&path, text.as_bytes()).expect("compiles");
    assert!(!compiled.has_errors(), "{:?}", compiled.diagnostics);
    let (model, plan) = (&compiled.model, &compiled.analysis.plan);
    assert!(plan.defaults.is_empty() && plan.iterations.is_empty());
    let scope: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let index = |name: &str| {
        (model.params.iter())
            .position(|(_, p)| p.name == name)
            .unwrap_or_else(|| panic!("no param {name}"))
    };
    let names = ["px", "py", "pz", "rx", "ry", "rz"].map(index);
    let axis = |s: &Solution, name: &str| {
        let a = &(s.vectors.iter()).find(|(n, _)| n == name).expect(name).1;
        v([a[0], a[1], a[2]])
    };
    let mut rng = Rng(0x70a5_e5ee);
    let mut solutions = 0;
    for _ in 0..1000 {
        let q: Vec<f64> = (0..6).map(|_| rng.angle()).collect();
        let fk = forward(&arm, &q);
        let (r, t) = fk.last().expect("a body");
        let (p0, z0, x0) = arm.tool;
        let (p, z, x) = (r * v(p0) + t, r * v(z0), r * v(x0));
        // The target's frame carries its marker's z (0, 0, 1) to z and x (1, 0, 0) to x.
        let goal = Rotation3::from_basis_unchecked(&[x, z.cross(&x), z]);
        let turn = goal.scaled_axis();
        let mut params = model.default_params();
        for (i, value) in names.iter().zip([p.x, p.y, p.z, turn.x, turn.y, turn.z]) {
            params[*i] = value;
        }
        let found = solve_all(model, plan, &scope, &params, &[]);
        let want = count(arm.count.as_ref().expect("a count"), p, z);
        assert_eq!(found.solutions.len(), want, "q = {q:?}");
        for s in &found.solutions {
            let (tp, tz, tx) = (
                point_of(s, "tool.tcp"),
                axis(s, "tool.tcp.z"),
                axis(s, "tool.tcp.x"),
            );
            // On the target as gcs reads it from the params, to the solve's accuracy; the
            // target on the pose the params came from, to the rotation vector's round trip
            // (nalgebra's axis near a half turn loses digits: 4e-11 seen).
            let (gp, gz, gx) = (
                point_of(s, "goal.target"),
                axis(s, "goal.target.z"),
                axis(s, "goal.target.x"),
            );
            assert!(
                (tp - gp).norm() <= 1e-12 && (tz - gz).norm() <= 1e-12 && (tx - gx).norm() <= 1e-12,
                "q = {q:?}: the tool at {tp:?} {tz:?} {tx:?}, the target at {gp:?} {gz:?} {gx:?}"
            );
            assert!(
                (gp - p).norm() <= 1e-12 && (gz - z).norm() <= 1e-9 && (gx - x).norm() <= 1e-9,
                "q = {q:?}: the target at {gp:?} {gz:?} {gx:?}, not {p:?} {z:?} {x:?}"
            );
        }
        assert!(
            found.solutions.iter().any(|s| is_arm(&arm, s, &fk, 1e-8)),
            "q = {q:?}: the arm the pose came from is not among the solutions"
        );
        solutions += found.solutions.len();
    }
    eprintln!("puma, pose from a rotation vector: {solutions} solutions over 1000 poses");
}

/// The turn of the arm's base body about its joint's axis, from the sketch, in (-pi, pi].
fn base_turn(arm: &Arm, s: &Solution) -> f64 {
    let (r, _) = motions(arm, s)[0];
    let a = v(arm.joints[0].axis).normalize();
    let e = a
        .cross(&Vector3::x())
        .try_normalize(1e-9)
        .unwrap_or_else(|| a.cross(&Vector3::y()).normalize());
    let turned = r * e;
    a.dot(&e.cross(&turned)).atan2(e.dot(&turned))
}

/// The quartic branches read as their meanings say: by the base's counter-clockwise turn from
/// where it was, the three-circle problem's largest first (its first angle is the target's turn,
/// the base's backwards) and the planar sub-chain's ends' smallest first.
#[test]
fn the_quartic_branches_order_the_base_turns_as_their_meanings_say() {
    for (arm, branch, ascending) in [
        (spherical_bot(), "revolute_link_3_j3_link_2_j3", false),
        (three_parallel_bot(), "revolute_link_5_j5_link_4_j5", true),
    ] {
        let l = load(&arm);
        let (model, plan) = (&l.compiled.model, &l.compiled.analysis.plan);
        let mut rng = Rng(0x0b5e_55ed);
        let mut compared = 0;
        for _ in 0..60 {
            let q: Vec<f64> = arm.joints.iter().map(|_| rng.angle()).collect();
            let (params, _, _) = pose_params(&arm, &l, &q);
            let found = solve_all(model, plan, &l.scope, &params, &plan.sketch_defaults());
            let mut turns: Vec<(usize, f64)> = (found.solutions.iter())
                .map(|s| {
                    let k = (s.branches.iter())
                        .find(|(n, _)| n == branch)
                        .map(|&(_, k)| k)
                        .expect("the quartic's branch");
                    (k, base_turn(&arm, s))
                })
                .collect();
            turns.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
            for w in turns.windows(2) {
                let ((k0, t0), (k1, t1)) = (w[0], w[1]);
                if k0 == k1 {
                    // The same root: the same base turn, whatever the later branches.
                    assert!((t0 - t1).abs() <= 1e-9, "{}: {turns:?}", arm.file);
                    continue;
                }
                compared += 1;
                let ordered = if ascending { t0 < t1 } else { t0 > t1 };
                assert!(ordered, "{}: q = {q:?}: {turns:?}", arm.file);
            }
        }
        assert!(
            compared > 20,
            "{}: only {compared} pairs compared",
            arm.file
        );
    }
}

/// The Jacobian of the tool's pose in the joints that are not params, at joint angles `q`:
/// a column per joint, the tool point's velocity (and, where the pose fixes the tool's axes,
/// the angular velocity) of a unit turn about the joint's axis as the joints before it place it.
fn jacobian(arm: &Arm, q: &[f64]) -> nalgebra::DMatrix<f64> {
    let fk = forward(arm, q);
    let (r, t) = fk.last().expect("a body");
    let tool = r * v(arm.tool.0) + t;
    let free: Vec<usize> = (0..arm.joints.len())
        .filter(|j| !arm.joint_params.iter().any(|(k, _)| k == j))
        .collect();
    let rows = if arm.params.len() == 9 { 6 } else { 3 };
    let mut jac = nalgebra::DMatrix::zeros(rows, free.len());
    for (c, &k) in free.iter().enumerate() {
        let (rb, tb) = if k == 0 {
            (Rotation3::identity(), Vector3::zeros())
        } else {
            fk[k - 1]
        };
        let axis = rb * v(arm.joints[k].axis).normalize();
        let point = rb * v(arm.joints[k].point) + tb;
        let velocity = axis.cross(&(tool - point));
        for i in 0..3 {
            jac[(i, c)] = velocity[i];
            if rows == 6 {
                jac[(i + 3, c)] = axis[i];
            }
        }
    }
    jac
}

/// A singular configuration on the turn of joint `k` from `q`: the first angle past `q`'s,
/// counter-clockwise, where the Jacobian's determinant changes sign (bisected to rounding);
/// none when it keeps its sign over the whole turn.
fn singular_on_turn(arm: &Arm, q: &[f64], k: usize) -> Option<f64> {
    let det = |a: f64| {
        let mut at = q.to_vec();
        at[k] = a;
        jacobian(arm, &at).determinant()
    };
    let samples = 48;
    let step = std::f64::consts::TAU / samples as f64;
    let (mut lo, mut f_lo) = (q[k], det(q[k]));
    for i in 1..=samples {
        let hi = q[k] + i as f64 * step;
        let f_hi = det(hi);
        if f_lo == 0.0 {
            return Some(lo);
        }
        if f_lo.signum() != f_hi.signum() {
            let mut hi = hi;
            for _ in 0..64 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let f = det(mid);
                if f == 0.0 {
                    return Some(mid);
                }
                if f.signum() == f_lo.signum() {
                    (lo, f_lo) = (mid, f);
                } else {
                    hi = mid;
                }
            }
            return Some(0.5 * (lo + hi));
        }
        (lo, f_lo) = (hi, f_hi);
    }
    None
}

/// Poses at and next to an arm's singular configurations, found here by the Jacobian's rank
/// and not named (a wrist straight, an elbow stretched, a wrist centre on the base's axis,
/// whichever the arm has): random joint angles, one joint turned to where the determinant of
/// the Jacobian changes sign, then moved off it by 0, 1e-13, -1e-10, 1e-7, 1e-4 or -1e-3.
/// A typed error (no solution) is an answer; a wrong solution never is. Every solution
/// returned must reach the tool's pose to 1e-9 of the arm's reach, and close its joints to
/// the square root of rounding: at a fold two roots meet, and a root there is fixed only to
/// that (a joint off by `d` misses by about `d²`). Off a singularity by 1e-3, the arm the pose
/// came from must be among the solutions; nearer, a fold's two roots may be one within the
/// tolerance a pose is met to (1e-12 leaves a joint near a fold free by about 1e-6, which a
/// second fold downstream can magnify), and one root stands for both. The arm is compared to
/// 1e-6: 1e-3 from a fold, a quartic's pair of roots places the bodies to about 3e-8.
fn check_near_singularities(arm: &Arm, poses: usize, seed: u64) {
    let l = load(arm);
    let (model, plan) = (&l.compiled.model, &l.compiled.analysis.plan);
    let mut rng = Rng(seed);
    let free: Vec<usize> = (0..arm.joints.len())
        .filter(|j| !arm.joint_params.iter().any(|(k, _)| k == j))
        .collect();
    let reach = 2.0;
    let offsets = [0.0, 1e-13, -1e-10, 1e-7, 1e-4, -1e-3];
    let (mut answered, mut refused, mut singular_joints) = (0, 0, BTreeSet::new());
    for i in 0..poses {
        let (q, k) = loop {
            let mut q: Vec<f64> = arm.joints.iter().map(|_| rng.angle()).collect();
            let k = free[(rng.next() * free.len() as f64) as usize % free.len()];
            if let Some(a) = singular_on_turn(arm, &q, k) {
                q[k] = a + offsets[i % offsets.len()];
                break (q, k);
            }
        };
        singular_joints.insert(k);
        let fk = forward(arm, &q);
        let (params, p, _) = pose_params(arm, &l, &q);
        let (r, _) = fk.last().expect("a body");
        let (z, x) = (r * v(arm.tool.1), r * v(arm.tool.2));
        let found = solve_all(model, plan, &l.scope, &params, &plan.sketch_defaults());
        if found.solutions.is_empty() {
            refused += 1;
        } else {
            answered += 1;
        }
        for s in &found.solutions {
            let (rs, ts) = *motions(arm, s).last().expect("a body");
            let mut miss = (rs * v(arm.tool.0) + ts - p).norm();
            if arm.params.len() == 9 {
                miss = miss
                    .max((rs * v(arm.tool.1) - z).norm())
                    .max((rs * v(arm.tool.2) - x).norm());
            }
            assert!(
                s.max_residual <= f64::EPSILON.sqrt() * reach && miss <= 1e-9 * reach,
                "{}: q = {q:?} (joint {k} singular, off by {}): a wrong answer, its residual {}, the tool off by {miss}",
                arm.file,
                offsets[i % offsets.len()],
                s.max_residual
            );
        }
        if offsets[i % offsets.len()] == -1e-3 {
            assert!(
                found.solutions.iter().any(|s| is_arm(arm, s, &fk, 1e-6)),
                "{}: q = {q:?}: 1e-3 off a singularity of joint {k}, the arm the pose came from is not among {} solutions",
                arm.file,
                found.solutions.len()
            );
        }
    }
    eprintln!(
        "{}: near singularities of joints {singular_joints:?}: {answered} answered, {refused} refused",
        arm.file
    );
}

/// One test an arm, so that the arms run side by side.
macro_rules! near_singularities {
    ($($test:ident: $arm:expr, $seed:expr;)*) => {
        $(
            #[test]
            fn $test() {
                check_near_singularities(&$arm, 1000, $seed);
            }
        )*
    };
}

near_singularities! {
    the_3r_arm_gives_no_wrong_answer_near_its_singularities: arm_3r(), 0x3a3a_0001;
    the_puma_arm_gives_no_wrong_answer_near_any_singularity: puma(), 0x9a9a_0001;
    the_ur5_arm_gives_no_wrong_answer_near_its_singularities: ur5(), 0x0405_0001;
    the_irb6640_arm_gives_no_wrong_answer_near_its_singularities: irb6640(), 0x6640_0001;
    the_spherical_bot_gives_no_wrong_answer_near_its_singularities: spherical_bot(), 0x5b07_0001;
    the_three_parallel_bot_gives_no_wrong_answer_near_its_singularities: three_parallel_bot(), 0x3b07_0001;
    the_7_joint_arm_gives_no_wrong_answer_near_its_singularities: iiwa(), 0x0007_0001;
}

/// A cylindrical (RPP) robot, `tests/models/cylindrical_robot.gcs`: no closed form is
/// recognised, and the column's turn and the carriage's place are iterated together, closing
/// the arm's slide onto the carriage's guide (a point on a line of space, two equations; one
/// default closing it alone left the column's turn free and the model "under-constrained").
/// At random reachable targets, drawn from the joints through forward kinematics written here,
/// every solution reaches the target, and both arms (the arm out towards the target, and the
/// column turned half a turn with the arm slid back through it) are found.
#[test]
fn a_cylindrical_robot_is_well_constrained_and_reaches_its_targets() {
    let text = std::fs::read_to_string(format!(
        "{}/../tests/models/cylindrical_robot.gcs",
        env!("CARGO_MANIFEST_DIR")
    ))
    .expect("the model");
    let compiled =
        gcs_compiler::compile("cylindrical_robot.gcs", text.as_bytes()).expect("compiles");
    assert!(!compiled.has_errors(), "{:?}", compiled.diagnostics);
    let (model, analysis) = (&compiled.model, &compiled.analysis);
    let plan = &analysis.plan;
    assert!(
        analysis.free_defaults().is_empty() && analysis.redundant.is_empty(),
        "well-constrained: no free default, no redundancy"
    );
    let scope: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let scalar = |s: &Solution, name: &str| {
        (s.scalars.iter())
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("no scalar {name}"))
            .1
    };
    let mut rng = Rng(0x0c71_5eed);
    let (poses, mut both) = (200, 0);
    for _ in 0..poses {
        // The column's turn, the carriage's rise and the arm's reach from the column's axis.
        let (turn, rise, reach) = (rng.angle(), rng.next() - 0.4, 0.2 + rng.next());
        let target = Vector3::new(turn.cos() * reach, turn.sin() * reach, 0.45 + rise);
        let mut params = model.default_params();
        for (name, value) in [("tx", target.x), ("ty", target.y), ("tz", target.z)] {
            let i = (model.params.iter())
                .position(|(_, p)| p.name == name)
                .expect("a param");
            params[i] = value;
        }
        let found = solve_all(model, plan, &scope, &params, &plan.sketch_defaults());
        for s in &found.solutions {
            let tip = point_of(s, "arm.tip");
            assert!(
                s.max_residual <= 1e-12 && (tip - target).norm() <= 1e-12,
                "target {target:?}: a solution off by {} (tip {tip:?})",
                s.max_residual
            );
        }
        // The joint angle is the base's x axis from the column's: minus the column's turn.
        let wrapped = |a: f64| {
            (a + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU) - std::f64::consts::PI
        };
        let drawn = |s: &Solution| {
            wrapped(scalar(s, "q1.angle") + turn).abs() <= 1e-9
                && (scalar(s, "d2.travel") - rise).abs() <= 1e-9
                && (scalar(s, "d3.travel") - (reach - 0.4)).abs() <= 1e-9
        };
        let flipped = |s: &Solution| {
            wrapped(scalar(s, "q1.angle") + turn + std::f64::consts::PI).abs() <= 1e-9
                && (scalar(s, "d3.travel") - (-reach - 0.4)).abs() <= 1e-9
        };
        assert!(
            found.solutions.iter().any(drawn),
            "target {target:?}: the drawn robot is not among {} solutions",
            found.solutions.len()
        );
        both += usize::from(found.solutions.iter().any(flipped));
    }
    assert_eq!(
        both, poses,
        "the flipped robot found at {both} of {poses} targets"
    );
}
