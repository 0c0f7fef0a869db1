//! Errors: every way a model can fail to assemble is reported, naming the constraint (or param)
//! and by how much, never as a panic or a wrong answer.
//!
//! (a) an impossible assembly: a four-bar whose loop cannot close; (b) an under-constrained
//! model; (c) over-constrained models, consistent (a redundant check) and inconsistent (a
//! conflict of a known size); (d) non-finite params; (e) a branch index with no real root.
//! The CLI side of (a) is in `compiler/cli/tests/solve_errors.rs`.

use gcs_compiler::analyse;
use gcs_compiler::analysis::Analysis;
use gcs_compiler::report::problems;
use gcs_lang::Model;
use gcs_runtime::error::{ErrorKind, SolveError};

/// The four-bar of examples/fourbar.gcs, with its coupler's and rocker's `c` members and the
/// extra statements given.
fn fourbar(coupler_c: &str, rocker_c: &str, extra: &str, drive: bool) -> String {
    format!(
        "space 2d;
param theta = 30 deg;
param crank_len = 1.5;
fixed point A = (0, 0);
fixed point D = (4, 0);
fixed vector X = (1, 0);
body crank   at (0, 0)   {{ point a = (0, 0); point b = (crank_len, 0); vector u = (1, 0); }}
body coupler at (1.5, 0) {{ point b = (0, 0); point c = {coupler_c}; }}
body rocker  at (4, 0)   {{ point d = (0, 0); point c = {rocker_c}; }}
coincident(crank.a, A);
{}coincident(crank.b, coupler.b);
elbow: coincident(coupler.c, rocker.c);
coincident(rocker.d, D);
{extra}
",
        if drive {
            "drive: angle(X, crank.u) = theta;\n"
        } else {
            ""
        }
    )
}

/// The lines of a solve's body, without the body's indent.
fn dedent(code: &str) -> String {
    let lines: Vec<&str> = code
        .lines()
        .map(|l| l.strip_prefix("    ").unwrap_or(l))
        .collect();
    lines.join("\n")
}

fn load(text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load("test.gcs", text.as_bytes());
    assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}\n{text}");
    model.unwrap_or_else(|| panic!("no model\n{text}"))
}

fn example(name: &str) -> Model {
    let path = format!("{}/../examples/{name}.gcs", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("read {path}: {e}"));
    load(&text)
}

fn defaults(a: &Analysis) -> Vec<usize> {
    a.plan.branches.iter().map(|b| b.default).collect()
}

fn solve_defaults(
    model: &Model,
    a: &Analysis,
) -> Result<gcs_compiler::solution::Solution, SolveError> {
    gcs_compiler::solve(model, a, &model.default_params(), &defaults(a))
}

/// Every diagnostic as one line: message, labels and notes.
fn diag_text(d: &gcs_lang::Diagnostic) -> String {
    let mut s = d.message.clone();
    s.push_str(" | ");
    s.push_str(&d.primary.message);
    for l in &d.secondary {
        s.push_str(" | ");
        s.push_str(&l.message);
    }
    for n in &d.notes {
        s.push_str(" | ");
        s.push_str(n);
    }
    s
}

/// The gap between the circle about `crank.b` (crank at 30 degrees, length 1.5) with radius
/// `r1` and the circle about D = (4, 0) with radius `r2`.
fn fourbar_gap(r1: f64, r2: f64) -> f64 {
    let t = 30f64.to_radians();
    let b = (1.5 * t.cos(), 1.5 * t.sin());
    let d = (4.0 - b.0).hypot(0.0 - b.1);
    if d > r1 + r2 {
        d - (r1 + r2)
    } else {
        (r1 - r2).abs() - d
    }
}

