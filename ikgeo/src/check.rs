//! The check: for random poses of each arm (from random joint angles through `arms`' forward
//! kinematics, apart from both solvers), ik-geo's `Robot::ik` and gcs's generated `solve_all`
//! return the same solution sets. Every exact ik-geo solution (ik-geo flags least-squares ones;
//! those are skipped) must match one of gcs's to `TOL` in every joint angle (differences
//! wrapped to (-pi, pi]), and every gcs solution one of ik-geo's. gcs's joint angles are read
//! from its solved body frames (`Angles`).

use crate::arms::{self, Arm, Pose};
use crate::{compare, ik_geo_robot, ik_geo_solutions, pose_error, Angles, Gcs};
use std::fmt::Write as _;

/// The tolerance on joint angles, radians.
pub const TOL: f64 = 1e-10;

/// A pose error this small is a solution to machine precision (the arms' reach is about 3).
pub const EXACT_POSE: f64 = 1e-12;

/// How far apart (in joint angles) two solutions of a near-singular pose may be and still be
/// one root found to different accuracy (the quartic arms' worst matched pair is 9.5e-11).
pub const NEAR: f64 = 1e-7;

/// The seed of an arm's poses: the same in the check and the bench.
pub fn seed(arm: &Arm) -> u64 {
    0x9e37_79b9_7f4a_7c15
        ^ arm
            .name
            .bytes()
            .fold(0u64, |h, b| h.wrapping_mul(31) + b as u64)
}

/// The totals over one arm's poses.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// The arm.
    pub arm: &'static str,
    /// Poses compared.
    pub poses: usize,
    /// Poses where the two sets differ (an unmatched solution on either side).
    pub mismatched_poses: usize,
    /// ik-geo's exact solutions with no gcs solution within `TOL`.
    pub ik_geo_unmatched: usize,
    /// gcs's solutions with no ik-geo solution within `TOL`.
    pub gcs_unmatched: usize,
    /// ik-geo's exact solutions, its least-squares ones, gcs's solutions.
    pub counts: (usize, usize, usize),
    /// Poses where `solve_all` said its list may not be complete.
    pub incomplete: usize,
    /// The largest joint-angle distance between matched solutions.
    pub worst_match: f64,
    /// The largest departure of a gcs link's relative rotation from a turn about its joint.
    pub worst_axis: f64,
    /// The largest pose error of a gcs solution's joint angles (this crate's kinematics).
    pub worst_gcs_pose: f64,
    /// The largest pose error of an exact ik-geo solution.
    pub worst_ik_geo_pose: f64,
    /// Poses where `solve` (the sketch's branches) found a solution; of those, how many are in
    /// ik-geo's set.
    pub one_found: (usize, usize),
    /// Poses whose drawing joint angles are among gcs's solutions.
    pub drawn_found: usize,
    /// The first few mismatched poses, described: those whose solution counts differ first.
    pub examples: String,
    /// How many of `examples` are poses whose solution counts differ.
    pub counted_examples: usize,
    /// Of ik-geo's unmatched exact solutions, those that miss the pose by more than
    /// [`EXACT_POSE`]: a root ik-geo found only roughly, which gcs may have found exactly.
    pub ik_geo_unmatched_rough: usize,
    /// Of gcs's unmatched solutions, those that reach the pose to [`EXACT_POSE`] (by this
    /// crate's forward kinematics, apart from both solvers): solutions ik-geo did not return.
    pub gcs_unmatched_exact: usize,
    /// ik-geo's exact solutions that reach the pose to [`EXACT_POSE`], and the angles the pose
    /// was drawn from, with no gcs solution within [`NEAR`]: a root gcs missed (not one found by
    /// both to different accuracy).
    pub gcs_missed: usize,
    /// Of those, the ones at poses whose gcs list says it is complete: a false claim.
    pub missed_in_complete: usize,
    /// gcs's solutions that miss the pose by more than [`EXACT_POSE`]: wrong answers.
    pub gcs_wrong: usize,
}

