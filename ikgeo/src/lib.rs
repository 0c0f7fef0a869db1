//! gcs's generated arm solvers against ik-geo 0.1.2 (IK-Geo, Elias and Wen's subproblem
//! decomposition), on ik-geo's own arms: the kinematics (`arms`), their `.gcs` models
//! (`model`, written into `models/`), the solvers `build.rs` generates from those models, and
//! what the check (`src/main.rs`) and the bench (`benches/ik.rs`) share: reading joint angles
//! from gcs's solved body frames, and comparing solution sets.
//!
//! Four analyse in closed form (no default, no iteration): `ur5` and `irb6640` by circles
//! and spheres (a planar sub-chain's plane, a pivoted pair, a spherical wrist), `spherical_bot`
//! by the three-circle problem and `three_parallel_bot` by a planar sub-chain's ends (ik-geo's
//! subproblems 5 and 6, each a quartic). `two_parallel_bot` has no closed form: one default,
//! the last joint's turn, which `solve_all` scans, subproblem 6 inside.

pub mod arms;
pub mod check;
pub mod model;

use arms::{angle_distance, Arm, Pose};
use ik_geo::nalgebra::{Matrix3, Vector3};
use ik_geo::robot::{IKSolver, Robot};

/// The generated solver of `models/ikgeo_ur5.gcs`.
pub mod ur5 {
    gcs_runtime::include_solver!("ikgeo_ur5");
}

/// The generated solver of `models/ikgeo_irb6640.gcs`.
pub mod irb6640 {
    gcs_runtime::include_solver!("ikgeo_irb6640");
}

/// The generated solver of `models/ikgeo_spherical_bot.gcs` (the three-circle problem). Its
/// code may hold a length of 1.414213562373095 (the arm's), which clippy takes for `SQRT_2`.
#[allow(clippy::approx_constant)]
pub mod spherical_bot {
    gcs_runtime::include_solver!("ikgeo_spherical_bot");
}

/// The generated solver of `models/ikgeo_three_parallel_bot.gcs` (a planar sub-chain's ends).
pub mod three_parallel_bot {
    gcs_runtime::include_solver!("ikgeo_three_parallel_bot");
}

/// The generated solver of `models/ikgeo_two_parallel_bot.gcs` (an outer iteration: a scan of
/// the last joint's turn).
#[allow(clippy::approx_constant)]
pub mod two_parallel_bot {
    gcs_runtime::include_solver!("ikgeo_two_parallel_bot");
}

/// A rotation of gcs's frames (nalgebra of gcs-runtime) as ik-geo's nalgebra has it.
fn rotation(f: &gcs_runtime::frame::Frame3) -> Matrix3<f64> {
    let m = f.rotation.to_rotation_matrix();
    let m = m.matrix();
    Matrix3::from_fn(|r, c| m[(r, c)])
}

/// What the check and the bench ask of one arm's generated solver.
pub trait Gcs {
    /// The solver's params.
    type Params;
    /// The params of a pose (the target marker's point, z and x axes).
    fn params(pose: &Pose) -> Self::Params;
    /// Every solution's link rotations from the sketch (`link_1` to `tool`), and whether
    /// `solve_all` says its list is complete.
    fn all(params: &Self::Params) -> (Vec<[Matrix3<f64>; 6]>, bool);
    /// The solution on the sketch's branches (and defaults), if `solve` finds one.
    fn one(params: &Self::Params) -> Option<[Matrix3<f64>; 6]>;
    /// `solve_all`, for timing: how many solutions.
    fn time_all(params: &Self::Params) -> usize;
    /// `solve`, for timing: whether it found one.
    fn time_one(params: &Self::Params) -> bool;
    /// `solve_all` and every solution's joint angles read from its frames ([`Angles`]), for
    /// timing: the sum of the angles.
    fn time_all_angles(angles: &Angles, params: &Self::Params) -> f64;
}

macro_rules! gcs_arm {
    ($ty:ident, $m:ident) => {
        /// The generated solver of this arm, as [`Gcs`].
        #[derive(Debug, Clone, Copy)]
        pub struct $ty;

        impl $ty {
            fn links(s: &$m::Solution) -> [Matrix3<f64>; 6] {
                [
                    rotation(&s.link_1()),
                    rotation(&s.link_2()),
                    rotation(&s.link_3()),
                    rotation(&s.link_4()),
                    rotation(&s.link_5()),
                    rotation(&s.tool()),
                ]
            }
        }

        impl Gcs for $ty {
            type Params = $m::Params;
            fn params(pose: &Pose) -> $m::Params {
                let [px, py, pz, zx, zy, zz, xx, xy, xz] = pose.params();
                $m::Params {
                    px,
                    py,
                    pz,
                    zx,
                    zy,
                    zz,
                    xx,
                    xy,
                    xz,
                }
            }
            fn all(params: &$m::Params) -> (Vec<[Matrix3<f64>; 6]>, bool) {
                let all = $m::solve_all(params, &Default::default());
                (all.iter().map(Self::links).collect(), all.is_complete())
            }
            fn one(params: &$m::Params) -> Option<[Matrix3<f64>; 6]> {
                $m::solve(params, &Default::default(), &Default::default())
                    .ok()
                    .map(|s| Self::links(&s))
            }
            #[inline]
            fn time_all(params: &$m::Params) -> usize {
                $m::solve_all(params, &Default::default()).len()
            }
            #[inline]
            fn time_one(params: &$m::Params) -> bool {
                $m::solve(params, &Default::default(), &Default::default()).is_ok()
            }
            #[inline]
            fn time_all_angles(angles: &Angles, params: &$m::Params) -> f64 {
                $m::solve_all(params, &Default::default())
                    .iter()
                    .map(|s| angles.read(&Self::links(s)).0.iter().sum::<f64>())
                    .sum()
            }
        }
    };
}