fn assert_no_assembly(text: &str, gap: f64) {
    assert!(gap > 0.0, "the test model must not close (gap {gap})");
    let model = load(text);
    let a = analyse(&model).expect("analyse");
    let e = match solve_defaults(&model, &a) {
        Ok(s) => panic!("the loop cannot close, yet solve gave {:?}", s.points),
        Err(e) => e,
    };
    assert_eq!(e.kind, ErrorKind::NoIntersection, "{e}");
    assert_eq!(e.label, "elbow", "{e}");
    assert_eq!(e.text, "coincident(coupler.c, rocker.c)", "{e}");
    assert!(e.magnitude > 0.0, "{e}");
    assert!(
        (e.magnitude - gap).abs() <= 1e-12 * 5.0,
        "gap {} reported, {gap} true",
        e.magnitude
    );
    let msg = e.to_string();
    assert!(
        msg.contains("`elbow`") && msg.contains(&format!("{}", e.magnitude)),
        "{msg}"
    );
    // `check` reports the same problem on the constraint.
    let p = problems(&model, &a);
    assert!(
        p.iter()
            .any(|d| d.is_error() && diag_text(d).contains("elbow")),
        "{:?}",
        p.iter().map(diag_text).collect::<Vec<_>>()
    );
}

#[test]
fn a_coupler_too_short_to_reach_names_elbow_and_the_gap() {
    // Coupler 0.5 and rocker 1 cannot span the 2.80 from crank.b to D.
    let text = fourbar("(0.5, 0)", "(0, 1)", "", true);
    let gap = fourbar_gap(0.5, 1.0);
    assert!((gap - 1.3031580680701431).abs() < 1e-12);
    assert_no_assembly(&text, gap);
}

#[test]
fn a_coupler_too_long_to_fold_names_elbow_and_the_gap() {
    // Only the coupler's c member moves: a coupler of 8 against a rocker of 3 needs crank.b at
    // least 5 from D, but it is 2.80 away.
    let text = fourbar("(8, 0)", "(0, 3)", "", true);
    let gap = fourbar_gap(8.0, 3.0);
    assert_no_assembly(&text, gap);
}

#[test]
fn the_example_four_bar_assembles() {
    let text = fourbar("(4, 0)", "(0, 3)", "", true);
    let model = load(&text);
    let a = analyse(&model).expect("analyse");
    let s = solve_defaults(&model, &a).expect("the example closes");
    assert!(s.max_residual <= 1e-12 * 5.0);
    assert!(problems(&model, &a).is_empty());
}

#[test]
fn a_pinned_crank_without_its_drive_is_free_to_rotate() {
    // Its one free motion is a default at the sketch's angle: the solve leaves it there.
    let model = load(
        "space 2d;
fixed point A = (0, 0);
body crank at (0.5, 0.5) rotated 30 deg { point a = (0, 0); point b = (1.5, 0); }
coincident(crank.a, A);
",
    );
    let a = analyse(&model).expect("analyse");
    assert!(a.unsolved.is_empty());
    assert!(a.free_geoms().is_empty(), "the default holds it");
    let free: Vec<&str> = (a.free_defaults().iter())
        .map(|d| a.plan.defaults[d.0 as usize].name.as_str())
        .collect();
    assert_eq!(free, ["crank_angle"]);
    let sketch = a.plan.defaults[0].sketch;
    assert!((sketch - 30f64.to_radians()).abs() < 1e-15, "{sketch}");
    let s = solve_defaults(&model, &a).expect("solves");
    let b = &s.points.iter().find(|(n, _)| n == "crank.b").expect("b").1;
    let want = [
        1.5 * 30f64.to_radians().cos(),
        1.5 * 30f64.to_radians().sin(),
    ];
    assert!(
        (b[0] - want[0]).abs() < 1e-15 && (b[1] - want[1]).abs() < 1e-15,
        "{b:?}"
    );
}

