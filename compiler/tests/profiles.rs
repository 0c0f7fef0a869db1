//! Closed profiles whose directions are all known: a stair-step profile of horizontal and
//! vertical segments, every corner filleted, one point fixed and every edge's length given but
//! the first's and the last's (`families::stair_profile`, the profile of the sketch benchmarks
//! of SolveSpace and PlaneGCS). Its closure is linear in the segments' slides and the two free
//! lengths, and the linear stage solves it in closed form: no default, no iteration, from a
//! sketch a user's drag left anywhere near it, at every size; with both closing lengths given
//! the two extra lengths are redundant (reported, checked), not a degenerate configuration.
//!
//! Every solution is judged by the verifier, which shares nothing with the plan, and compared
//! with the profile as drawn exactly (the sketch with no jitter, which the family writes from
//! its corners).

use gcs_compiler::families::{stair_profile, stair_profile_sketched, StairSketch};
use gcs_compiler::pipeline::Compiled;
use gcs_compiler::plan::{Op, PlanarOp};
use gcs_compiler::solution::Solution;
use gcs_runtime::error::ErrorKind;

fn compiled(text: &str) -> Compiled {
    gcs_compiler::compile("profile.gcs", text.as_bytes()).unwrap_or_else(|e| panic!("{e:?}"))
}

fn solved(c: &Compiled) -> Result<Solution, gcs_runtime::error::SolveError> {
    let branches: Vec<usize> = c.analysis.plan.branches.iter().map(|b| b.default).collect();
    gcs_compiler::solve(&c.model, &c.analysis, &c.model.default_params(), &branches)
}

/// The profile's size: its largest coordinate.
fn size(s: &Solution) -> f64 {
    (s.points.iter())
        .flat_map(|(_, p)| p.iter())
        .fold(1.0_f64, |m, v| m.max(v.abs()))
}

fn linear_systems(c: &Compiled) -> usize {
    (c.analysis.plan.steps.iter())
        .filter(|s| matches!(s.op, Op::Planar(PlanarOp::Linear(_))))
        .count()
}

/// The edge counts the issue names.
const EDGES: [usize; 4] = [4, 16, 64, 256];

#[test]
fn stair_profiles_close_in_closed_form_at_every_size() {
    for n in EDGES {
        let c = compiled(&stair_profile(n));
        let plan = &c.analysis.plan;
        assert!(
            plan.defaults.is_empty(),
            "{n} edges: defaults {:?}",
            plan.defaults
        );
        assert!(plan.iterations.is_empty(), "{n} edges: iterates");
        assert_eq!(linear_systems(&c), 1, "{n} edges");
        assert!(c.analysis.unsolved.is_empty() && c.analysis.redundant.is_empty());
        let words = gcs_compiler::explain::explain(&c.model, plan);
        assert!(!words.contains("default"), "{n} edges:\n{words}");
        assert!(words.contains("linear system"), "{n} edges");
        let s = solved(&c).unwrap_or_else(|e| panic!("{n} edges: {e}"));
        assert!(
            s.max_residual <= 1e-12 * size(&s),
            "{n} edges: {}",
            s.max_residual
        );
    }
}

/// Every point of the sketch moved by up to `jitter` in x and y, several times: each solve
/// satisfies every constraint to 1e-12 of the profile's size and lands on the profile as
/// drawn. At 4 edges the jitter is 5% of the profile's size, as the issue asks; at more edges
/// it is 0.2 (two fifths of the fillets' radius, a twentieth of an edge): 5% of a 256-edge
/// profile's size moves points by six edges, flips which side of each segment its fillet
/// lies on and which way each segment runs, which the sketch decides, so that the sketch
/// poses another model (the model is read from the sketch; no solver can keep a profile the
/// sketch no longer draws).
#[test]
fn stair_profiles_solve_from_moved_sketches_onto_the_profile_drawn() {
    for n in EDGES {
        let exact = solved(&compiled(&stair_profile(n))).expect("the exact profile");
        let scale = size(&exact);
        let jitter = if n == 4 { 0.05 * scale } else { 0.2 };
        // Ten sketches each, three at 256 edges (whose analysis takes a while in a debug build).
        for seed in 0..if n > 64 { 3 } else { 10 } {
            let how = StairSketch {
                jitter,
                seed,
                closed: false,
            };
            let c = compiled(&stair_profile_sketched(n, &how));
            assert!(
                c.analysis.plan.defaults.is_empty(),
                "{n} edges, seed {seed}"
            );
            let s = solved(&c).unwrap_or_else(|e| panic!("{n} edges, seed {seed}: {e}"));
            assert!(
                s.max_residual <= 1e-12 * scale,
                "{n} edges, seed {seed}: residual {}",
                s.max_residual
            );
            for ((name, got), (_, want)) in s.points.iter().zip(&exact.points) {
                let off = (got[0] - want[0]).hypot(got[1] - want[1]);
                assert!(
                    off <= 1e-9 * scale,
                    "{n} edges, seed {seed}: {name} off by {off}"
                );
            }
        }
    }
}

/// Both closing lengths given, and consistent: two constraints too many, each reported as
/// redundant (a run-time check), never as a degenerate configuration; the profile solves. One
/// of them off by 0.5: the solve names a constraint of the profile's closure with that gap.
#[test]
fn a_profile_with_both_closing_lengths_is_redundant_not_degenerate() {
    for n in EDGES {
        for seed in 0..3 {
            let how = StairSketch {
                jitter: if seed == 0 { 0.0 } else { 0.1 },
                seed,
                closed: true,
            };
            let text = stair_profile_sketched(n, &how);
            let c = compiled(&text);
            assert_eq!(
                c.analysis.redundant.len(),
                2,
                "{n} edges, seed {seed}: redundant {:?}",
                c.analysis.redundant
            );
            assert!(c.analysis.plan.defaults.is_empty(), "{n} edges");
            let s = solved(&c).unwrap_or_else(|e| panic!("{n} edges, seed {seed}: {e}"));
            assert!(
                s.max_residual <= 1e-12 * size(&s),
                "{n} edges: {}",
                s.max_residual
            );
        }
        // The first edge's length 0.5 too long.
        let how = StairSketch {
            closed: true,
            ..StairSketch::default()
        };
        let text = stair_profile_sketched(n, &how).replace("length(L0) = 3;", "length(L0) = 3.5;");
        let c = compiled(&text);
        let e = solved(&c).expect_err("a closing length off by 0.5");
        assert_eq!(e.kind, ErrorKind::Inconsistent, "{n} edges: {e}");
        assert!((e.magnitude - 0.5).abs() < 1e-9, "{n} edges: {e}");
    }
}

/// The rounded rectangle with a different radius and edge: the same plan, every constraint
/// met to rounding.
#[test]
fn a_profile_solves_at_other_params() {
    let c = compiled(&stair_profile(16));
    let r = c
        .model
        .param_named("r")
        .expect("param r")
        .into_raw()
        .into_u32() as usize;
    let branches: Vec<usize> = c.analysis.plan.branches.iter().map(|b| b.default).collect();
    for radius in [0.3, 0.45, 0.7] {
        let mut params = c.model.default_params();
        params[r] = radius;
        let s = gcs_compiler::solve(&c.model, &c.analysis, &params, &branches)
            .unwrap_or_else(|e| panic!("r = {radius}: {e}"));
        assert!(
            s.max_residual <= 1e-12 * size(&s),
            "r = {radius}: {}",
            s.max_residual
        );
    }
}
