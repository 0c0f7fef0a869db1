//! A duplicate of a constraint is a run-time check whatever the two are called, and a
//! duplicate with another value is a conflict of that size.
//!
//! The analysis takes relations in constraint-name order, so a duplicate's label decides
//! whether it comes before or after the constraint it repeats. It used to matter: a duplicate
//! met first moved a point onto its locus, and the original then intersected that locus with
//! itself (a "degenerate configuration"). Now the relation met second never constructs: it is
//! checked once the first is done. Every constraint form of the plane is duplicated here,
//! labelled to sort before the original, after it, and unlabelled.

use gcs_runtime::error::ErrorKind;

/// A model with one constraint labelled `orig`, the same statement with another value (when
/// it has one), and how far that other value is from the first.
struct Case {
    model: &'static str,
    statement: &'static str,
    other: Option<(&'static str, f64)>,
}

const CASES: &[Case] = &[
    Case {
        model: "fixed point A = (0, 0);\npoint B = (1, 1);\norig: coincident(B, A);",
        statement: "coincident(B, A)",
        other: None,
    },
    Case {
        model: "fixed point A = (0, 0);\nfixed point C = (5, 0);\npoint B = (2, 2);\n\
                orig: distance(A, B) = 3;\ndistance(C, B) = 4;",
        statement: "distance(A, B) = 3",
        other: Some(("distance(A, B) = 3.5", 0.5)),
    },
    Case {
        model: "fixed line L = (0, 0) -> (1, 0);\nfixed line M = (2, -5) -> (2, 5);\n\
                point B = (1, 1);\norig: distance(B, L) = 2;\non(B, M);",
        statement: "distance(B, L) = 2",
        other: Some(("distance(B, L) = 2.25", 0.25)),
    },
    Case {
        model: "fixed circle C = center (0, 0) radius 2;\nfixed line L = (0, 0) -> (1, 0);\n\
                point B = (2.5, 0.5);\norig: distance(B, C) = 1;\non(B, L);",
        statement: "distance(B, C) = 1",
        other: Some(("distance(B, C) = 1.5", 0.5)),
    },
    Case {
        model: "fixed circle C = center (0, 0) radius 2;\nline L = (-1, 3.5) -> (1, 3.5);\n\
                horizontal(L);\norig: distance(L, C) = 1;",
        statement: "distance(L, C) = 1",
        other: Some(("distance(L, C) = 0.75", 0.25)),
    },
    Case {
        model: "fixed circle A = center (0, 0) radius 2;\ncircle B = center (3.2, 0) radius 0.9;\n\
                fixed line L = (0, 0) -> (1, 0);\nradius(B) = 1;\non(B.center, L);\n\
                orig: distance(A, B) = 0.5;",
        statement: "distance(A, B) = 0.5",
        other: Some(("distance(A, B) = 0.25", 0.25)),
    },
    Case {
        model: "fixed line L = (0, 0) -> (1, 0);\nfixed point A = (3, 4);\npoint B = (2, 1);\n\
                orig: on(B, L);\ndistance(A, B) = 5;",
        statement: "on(B, L)",
        other: None,
    },
    Case {
        model: "fixed circle C = center (0, 0) radius 2;\nfixed line L = (0, 0) -> (1, 0);\n\
                point B = (1.5, 0.3);\norig: on(B, C);\non(B, L);",
        statement: "on(B, C)",
        other: None,
    },
    Case {
        model: "fixed line L = (0, 0) -> (1, 0);\nfixed line M = (0, 0) -> (0, 1);\n\
                circle K = center (1.2, 1.1) radius 0.9;\nradius(K) = 1;\n\
                orig: tangent(L, K);\ntangent(M, K);",
        statement: "tangent(L, K)",
        other: None,
    },
    Case {
        model: "fixed circle A = center (0, 0) radius 2;\nfixed line L = (0, 0) -> (1, 0);\n\
                circle B = center (3.1, 0.2) radius 1;\nradius(B) = 1;\non(B.center, L);\n\
                orig: tangent(A, B);",
        statement: "tangent(A, B)",
        other: None,
    },
    Case {
        model: "fixed vector X = (1, 0);\nvector u = (0.8, 0.5);\norig: angle(X, u) = 30 deg;",
        statement: "angle(X, u) = 30 deg",
        other: Some(("angle(X, u) = 40 deg", std::f64::consts::PI / 18.0)),
    },
    Case {
        model: "fixed vector X = (1, 0);\nvector u = (0.9, 0.1);\norig: parallel(X, u);",
        statement: "parallel(X, u)",
        other: None,
    },
    Case {
        model: "fixed vector X = (1, 0);\nvector u = (0.1, 0.9);\norig: perpendicular(X, u);",
        statement: "perpendicular(X, u)",
        other: None,
    },
    Case {
        model: "fixed point A = (0, 0);\nline L = (0, 0.1) -> (1, 0.2);\n\
                on(A, L);\norig: horizontal(L);",
        statement: "horizontal(L)",
        other: None,
    },
    Case {
        model: "fixed point A = (0, 0);\nsegment S = (0.1, 0) -> (0.2, 1);\n\
                coincident(S.start, A);\nlength(S) = 2;\norig: vertical(S);",
        statement: "vertical(S)",
        other: None,
    },
    Case {
        model: "fixed point A = (0, 0);\nsegment S = (0, 0) -> (2, 0.3);\n\
                coincident(S.start, A);\nhorizontal(S);\norig: length(S) = 5;",
        statement: "length(S) = 5",
        other: Some(("length(S) = 5.5", 0.5)),
    },
    Case {
        model: "fixed point A = (0, 0);\ncircle K = center (0.2, 0.1) radius 1.5;\n\
                coincident(K.center, A);\norig: radius(K) = 2;",
        statement: "radius(K) = 2",
        other: Some(("radius(K) = 2.5", 0.5)),
    },
    Case {
        model: "fixed body G { marker m = (0, 0) x (1, 0); }\n\
                body P at (1, 0.5) { marker k = (0, 0) x (1, 0); }\n\
                fixed line M = (2, -5) -> (2, 5);\n\
                orig: in_line(P.k, G.m);\non(P.k, M);\nangle(G.m.x, P.k.x) = 0;",
        statement: "in_line(P.k, G.m)",
        other: None,
    },
    Case {
        model: "fixed body G { marker m = (0, 0) x (1, 0); }\n\
                body P at (0, 0) rotated 0.3 { marker k = (0, 0) x (1, 0); }\n\
                revolute(P.k, G.m);\norig: offset_x(G.m, P.k) = 45 deg;",
        statement: "offset_x(G.m, P.k) = 45 deg",
        other: Some(("offset_x(G.m, P.k) = 50 deg", std::f64::consts::PI / 36.0)),
    },
    Case {
        model: "fixed body G { marker m = (1, 1) x (1, 0); }\n\
                body P at (0, 0) { marker k = (0, 0) x (0, 1); }\n\
                orig: revolute(P.k, G.m);\nangle(G.m.x, P.k.x) = 20 deg;",
        statement: "revolute(P.k, G.m)",
        other: None,
    },
    Case {
        model: "fixed body G { marker m = (0, 0) x (1, 0); }\n\
                body P at (1, 0.2) rotated 0.1 { marker k = (0, 0) x (1, 0); }\n\
                fixed point Q = (2, 0);\norig: prismatic(P.k, G.m);\ncoincident(P.k, Q);",
        statement: "prismatic(P.k, G.m)",
        other: None,
    },
    Case {
        model: "fixed point A = (0, 0);\nbody P at (0.3, 0.2) { point a = (0, 0); vector v = (1, 0); }\n\
                fixed vector X = (1, 0);\norig: spherical(P.a, A);\nangle(X, P.v) = 10 deg;",
        statement: "spherical(P.a, A)",
        other: None,
    },
];

/// The points of a solution, by name.
type Points = Vec<(String, Vec<f64>)>;

/// The solve of `text` at its default params and sketch branches: its points by name, or the
/// error's kind, label and magnitude.
fn solve(text: &str) -> Result<Points, (ErrorKind, String, f64)> {
    let text = format!("space 2d;\n{text}\n");
    let c = gcs_compiler::compile("dup.gcs", text.as_bytes())
        .unwrap_or_else(|e| panic!("{text}\n{e:?}"));
    let branches: Vec<usize> = c.analysis.plan.branches.iter().map(|b| b.default).collect();
    let params = c.model.default_params();
    match gcs_compiler::solve(&c.model, &c.analysis, &params, &branches) {
        Ok(s) => {
            assert!(
                s.max_residual < 1e-12,
                "{text}: residual {}",
                s.max_residual
            );
            Ok(s.points)
        }
        Err(e) => Err((e.kind, e.label.to_string(), e.magnitude)),
    }
}

/// The duplicate of a statement, labelled to sort before `orig`, after it, and unlabelled.
fn duplicates(statement: &str) -> [String; 3] {
    [
        format!("a_dup: {statement};"),
        format!("zzz: {statement};"),
        format!("{statement};"),
    ]
}

#[test]
fn a_duplicate_is_checked_whatever_its_name() {
    for case in CASES {
        let base = solve(case.model).unwrap_or_else(|e| panic!("{}: {e:?}", case.model));
        for dup in duplicates(case.statement) {
            let text = format!("{}\n{dup}", case.model);
            let solved = solve(&text).unwrap_or_else(|e| panic!("{text}\n{e:?}"));
            for ((name, p), (_, q)) in solved.iter().zip(&base) {
                let off = p
                    .iter()
                    .zip(q)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                assert!(off < 1e-12, "{text}\n{name} moved by {off}");
            }
            let c = gcs_compiler::compile("dup.gcs", format!("space 2d;\n{text}").as_bytes())
                .expect("compiles");
            assert!(
                !c.analysis.redundant.is_empty(),
                "{text}: nothing redundant"
            );
        }
    }
}

#[test]
fn a_duplicate_with_another_value_is_a_conflict_of_that_size() {
    for case in CASES {
        let Some((other, miss)) = case.other else {
            continue;
        };
        for dup in duplicates(other) {
            let text = format!("{}\n{dup}", case.model);
            match solve(&text) {
                Err((ErrorKind::Inconsistent, _, m)) => {
                    assert!((m - miss).abs() < 1e-9, "{text}\noff by {m}, not {miss}")
                }
                other => panic!("{text}\n{other:?}"),
            }
        }
    }
}