#[test]
fn a_four_bar_without_its_drive_is_under_constrained() {
    // Without `drive` the four-bar keeps its one DOF: the report says so as a warning, with
    // the true mobility (one default, on the crank, not a DOF on each link), and the solve
    // keeps the crank where the sketch has it.
    let model = load(&fourbar("(4, 0)", "(0, 3)", "", false));
    let a = analyse(&model).expect("analyse");
    let problems = problems(&model, &a);
    assert!(problems.iter().all(|d| !d.is_error()), "{problems:#?}");
    let warnings: Vec<String> = problems.iter().map(diag_text).collect();
    assert_eq!(warnings.len(), 1, "{warnings:#?}");
    assert!(
        warnings[0].contains("`crank` is under-constrained")
            && warnings[0].contains("default `crank_angle`"),
        "{warnings:#?}"
    );
    assert!(a.free_geoms().is_empty());
    assert_eq!(a.free_defaults().len(), 1, "the mobility is one");
    let s = solve_defaults(&model, &a).expect("solves at the sketch");
    assert!(s.max_residual <= 1e-12 * 5.0, "{}", s.max_residual);
    let b = &s.points.iter().find(|(n, _)| n == "crank.b").expect("b").1;
    assert_eq!(b, &vec![1.5, 0.0], "the crank stays where it is sketched");
}

fn redundant_names(model: &Model, a: &Analysis) -> Vec<String> {
    a.redundant
        .iter()
        .map(|c| model.constraints[*c].name.clone())
        .collect()
}

#[test]
fn an_implied_distance_is_redundant_and_solves() {
    let model = load(&fourbar(
        "(4, 0)",
        "(0, 3)",
        "distance(crank.a, A) = 0;",
        true,
    ));
    let a = analyse(&model).expect("analyse");
    assert!(a.unsolved.is_empty());
    let red = redundant_names(&model, &a);
    assert_eq!(red.len(), 1, "{red:?}");
    assert!(
        red[0] == "distance_crank_a_A" || red[0] == "coincident_crank_a_A",
        "{red:?}"
    );
    assert!(a.plan.validate(&model).is_ok());
    let s = solve_defaults(&model, &a).expect("a consistent model solves");
    assert!(s.max_residual <= 1e-12 * 5.0);
    assert!(problems(&model, &a).iter().all(|d| !d.is_error()));
}

#[test]
fn a_duplicate_coincidence_is_redundant_and_solves() {
    let model = load(&fourbar(
        "(4, 0)",
        "(0, 3)",
        "coincident(A, crank.a);",
        true,
    ));
    let a = analyse(&model).expect("analyse");
    assert!(a.unsolved.is_empty());
    let red = redundant_names(&model, &a);
    assert_eq!(red.len(), 1, "{red:?}");
    assert!(
        red[0] == "coincident_A_crank_a" || red[0] == "coincident_crank_a_A",
        "{red:?}"
    );
    let s = solve_defaults(&model, &a).expect("a consistent model solves");
    assert!(s.max_residual <= 1e-12 * 5.0);
    // The same solution as without the duplicate.
    let plain = load(&fourbar("(4, 0)", "(0, 3)", "", true));
    let pa = analyse(&plain).expect("analyse");
    let ps = solve_defaults(&plain, &pa).expect("solves");
    let named = s.by_name();
    for (name, v) in &ps.points {
        let w = named.point(name).expect("same points");
        assert!(
            (v[0] - w[0]).abs() <= 1e-12 && (v[1] - w[1]).abs() <= 1e-12,
            "{name}"
        );
    }
    assert!(problems(&model, &a).iter().all(|d| !d.is_error()));
}

