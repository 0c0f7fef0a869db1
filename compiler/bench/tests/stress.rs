//! Stress: sweeps through the cases where numeric solvers struggle — a four-bar at toggle, a
//! Grashof change-point linkage, circles that become tangent and then miss, lines that become
//! parallel, and the four-bar at scales from 1e-6 to 1e6.
//!
//! Every sample must end either in an answer whose residual (by `verify`) is at machine
//! precision for its scale, or in a `SolveError` that names a constraint and carries a finite
//! magnitude; no panic. On each fixed branch the plan's answers must stay continuous (no flip;
//! counted against a Newton continuation from the previous answer). The baseline's flips on
//! the same sweeps are counted and printed, not asserted: they are what the plan avoids.
//! `cargo test -p gcs-bench --release --test stress -- --nocapture` prints the table that
//! docs/BENCHMARKS.md records.

use gcs_bench::bench::{self, Sweep};

struct Case {
    name: &'static str,
    /// The model's length scale.
    scale: f64,
    text: String,
    /// The param swept, and its values.
    param: &'static str,
    values: Vec<f64>,
    /// The residual an answer may have, relative to its size (its largest coordinate, at
    /// least the model's scale): machine precision.
    tolerance: f64,
}

/// Constraints whose residual is an angle (radians) rather than a length.
fn is_angle(kind: gcs_lang::constraints::ConstraintKind) -> bool {
    use gcs_lang::constraints::ConstraintKind as K;
    matches!(
        kind,
        K::Angle | K::Parallel | K::Perpendicular | K::Horizontal | K::Vertical | K::OffsetX
    )
}

/// What `verify` measures on an answer, for the constraints among the geoms the outputs need
/// (only those are solved): each constraint's text and its residual in units of `length`, or
/// in radians for an angle.
fn relative_residuals(
    model: &gcs_lang::Model,
    scope: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
    answer: &gcs_compiler::solution::Solution,
    params: &[f64],
    length: f64,
) -> Vec<(String, f64)> {
    gcs_compiler::verify::residuals(model, answer, params)
        .into_iter()
        .filter_map(|r| {
            let c = &model.constraints[r.constraint];
            let solved = c
                .args
                .iter()
                .all(|a| scope.contains(&model.top_level_of(*a)));
            let unit = if is_angle(c.kind) { 1.0 } else { length };
            solved.then(|| (c.text.clone(), r.value / unit))
        })
        .collect()
}

fn fourbar(crank: f64, coupler: f64, rocker: f64, ground: f64) -> String {
    format!(
        "space 2d;
param theta = 0;
fixed point A = (0, 0);
fixed point D = ({ground}, 0);
fixed vector X = (1, 0);
body crank at (0, 0) {{ point a = (0, 0); point b = ({crank}, 0); vector u = (1, 0); }}
body coupler at ({crank}, 0) {{ point b = (0, 0); point c = ({coupler}, 0); }}
body rocker at ({ground}, 0) {{ point d = (0, 0); point c = (0, {rocker}); }}
coincident(crank.a, A);
drive: angle(X, crank.u) = theta;
coincident(crank.b, coupler.b);
elbow: coincident(coupler.c, rocker.c);
coincident(rocker.d, D);
output coupler.c;
"
    )
}

/// A full turn of the crank in 1-degree steps, passing exactly through 0 and 180 degrees.
fn turn() -> Vec<f64> {
    (0..360).map(|d| f64::from(d).to_radians()).collect()
}