/// Compares both solvers over `n` poses of `arm`, whose generated solver is `G`.
pub fn check<G: Gcs>(arm: &Arm, n: usize) -> Report {
    let robot = ik_geo_robot(arm);
    let reader = Angles::new(arm);
    let mut r = Report {
        arm: arm.name,
        poses: n,
        ..Report::default()
    };
    for (k, pose) in arms::poses(arm, n, seed(arm)).iter().enumerate() {
        let params = G::params(pose);
        let ik = ik_geo_solutions(&robot, pose);
        let (all, complete) = G::all(&params);
        let c = compare(arm, &ik, &all, TOL);
        r.incomplete += usize::from(!complete);
        r.ik_geo_unmatched += c.ik_geo_unmatched;
        r.gcs_unmatched += c.gcs_unmatched;
        r.counts.0 += c.counts.0;
        r.counts.1 += c.counts.1;
        r.counts.2 += c.counts.2;
        r.worst_match = r.worst_match.max(c.worst_match);
        r.worst_axis = r.worst_axis.max(c.worst_axis);
        let gcs_q: Vec<[f64; 6]> = all.iter().map(|l| reader.read(l).0).collect();
        for q in &gcs_q {
            r.worst_gcs_pose = r.worst_gcs_pose.max(pose_error(arm, q, pose));
        }
        for (q, _) in ik.iter().filter(|s| !s.1) {
            r.worst_ik_geo_pose = r.worst_ik_geo_pose.max(pose_error(arm, q, pose));
        }
        let unmatched = |q: &[f64; 6], among: &mut dyn Iterator<Item = &[f64; 6]>| {
            among.fold(true, |u, p| u && arms::angle_distance(p, q) > TOL)
        };
        let mut missed = 0;
        for (q, _) in ik.iter().filter(|s| !s.1) {
            let exact = pose_error(arm, q, pose) <= EXACT_POSE;
            if unmatched(q, &mut gcs_q.iter()) && !exact {
                r.ik_geo_unmatched_rough += 1;
            }
            let near = gcs_q.iter().any(|p| arms::angle_distance(p, q) <= NEAR);
            if exact && !near {
                missed += 1;
            }
        }
        for q in &gcs_q {
            let exact = pose_error(arm, q, pose) <= EXACT_POSE;
            if unmatched(q, &mut ik.iter().map(|s| &s.0)) && exact {
                r.gcs_unmatched_exact += 1;
            }
            if !exact {
                r.gcs_wrong += 1;
            }
        }
        if gcs_q
            .iter()
            .any(|q| arms::angle_distance(q, &pose.q) <= TOL)
        {
            r.drawn_found += 1;
        }
        // The angles the pose was drawn from are a solution to rounding, whatever ik-geo finds
        // (its search on `two_parallel_bot` finds few): one with no gcs solution near is
        // missed, and the pose is described first.
        if !gcs_q
            .iter()
            .any(|q| arms::angle_distance(q, &pose.q) <= NEAR)
        {
            missed += 1;
            let mut s = String::new();
            describe(&mut s, arm, k, pose, &ik, &gcs_q);
            r.examples.insert_str(0, &s);
        }
        r.gcs_missed += missed;
        if complete {
            r.missed_in_complete += missed;
        }
        if let Some(one) = G::one(&params) {
            r.one_found.0 += 1;
            let q = reader.read(&one).0;
            if ik.iter().any(|(p, _)| arms::angle_distance(p, &q) <= TOL) {
                r.one_found.1 += 1;
            }
        }
        if c.ik_geo_unmatched + c.gcs_unmatched > 0 {
            r.mismatched_poses += 1;
            // Poses where the counts differ first: a root one side missed, not two answers
            // to a pose that differ past `TOL`.
            if c.counts.0 != c.counts.2 && r.counted_examples < 3 {
                r.counted_examples += 1;
                let mut s = String::new();
                describe(&mut s, arm, k, pose, &ik, &gcs_q);
                r.examples.insert_str(0, &s);
            } else if r.mismatched_poses <= 3 {
                describe(&mut r.examples, arm, k, pose, &ik, &gcs_q);
            }
        }
    }
    r
}

fn describe(
    out: &mut String,
    arm: &Arm,
    k: usize,
    pose: &Pose,
    ik: &[([f64; 6], bool)],
    gcs: &[[f64; 6]],
) {
    let fmt = |q: &[f64; 6]| {
        let v: Vec<String> = q.iter().map(|x| format!("{x:+.12}")).collect();
        v.join(", ")
    };
    let _ = writeln!(out, "  pose {k}, drawn from q = ({})", fmt(&pose.q));
    for (q, ls) in ik {
        let _ = writeln!(
            out,
            "    ik-geo{} ({}), pose error {:.1e}",
            if *ls { " least-squares" } else { "" },
            fmt(q),
            pose_error(arm, q, pose)
        );
    }
    for q in gcs {
        let _ = writeln!(
            out,
            "    gcs ({}), pose error {:.1e}",
            fmt(q),
            pose_error(arm, q, pose)
        );
    }
}

impl Report {
    /// Whether gcs gave no wrong solution, and missed no solution ik-geo found to machine
    /// precision (nor the drawing angles) where its list says it is complete: the check of the
    /// quartic arms, whose roots near a fold the two sides find to different accuracy, and of
    /// the searched one, whose list does not claim completeness.
    pub fn nothing_missed_or_wrong(&self) -> bool {
        self.missed_in_complete == 0 && self.gcs_wrong == 0
    }

    /// Whether both sets agreed at every pose.
    pub fn agrees(&self) -> bool {
        self.ik_geo_unmatched == 0 && self.gcs_unmatched == 0
    }

    /// The report in words.
    pub fn text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{}: {} poses, {} with different solution sets; ik-geo exact solutions unmatched {}, gcs solutions unmatched {}",
            self.arm, self.poses, self.mismatched_poses, self.ik_geo_unmatched, self.gcs_unmatched
        );
        let _ = writeln!(
            s,
            "  of those: ik-geo's missing the pose by more than {EXACT_POSE:e} {}, gcs's reaching it to {EXACT_POSE:e} {}; ik-geo's reaching it, or the drawing angles, with no gcs solution within {NEAR:e} (missed by gcs) {} ({} where gcs's list says it is complete); gcs's missing it (wrong) {}",
            self.ik_geo_unmatched_rough, self.gcs_unmatched_exact, self.gcs_missed, self.missed_in_complete, self.gcs_wrong
        );
        let _ = writeln!(
            s,
            "  solutions: ik-geo {} exact + {} least-squares, gcs {} (solve_all incomplete at {} poses); the drawing angles among gcs's at {} poses",
            self.counts.0, self.counts.1, self.counts.2, self.incomplete, self.drawn_found
        );
        let _ = writeln!(
            s,
            "  largest: matched angle difference {:.1e}, gcs pose error {:.1e}, ik-geo exact pose error {:.1e}, gcs joint off its axis {:.1e}",
            self.worst_match, self.worst_gcs_pose, self.worst_ik_geo_pose, self.worst_axis
        );
        let _ = writeln!(
            s,
            "  solve on the sketch's branches: a solution at {} poses, {} of them in ik-geo's set",
            self.one_found.0, self.one_found.1
        );
        s.push_str(&self.examples);
        s
    }
}