#[test]
fn an_inconsistent_distance_names_the_conflict_and_its_size() {
    // The crank is 1.5 long and pinned at A: crank.b cannot be 2 from A.
    let model = load(&fourbar(
        "(4, 0)",
        "(0, 3)",
        "distance(crank.b, A) = 2;",
        true,
    ));
    let a = analyse(&model).expect("analyse");
    let p: Vec<String> = problems(&model, &a)
        .iter()
        .filter(|d| d.is_error())
        .map(diag_text)
        .collect();
    assert!(
        p.iter()
            .any(|d| d.contains("distance_crank_b_A") && d.contains("0.5")),
        "no error names distance_crank_b_A with its conflict 0.5: {p:#?}"
    );
    let e = match solve_defaults(&model, &a) {
        Ok(s) => panic!("an inconsistent model solved: {:?}", s.points),
        Err(e) => e,
    };
    assert_eq!(e.label, "distance_crank_b_A", "{e}");
    assert!(
        matches!(e.kind, ErrorKind::Inconsistent | ErrorKind::NoIntersection),
        "{e}"
    );
    assert!((e.magnitude - 0.5).abs() <= 1e-12 * 5.0, "{e}");
}

#[test]
fn non_finite_params_are_invalid_input_naming_the_param() {
    let model = example("fourbar");
    let a = analyse(&model).expect("analyse");
    for name in ["theta", "crank_len"] {
        let i = model
            .param_named(name)
            .expect("param")
            .into_raw()
            .into_u32() as usize;
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut params = model.default_params();
            params[i] = bad;
            let e = match gcs_compiler::solve(&model, &a, &params, &defaults(&a)) {
                Ok(s) => panic!("{name} = {bad} solved: {:?}", s.points),
                Err(e) => e,
            };
            assert_eq!(e.kind, ErrorKind::InvalidInput, "{name} = {bad}: {e}");
            assert_eq!(e.label, name, "{name} = {bad}: {e}");
            assert!(
                e.magnitude.is_nan() && bad.is_nan() || e.magnitude == bad,
                "{name} = {bad}: magnitude {}",
                e.magnitude
            );
            assert!(e.to_string().contains(&format!("`{name}`")), "{e}");
        }
    }
}

#[test]
fn finite_params_that_overflow_the_sketch_are_invalid_input() {
    // A finite param whose sketch overflows: no panic, no answer, an InvalidInput error.
    let model = load(
        "space 2d;
param s = 1;
fixed point A = (0, 0);
fixed vector X = (1, 0);
body crank { point a = (0, 0); point b = (s * s, 0); vector u = (1, 0); }
coincident(crank.a, A);
angle(X, crank.u) = 0.5;
",
    );
    let a = analyse(&model).expect("analyse");
    let mut params = model.default_params();
    params[0] = 1e200;
    match gcs_compiler::solve(&model, &a, &params, &defaults(&a)) {
        Ok(s) => panic!("an overflowing sketch solved: {:?}", s.points),
        Err(e) => assert_eq!(e.kind, ErrorKind::InvalidInput, "{e}"),
    }
}

/// A four-bar whose drive angle is a value the params give, not a param itself.
const SCALED_DRIVE: &str = "space 2d;
param theta = 0.5;
fixed point A = (0, 0);
fixed point D = (4, 0);
fixed vector X = (1, 0);
body crank   at (0, 0)   { point a = (0, 0); point b = (1.5, 0); vector u = (1, 0); }
body coupler at (1.5, 0) { point b = (0, 0); point c = (4, 0); }
body rocker  at (4, 0)   { point d = (0, 0); point c = (0, 3); }
coincident(crank.a, A);
drive: angle(X, crank.u) = theta * 1e300;
coincident(crank.b, coupler.b);
elbow: coincident(coupler.c, rocker.c);
coincident(rocker.d, D);
output coupler.c;
";