gcs_arm!(Ur5, ur5);
gcs_arm!(Irb6640, irb6640);
gcs_arm!(SphericalBot, spherical_bot);
gcs_arm!(ThreeParallelBot, three_parallel_bot);
gcs_arm!(TwoParallelBot, two_parallel_bot);

/// ik-geo's solver of an arm, by its name.
pub fn ik_geo_robot(arm: &Arm) -> Robot {
    match arm.name {
        "ur5" => ik_geo::robot::ur5(),
        "irb6640" => ik_geo::robot::irb6640(),
        "spherical_bot" => ik_geo::robot::spherical_bot(),
        "three_parallel_bot" => ik_geo::robot::three_parallel_bot(),
        "two_parallel_bot" => ik_geo::robot::two_parallel_bot(),
        other => panic!("no ik-geo arm {other}"),
    }
}

/// ik-geo's solutions at a pose: joint angles, and whether each is a least-squares one.
pub fn ik_geo_solutions(robot: &Robot, pose: &Pose) -> Vec<([f64; 6], bool)> {
    robot
        .ik(pose.r, pose.t)
        .into_iter()
        .map(|(q, ls)| (std::array::from_fn(|i| q[i]), ls))
        .collect()
}

/// Reads joint angles from gcs's link rotations (each from the sketch): link `i`'s rotation
/// from the zero configuration is the solved one times the sketch's, and the angle of link
/// `i` relative to link `i - 1` is read about joint `i`'s axis (`Arm::angles`).
#[derive(Debug, Clone)]
pub struct Angles {
    arm: Arm,
    sketch: [Matrix3<f64>; 6],
}

impl Angles {
    /// The reader of `arm`'s angles, with its sketch's rotations computed once.
    pub fn new(arm: &Arm) -> Angles {
        let links = arm.links(&arm.sketch);
        Angles {
            arm: *arm,
            sketch: std::array::from_fn(|i| links[i].r),
        }
    }

    /// The joint angles, wrapped to (-pi, pi], and how far any relative rotation is from a
    /// turn about its joint's axis.
    pub fn read(&self, from_sketch: &[Matrix3<f64>; 6]) -> ([f64; 6], f64) {
        let rotations: [Matrix3<f64>; 6] = std::array::from_fn(|i| from_sketch[i] * self.sketch[i]);
        self.arm.angles(&rotations)
    }
}

/// Joint angles from gcs's link rotations, as [`Angles::read`] reads them.
pub fn gcs_angles(arm: &Arm, from_sketch: &[Matrix3<f64>; 6]) -> ([f64; 6], f64) {
    Angles::new(arm).read(from_sketch)
}

/// The tool's pose error of joint angles `q` against `pose`: the largest of the point's
/// distance and the rotation's entries' differences.
pub fn pose_error(arm: &Arm, q: &[f64; 6], pose: &Pose) -> f64 {
    let (r, t): (Matrix3<f64>, Vector3<f64>) = arm.pose(q);
    (t - pose.t).norm().max((r - pose.r).amax())
}

/// How one pose compared.
#[derive(Debug, Clone, Default)]
pub struct Compared {
    /// ik-geo's exact solutions (not least-squares) with no gcs solution within the tolerance.
    pub ik_geo_unmatched: usize,
    /// gcs's solutions with no ik-geo solution (exact or not) within the tolerance.
    pub gcs_unmatched: usize,
    /// ik-geo's exact solutions, least-squares ones, gcs's solutions.
    pub counts: (usize, usize, usize),
    /// The largest distance from a matched solution to its match.
    pub worst_match: f64,
    /// The largest departure of a gcs relative rotation from a turn about its joint's axis.
    pub worst_axis: f64,
}

/// Compares ik-geo's and gcs's solution sets at one pose, joint angles to `tol`.
pub fn compare(
    arm: &Arm,
    ik_geo: &[([f64; 6], bool)],
    gcs: &[[Matrix3<f64>; 6]],
    tol: f64,
) -> Compared {
    let mut c = Compared::default();
    let reader = Angles::new(arm);
    let gcs: Vec<[f64; 6]> = gcs
        .iter()
        .map(|r| {
            let (q, off) = reader.read(r);
            c.worst_axis = c.worst_axis.max(off);
            q
        })
        .collect();
    let exact: Vec<&[f64; 6]> = ik_geo.iter().filter(|s| !s.1).map(|s| &s.0).collect();
    c.counts = (exact.len(), ik_geo.len() - exact.len(), gcs.len());
    let nearest = |q: &[f64; 6], among: &mut dyn Iterator<Item = &[f64; 6]>| {
        among
            .map(|p| angle_distance(p, q))
            .fold(f64::INFINITY, f64::min)
    };
    for q in &exact {
        let d = nearest(q, &mut gcs.iter());
        if d > tol {
            c.ik_geo_unmatched += 1;
        } else {
            c.worst_match = c.worst_match.max(d);
        }
    }
    for q in &gcs {
        let d = nearest(q, &mut ik_geo.iter().map(|s| &s.0));
        if d > tol {
            c.gcs_unmatched += 1;
        } else {
            c.worst_match = c.worst_match.max(d);
        }
    }
    c
}
