//! Run-time checks hold the relation the analysis reasons with, and nothing less.
//!
//! Where the language leaves a discrete choice to the sketch (the sense of a parallel, the
//! side of a line a circle is tangent on, a point inside or outside a circle, internal or
//! external tangency), a constraint means that one reading, whether the plan constructs with
//! it or re-measures it as an implied check. So the same model gives the same verdict whatever
//! its constraints are called (the analysis takes them in name order, which decides which one
//! constructs and which one is checked). Checks used to accept either reading while the
//! constructions held the sketch's: these tests would have caught it.

use gcs_runtime::error::ErrorKind;

/// Solves a model with its sketch's branches: the error's kind and magnitude, or `None`.
fn verdict(text: &str) -> Option<(ErrorKind, f64)> {
    let c = gcs_compiler::compile("check.gcs", text.as_bytes()).expect("compiles");
    let branches: Vec<usize> = c.analysis.plan.branches.iter().map(|b| b.default).collect();
    match gcs_compiler::solve(&c.model, &c.analysis, &c.model.default_params(), &branches) {
        Ok(s) => {
            assert!(
                s.max_residual < 1e-12,
                "{text}: residual {}",
                s.max_residual
            );
            None
        }
        Err(e) => Some((e.kind, e.magnitude)),
    }
}

/// `model` with `{first}` and `{second}` replaced by the labels in both orders: the two
/// constraints so labelled take turns constructing and being checked.
fn both_orders(model: &str) -> [String; 2] {
    [("a", "b"), ("b", "a")]
        .map(|(first, second)| model.replace("{first}", first).replace("{second}", second))
}

/// Each model, with a sketch that reads the choice as the constraints hold it (`right`) or
/// the other way (`wrong`), and the size by which the wrong reading misses.
const CASES: &[(&str, &str, &str, f64)] = &[
    (
        // The sense of a parallel: a vector turned onto X by one, anti-parallel by the other.
        "space 2d;\nfixed vector X = (1, 0);\nvector u = {sketch};\n\
         {first}: angle(X, u) = 0;\n{second}: parallel(X, u);\n",
        "(1, 0.1)",
        "(-1, 0.1)",
        std::f64::consts::PI,
    ),
    (
        // Internal or external tangency: B's centre pinned at distance 3 from A's.
        "space 2d;\nfixed circle A = center (0, 0) radius 2;\ncircle B = center {sketch} radius 1;\n\
         fixed point P = (3, 0);\nradius(B) = 1;\n\
         {first}: coincident(B.center, P);\n{second}: tangent(A, B);\n",
        "(3.5, 0)",
        "(0.5, 0)",
        2.0,
    ),
    (
        // The side of the line a circle is tangent on.
        "space 2d;\nfixed line L = (0, 0) -> (1, 0);\ncircle C = center {sketch} radius 1;\n\
         fixed point P = (0, 1);\nradius(C) = 1;\n\
         {first}: coincident(C.center, P);\n{second}: tangent(L, C);\n",
        "(0, 1.5)",
        "(0, -1.5)",
        2.0,
    ),
    (
        // A point outside or inside a circle, at a distance from its perimeter.
        "space 2d;\nfixed circle C = center (0, 0) radius 2;\npoint Q = {sketch};\n\
         fixed point P = (3, 0);\n\
         {first}: coincident(Q, P);\n{second}: distance(Q, C) = 1;\n",
        "(2.5, 0)",
        "(0.5, 0)",
        2.0,
    ),
];

#[test]
fn a_choice_the_sketch_makes_means_the_same_constructed_or_checked() {
    for (model, right, wrong, miss) in CASES {
        for sketch in [right, wrong] {
            let text = model.replace("{sketch}", sketch);
            let [first, second] = both_orders(&text).map(|t| verdict(&t));
            let expected = if sketch == right { None } else { Some(*miss) };
            for (order, v) in [first, second].into_iter().enumerate() {
                match (v, expected) {
                    (None, None) => {}
                    (Some((ErrorKind::Inconsistent, m)), Some(miss)) => {
                        assert!(
                            (m - miss).abs() < 1e-12,
                            "{text} (order {order}): off by {m}"
                        )
                    }
                    (v, _) => {
                        panic!("{text} (order {order}): {v:?}, expected a miss of {expected:?}")
                    }
                }
            }
        }
    }
}

#[test]
fn every_relation_of_a_constraint_is_satisfied_or_checked() {
    // A prismatic joint is a point on a line and parallel axes. With the point already
    // pinned off the line, the plan still turns the axes parallel, and it must check the
    // point-line part: it is off by 1. (Only a constraint's last relation used to be checked,
    // and this model "solved" with `prismatic` violated by 1.)
    let text = "space 2d;\n\
        fixed body G0 { marker m = (2, 1) x (1, 0); }\n\
        fixed body G1 { marker r = (0, 0) x (1, 0); }\n\
        body P at (1, 1) { marker k = (0, 0) x (0, 1); }\n\
        p0: revolute(P.k, G0.m);\n\
        z: prismatic(P.k, G1.r);\n";
    assert_eq!(verdict(text), Some((ErrorKind::Inconsistent, 1.0)));
    assert_eq!(verdict(&text.replace("(2, 1) x", "(2, 0) x")), None);
}

/// An iterated region is guarded: once the plan has run, every relation of a constraint the
/// region claims is measured again, so an iteration that closed on an error that does not
/// measure what its default displaced is never an answer. Here the 3-RPR's closing error is
/// made to close `l3` at `leg1`'s length instead of `leg3`'s: the iteration converges, and
/// the guard refuses the result, naming `l3` with how far it is off.
#[test]
fn an_iteration_closed_on_the_wrong_error_is_refused_by_its_guard() {
    use gcs_compiler::plan::{Op, Residual};
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/rpr3.gcs"))
            .expect("rpr3.gcs");
    let c = gcs_compiler::compile("rpr3.gcs", text.as_bytes()).expect("compiles");
    let mut plan = c.analysis.plan.clone();
    let guards = (plan.steps.iter())
        .filter(|s| matches!(s.op, Op::Check { guard: true, .. }))
        .count();
    assert!(guards > 0, "the iterated region has guards");
    // The register holding leg1's length (the plan's first size), and l3's closing error.
    let leg1 = (plan.steps.iter())
        .find(|s| matches!(s.op, Op::Size { .. }))
        .and_then(|s| s.out)
        .map(|(r, _)| r)
        .expect("leg1's size");
    let error = (plan.steps.iter_mut())
        .find_map(|s| match &mut s.op {
            Op::Error {
                residual: Residual::PointPoint { d, .. },
                ..
            } => Some(d),
            _ => None,
        })
        .expect("l3's closing error");
    *error = Some(leg1);
    let params = c.model.default_params();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let choice = gcs_compiler::interp::Choice::Given(branches);
    let e =
        gcs_compiler::interp::run_with(&c.model, &plan, &params, &plan.sketch_defaults(), &choice)
            .expect_err("the guard refuses it");
    assert_eq!(e.kind, ErrorKind::Inconsistent);
    assert_eq!(e.label, "l3");
    assert!(
        (e.magnitude - (14.98 - 12.0)).abs() < 1e-9,
        "{}",
        e.magnitude
    );
    // The plan as analysed passes its guards.
    let plan = &c.analysis.plan;
    assert!(gcs_compiler::interp::run_with(
        &c.model,
        plan,
        &params,
        &plan.sketch_defaults(),
        &choice
    )
    .is_ok());
}