#[test]
fn a_value_that_overflows_finite_params_is_invalid_naming_its_constraint() {
    // `theta * 1e300` is finite for small `theta` and infinite for `theta = 1e10`: the drive
    // cannot be met, and the solve says so rather than leaving the crank where it was.
    let model = load(SCALED_DRIVE);
    let a = analyse(&model).expect("analyse");
    let mut params = model.default_params();
    params[0] = 1e-300;
    let s = gcs_compiler::solve(&model, &a, &params, &defaults(&a)).expect("a finite drive");
    assert!(s.max_residual <= 1e-12, "{}", s.max_residual);
    params[0] = 1e10;
    let e = match gcs_compiler::solve(&model, &a, &params, &defaults(&a)) {
        Ok(s) => panic!("an infinite drive angle solved: {:?}", s.points),
        Err(e) => e,
    };
    assert_eq!(
        (e.kind, e.label.as_ref(), e.magnitude),
        (ErrorKind::InvalidValue, "drive", f64::INFINITY),
        "{e}"
    );
    assert_eq!(
        e.to_string(),
        "constraint `drive` (angle(X, crank.u) = theta * 1e300) cannot be met: its value, inf, is not a finite number"
    );
}

#[test]
fn generated_code_checks_a_value_the_params_give_and_trusts_a_param() {
    // The drive's value is checked where it is computed, once; the rotation onto its
    // direction then needs no test of its own. A plain param needs neither.
    let model = load(SCALED_DRIVE);
    let a = analyse(&model).expect("analyse");
    let code = gcs_compiler::codegen::format(&gcs_compiler::codegen::generate(&model, &a.plan));
    let start = code.find("    // drive:").expect("the drive's step");
    let end = start + code[start..].find("\n\n").expect("the step's end");
    expect_test::expect![[r#"
        // drive: angle(X, crank.u) = theta * 1e300 (test.gcs:10)
        let value = params.theta * 1e300;
        if !gcs_runtime::num::is_finite(value) {
            return Err(SolveError::new(
                "drive",
                "angle(X, crank.u) = theta * 1e300",
                ErrorKind::InvalidValue,
                value,
            ));
        }
        let x_dir_turned = direction_at(value);
        let turn = rotation_from_x_unit(&x_dir_turned);
        crank.set_rotation(&turn);"#]]
    .assert_eq(&dedent(&code[start..end]));
    let plain = load(&SCALED_DRIVE.replace("theta * 1e300", "theta"));
    let a = analyse(&plain).expect("analyse");
    let code = gcs_compiler::codegen::format(&gcs_compiler::codegen::generate(&plain, &a.plan));
    assert!(
        code.contains("rotation_from_x_unit(&x_dir_turned)"),
        "{code}"
    );
    assert!(!code.contains("InvalidValue"), "{code}");
}

#[test]
fn circle_problem_has_two_real_branches_of_four() {
    let model = example("circle");
    let a = analyse(&model).expect("analyse");
    let k = a
        .plan
        .branches
        .iter()
        .position(|b| b.name == "meet")
        .expect("branch meet");
    assert_eq!(a.plan.branches[k].count, 4);
    let params = model.default_params();
    let mut centres = Vec::new();
    for i in 0..4 {
        let mut br = defaults(&a);
        br[k] = i;
        match gcs_compiler::solve(&model, &a, &params, &br) {
            Ok(s) => {
                assert!(i < 2, "meet = {i} solved, but only 2 roots are real");
                assert!(
                    s.max_residual <= 1e-12 * 10.0,
                    "meet = {i}: {}",
                    s.max_residual
                );
                let centre = s.by_name().point("G.center").expect("G.center").to_vec();
                centres.push(centre);
            }
            Err(e) => {
                assert!(i >= 2, "meet = {i}: {e}");
                assert_eq!(e.kind, ErrorKind::NoSuchBranch, "meet = {i}: {e}");
                assert_eq!(e.label, "meet", "{e}");
                assert_eq!(e.magnitude, 2.0, "two real roots: {e}");
            }
        }
    }
    assert_eq!(centres.len(), 2);
    let d = (centres[0][0] - centres[1][0]).hypot(centres[0][1] - centres[1][1]);
    assert!(d > 1e-6, "the two real branches are distinct: {centres:?}");
}

/// A triad whose third link cannot reach the platform: the outer iteration cannot close it
/// anywhere over the turn of its default, and the solve says that no assembly exists, naming a
/// constraint of the triad with how far it stays off, at every crank angle, and never returns an
/// answer that breaks a constraint.
#[test]
fn a_triad_that_cannot_close_names_its_constraint_and_the_residual() {
    let text = include_str!("../../examples/triad_sixbar.gcs").replace(
        "body link3 at (0.3, 0) { point o = (0, 0); point p = (0, 3); }",
        "body link3 at (0.3, 0) { point o = (0, 0); point p = (0, 30); }",
    );
    assert!(
        text.contains("(0, 30)"),
        "the model changed: update this test"
    );
    let model = load(&text);
    let a = analyse(&model).expect("analyse");
    assert_eq!(a.plan.iterations.len(), 1);
    let triad = ["j1", "j2", "j3"];
    for degrees in [0.0, 90.0, 200.0] {
        let params = vec![f64::to_radians(degrees)];
        let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
        let e = gcs_compiler::solve(&model, &a, &params, &branches)
            .expect_err("the third link is ten times too long");
        assert!(triad.contains(&e.label.as_ref()), "{e}");
        assert!(
            matches!(e.kind, ErrorKind::NoAssembly | ErrorKind::NoIntersection),
            "{e}"
        );
        assert!(e.magnitude > 1.0, "off by {}: {e}", e.magnitude);
    }
}

/// A line tangent to two pulleys in parallel planes 1 apart cannot lie in both: the second
/// tangency is refused naming it and the gap between the planes, not as a degenerate turn
/// about a normal parallel to itself; in one plane, the same model solves.
#[test]
fn a_line_tangent_to_pulleys_in_parallel_planes_names_the_gap() {
    let model = |height: &str| {
        load(&format!(
            "space 3d;
fixed circle A = center (0, 0, 0) radius 1 normal (0, 0, 1);
fixed circle B = center (4, 0, {height}) radius 1 normal (0, 0, 1);
line L = (0, 1, 0) -> (4, 1, 0);
tangent(L, A);
tangent(L, B);
"
        ))
    };
    let apart = model("1");
    let a = analyse(&apart).expect("analyse");
    let e = solve_defaults(&apart, &a).expect_err("the planes are 1 apart");
    assert_eq!(e.label.as_ref(), "tangent_L_B", "{e}");
    assert_eq!(e.kind, ErrorKind::NoIntersection, "{e}");
    assert!((e.magnitude - 1.0).abs() < 1e-12, "{e}");
    let flat = model("0");
    let a = analyse(&flat).expect("analyse");
    let s = solve_defaults(&flat, &a).expect("one plane");
    let worst =
        gcs_compiler::verify::max_residual(&gcs_compiler::verify::residuals(&flat, &s, &[]));
    assert!(worst < 1e-12, "{worst}");
}

/// An error about a large model fits a screen and gives the real gap: a strip of 2,000 quads
/// whose last point is also held 1 from the first, about 2,000 away along the strip. The
/// diagnostic marks a few of the constraints it builds on, nearest the one that fails, and
/// counts the others.
#[test]
fn an_error_about_a_large_model_fits_a_screen() {
    let mut text = gcs_compiler::families::strip(2000);
    text.push_str("distance(a2000, a0) = 1;\n");
    let model = load(&text);
    let a = analyse(&model).expect("analysed");
    let errors: Vec<_> = problems(&model, &a)
        .into_iter()
        .filter(|d| d.is_error())
        .collect();
    assert_eq!(errors.len(), 1, "{errors:#?}");
    let e = &errors[0];
    assert!(e.secondary.len() <= gcs_compiler::plan::SHOWN, "{e:#?}");
    let words = e.notes.join("\n");
    assert!(
        words.contains(" more (with fixed a0 and fixed b0)"),
        "{words}"
    );
    // The gap is the strip's length less 1, not a rounding-sized one.
    let gap: f64 = (e.primary.message)
        .strip_prefix("no assembly: the loci miss by ")
        .and_then(|m| m.parse().ok())
        .unwrap_or_else(|| panic!("{e:#?}"));
    assert!(gap > 1500.0, "{gap}");
}

/// Nothing off is `Ok`: the solve re-measures every constraint by the verifier, which shares
/// nothing with the plan, and a constraint off by more than a check's tolerance is an error
/// naming it. Shown on a plan with its run-time checks taken out: the redundant distance, which
/// only a check guarded, is then off by the difference of the two values.
#[test]
fn a_solution_off_a_constraint_is_never_ok() {
    let model = load(
        "space 2d;
fixed point A = (0, 0);
fixed point B = (3, 0);
point C = (1, 2);
distance(A, C) = 2;
distance(B, C) = 2;
twice: distance(A, C) = 2.5;
",
    );
    let a = analyse(&model).expect("analysed");
    let mut plan = a.plan.clone();
    assert!(plan.iterations.is_empty());
    let checks = plan.steps.len();
    plan.steps
        .retain(|s| !matches!(s.op, gcs_compiler::plan::Op::Check { .. }));
    assert!(plan.steps.len() < checks, "the plan checks `twice`");
    let all = model.top_level().map(|(id, _)| id).collect();
    let params = model.default_params();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let e =
        gcs_compiler::solve_plan(&model, &plan, &all, &params, &branches).expect_err("off by 0.5");
    assert_eq!(
        (&*e.label, e.kind),
        ("twice", ErrorKind::Inconsistent),
        "{e}"
    );
    assert!((e.magnitude - 0.5).abs() < 1e-12, "{e}");
}

/// A profile that cannot close with its segments running as sketched says so: with the
/// L profile's leg longer than its width, the top edge `s3` would need a length of
/// 100 - 150 - 5 - 3 = -58 to reach the inner fillet, so `on_s3_end_F2` is refused as
/// `CannotClose` with that length (not as a negative value of a constraint that has none).
/// The same holds for a length a linear stage solves for: its error names the constraint
/// whose row gives it, and generated code says the same (both ask `Plan::closing_length`).
#[test]
fn a_profile_that_cannot_close_says_so() {
    let path = format!("{}/tests/models/l_profile.gcs", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("l_profile.gcs");
    let c = gcs_compiler::compile("l_profile.gcs", text.as_bytes()).expect("compiles");
    let branches = defaults(&c.analysis);
    let mut params = c.model.default_params();
    gcs_compiler::solve(&c.model, &c.analysis, &params, &branches).expect("leg 40 closes");
    params[0] = 150.0;
    let e = gcs_compiler::solve(&c.model, &c.analysis, &params, &branches)
        .expect_err("leg 150 cannot close");
    assert_eq!(e.kind, ErrorKind::CannotClose);
    assert_eq!(e.label, "on_s3_end_F2");
    assert!((e.magnitude + 58.0).abs() < 1e-9, "{}", e.magnitude);
    assert!(e.to_string().contains("cannot close"), "{e}");

    // A linear stage's lengths: every one of the rounded rectangle's is a closing length,
    // named after the constraint of the row that gives it.
    let c = gcs_compiler::compile(
        "rr.gcs",
        std::fs::read_to_string(format!(
            "{}/../examples/sketches/rounded_rectangle.gcs",
            env!("CARGO_MANIFEST_DIR")
        ))
        .expect("rounded_rectangle.gcs")
        .as_bytes(),
    )
    .expect("compiles");
    let plan = &c.analysis.plan;
    let named: Vec<&str> = (plan.steps.iter().enumerate())
        .filter_map(|(i, _)| plan.closing_length(i))
        .map(|k| c.model.constraints[k].name.as_str())
        .collect();
    assert_eq!(named, ["on_bottom_end_br", "on_top_start_tr"]);
}