fn cases() -> Vec<Case> {
    let mut out = vec![
        Case {
            // s + l = 2 + 4 > p + q = 2.5 + 3: the crank cannot turn fully; it reaches the
            // toggle (coupler and rocker aligned) and the loop cannot close beyond it.
            name: "four-bar through toggle (non-Grashof)",
            scale: 1.0,
            text: fourbar(2.0, 2.5, 3.0, 4.0),
            param: "theta",
            values: turn(),
            tolerance: 4e-15,
        },
        Case {
            // s + l = p + q: the change point, where the linkage folds flat at theta = 180
            // degrees and the two assemblies meet.
            name: "Grashof change point (s + l = p + q)",
            scale: 1.0,
            text: fourbar(1.5, 2.5, 3.0, 4.0),
            param: "theta",
            values: turn(),
            tolerance: 4e-15,
        },
        Case {
            // Two circles about fixed centres 4 apart, radii r and 2: crossing while r > 2,
            // approaching tangency by down to 1e-15, tangent at r = 2, then apart.
            name: "circles becoming tangent, then apart",
            scale: 1.0,
            text: "space 2d;
param r = 3;
fixed point A = (0, 0);
fixed point B = (4, 0);
point P = (1, 1);
d1: distance(A, P) = r;
meet: distance(B, P) = 2;
output P;
"
            .to_string(),
            param: "r",
            values: (0..40)
                .map(|k| 2.0 + 10f64.powf(-(f64::from(k) * 0.4)))
                .chain([2.0, 2.0 - 1e-12, 2.0 - 1e-6, 1.5])
                .collect(),
            tolerance: 4e-15,
        },
        Case {
            // A point on two lines, one through A along X, one through B = (0, 1) at angle a
            // to it; a goes from 0.5 rad down to 1.6e-9 (the point 6e8 away) and to 0
            // (parallel lines).
            name: "lines becoming parallel",
            scale: 1.0,
            text: "space 2d;
param a = 0.5;
fixed point A = (0, 0);
fixed point B = (0, 1);
fixed vector X = (1, 0);
line L1 = (0, 0) -> (1, 0);
line L2 = (0, 1) -> (1, 2);
point P = (2, 0.5);
on(A, L1);
angle(X, L1) = 0;
on(B, L2);
angle(X, L2) = a;
on(P, L1);
meet: on(P, L2);
output P;
"
            .to_string(),
            param: "a",
            values: (0..=17)
                .map(|k| 0.5 * 10f64.powf(-f64::from(k) * 0.5))
                .chain([0.0])
                .collect(),
            tolerance: 4e-15,
        },
    ];
    for scale in [1e-6, 1e-3, 1e3, 1e6] {
        out.push(Case {
            name: match scale {
                s if s < 1e-4 => "four-bar at scale 1e-6",
                s if s < 1.0 => "four-bar at scale 1e-3",
                s if s < 1e4 => "four-bar at scale 1e3",
                _ => "four-bar at scale 1e6",
            },
            scale,
            text: fourbar(1.5 * scale, 4.0 * scale, 3.0 * scale, 4.0 * scale),
            param: "theta",
            values: turn(),
            tolerance: 4e-15,
        });
    }
    out
}

#[test]
fn stress_sweeps_end_exact_or_in_a_measured_error() {
    // One solve per sample: the timings are not what this test is about.
    let settings = bench::Settings {
        budget_ns: 1.0,
        ..bench::Settings::default()
    };
    println!(
        "\n| case | samples | answers | errors | max residual (radians, or relative to size) | plan flips | baseline flips (warm) | baseline on another assembly (cold) | baseline failures |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for case in cases() {
        let scale = case.scale;
        let (diags, model, _) = gcs_lang::load(case.name, case.text.as_bytes());
        let model = model.unwrap_or_else(|| panic!("{}: {diags:?}", case.name));
        let analysis = gcs_compiler::analyse(&model).expect("analysis");
        assert!(analysis.unsolved.is_empty(), "{}", case.name);
        let (plan, scope) = gcs_compiler::prune::prune(&model, &analysis.plan);
        let index = model
            .param_named(case.param)
            .map(|p| p.into_raw().into_u32() as usize)
            .expect("param");
        let base = model.default_params();
        let params: Vec<Vec<f64>> = case
            .values
            .iter()
            .map(|&v| {
                let mut p = base.clone();
                p[index] = v;
                p
            })
            .collect();
        let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
        // Every sample: an exact answer or a measured error.
        let (mut answers, mut errors) = (0, 0);
        let mut worst: f64 = 0.0;
        for p in &params {
            match gcs_compiler::solve_plan(&model, &plan, &scope, p, &branches) {
                Ok(s) => {
                    answers += 1;
                    let size = s
                        .points
                        .iter()
                        .flat_map(|(_, p)| p.iter())
                        .fold(scale, |m, x| m.max(x.abs()));
                    // Angles are measured in radians, lengths relative to the answer's size.
                    for (text, off) in relative_residuals(&model, &scope, &s, p, size) {
                        worst = worst.max(off);
                        assert!(
                            off <= case.tolerance,
                            "{}: {} = {}: {text} off by {off:e} of its size",
                            case.name,
                            case.param,
                            p[index],
                        );
                    }
                }
                Err(e) => {
                    errors += 1;
                    assert!(
                        e.magnitude.is_finite() && !e.label.is_empty(),
                        "{}: {e}",
                        case.name
                    );
                }
            }
        }
        assert!(answers > 0, "{}: no sample solved", case.name);
        let sweep = Sweep {
            driver: Some(case.param.to_string()),
            range: (case.values[0], case.values[case.values.len() - 1]),
            params,
        };
        let compiled =
            bench::interpreted(&model, &plan, &scope, &branches, &sweep, settings.budget_ns);
        let whole: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
        let report = bench::run(&model, &analysis.plan, &whole, sweep, compiled, &settings)
            .expect("baseline builds");
        assert_eq!(report.branch_flips, 0, "{}: the plan flipped", case.name);
        println!(
            "| {} | {} | {answers} | {errors} | {worst:.1e} | {} | {} | {} | {} |",
            case.name,
            case.values.len(),
            report.branch_flips,
            report.baseline.branch_flips,
            report.baseline.cold_branch_flips,
            report.baseline.failures
        );
    }
}

/// Far beyond the sweeps above, where the baseline's tolerances lose their meaning: the
/// four-bar at scales 1e-100, 1e-50, 1e50 and 1e100 gives, at every crank angle, the answers
/// of the same four-bar at scale 1, scaled, to machine precision. Geometry does not depend on
/// the unit, and neither may the plan. Circle-circle, whose Heron product overflows past
/// 1e76 and underflows below 1e-77, solves such circles scaled by a power of two
/// (`CHORD_SCALES`). Without that, at 1e-100 the coupler lands 3 units (scaled) off, on a
/// false tangency, and at 1e100 there is no answer. Beyond about 1e±150 the squares in the
/// norms of sketch vectors (a radius measured from the sketch) overflow or underflow; at
/// 1e-300, 1e-200 and 1e200 the solve returns an error rather than an answer.
#[test]
fn four_bar_at_extreme_scales_is_the_unit_four_bar_scaled() {
    // Each sample's points by name, or none where the solve failed.
    type Points = Vec<(String, Vec<f64>)>;
    let solve_all = |scale: f64| -> Vec<Option<Points>> {
        let text = fourbar(1.5 * scale, 4.0 * scale, 3.0 * scale, 4.0 * scale);
        let (diags, model, _) = gcs_lang::load("scaled", text.as_bytes());
        let model = model.unwrap_or_else(|| panic!("{diags:?}"));
        let analysis = gcs_compiler::analyse(&model).expect("analysis");
        let (plan, scope) = gcs_compiler::prune::prune(&model, &analysis.plan);
        let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
        turn()
            .into_iter()
            .map(|theta| {
                let s =
                    gcs_compiler::solve_plan(&model, &plan, &scope, &[theta], &branches).ok()?;
                for (text, off) in relative_residuals(&model, &scope, &s, &[theta], scale) {
                    assert!(
                        off <= 4e-15,
                        "scale {scale:e}, theta {theta}: {text} off by {off:e} of the scale"
                    );
                }
                Some(s.points)
            })
            .collect()
    };
    let unit = solve_all(1.0);
    assert!(
        unit.iter().all(Option::is_some),
        "the unit four-bar turns fully"
    );
    for scale in [1e-100, 1e-50, 1e50, 1e100] {
        for (k, (scaled, unit)) in solve_all(scale).iter().zip(&unit).enumerate() {
            let (Some(scaled), Some(unit)) = (scaled, unit) else {
                panic!("scale {scale:e}: no answer at {k} degrees");
            };
            for ((name, p), (_, q)) in scaled.iter().zip(unit) {
                // Scaled back before the difference is taken: no overflow or underflow.
                let off = p
                    .iter()
                    .zip(q)
                    .map(|(a, b)| (a / scale - b).abs())
                    .fold(0.0, f64::max);
                assert!(
                    off <= 1e-14 * 8.0,
                    "scale {scale:e}, {k} degrees: {name} is {off:e} off the unit answer"
                );
            }
        }
    }
}
