//! The constraints every sketcher has, `equal`, `midpoint` and `symmetric`, as the analysis
//! counts and solves them: each removes the freedom it says (equal 1, midpoint 2, symmetric 2
//! in the plane) whichever of its sides moves, an equal dimension is not a known one, and the
//! degenerate cases are errors naming the constraint, never a panic or a NaN.

use gcs_compiler::pipeline::Compiled;
use gcs_runtime::error::ErrorKind;

fn compiled(text: &str) -> Compiled {
    match gcs_compiler::compile("model.gcs", text.as_bytes()) {
        Ok(c) => c,
        Err(e) => panic!("does not compile: {e:?}\n{text}"),
    }
}

/// The freedom the constraints leave: the defaults that hold a free motion (the mobility),
/// with no constraint left unsolved.
fn mobility(text: &str) -> usize {
    let c = compiled(text);
    assert!(
        c.analysis.unsolved.is_empty(),
        "{:?}\n{text}",
        c.analysis.unsolved
    );
    assert!(
        !c.diagnostics.iter().any(|d| d.is_error()),
        "{:#?}\n{text}",
        c.diagnostics
    );
    c.analysis.free_defaults().len()
}

/// The DOF the record of `geom`'s cluster leaves before any default: what the constraints
/// alone fix of it.
fn record_dof(text: &str, geom: &str) -> usize {
    let c = compiled(text);
    let g = c.model.geom_named(geom).expect("the geom");
    (c.analysis.undefaulted.iter())
        .find(|k| k.geoms.contains(&g))
        .map_or(0, |k| k.dof)
}

/// Each case: a model without the constraint, the constraint, and the DOF it removes.
const CASES: &[(&str, &str, usize)] = &[
    // A segment whose length is all that is left takes a fixed segment's.
    (
        "space 2d;\nfixed point O = (0, 0);\nfixed segment T = (0, 3) -> (2, 3);\n\
         segment S = (0.1, 0) -> (1.7, 0.2);\ncoincident(S.start, O);\nhorizontal(S);\n",
        "equal(S, T);",
        1,
    ),
    // Two circles of free radius: equal leaves one radius free.
    (
        "space 2d;\nfixed point A = (0, 0);\nfixed point B = (5, 0);\n\
         circle C = center (0.1, 0) radius 1;\ncircle D = center (5, 0.2) radius 1.5;\n\
         coincident(C.center, A);\ncoincident(D.center, B);\n",
        "equal(C, D);",
        1,
    ),
    // A free segment pinned at its midpoint: it may still turn and be sized about it.
    (
        "space 2d;\nfixed point M = (2, 1);\nsegment S = (0.1, 0.1) -> (3.7, 2.1);\n",
        "midpoint(M, S);",
        2,
    ),
    // A free point at a fixed segment's midpoint.
    (
        "space 2d;\nfixed segment S = (0, 0) -> (4, 2);\npoint P = (1.9, 1.2);\n",
        "midpoint(P, S);",
        2,
    ),
    // A segment pinned at its start and a free point: the point is the midpoint.
    (
        "space 2d;\nfixed point O = (0, 0);\nsegment S = (0.1, 0) -> (4, 2);\n\
         point P = (1.9, 1.2);\ncoincident(S.start, O);\n",
        "midpoint(P, S);",
        2,
    ),
    // A free point mirrored across a fixed line from a fixed one.
    (
        "space 2d;\nfixed point P = (1, 2);\nfixed line L = (0, 0) -> (1, 1);\n\
         point Q = (2, 0.5);\n",
        "symmetric(P, Q, L);",
        2,
    ),
    // Two free points mirrored across a fixed line.
    (
        "space 2d;\nfixed line L = (0, 0) -> (1, 1);\npoint P = (1, 2);\npoint Q = (2, 0.5);\n",
        "symmetric(P, Q, L);",
        2,
    ),
    // A free line as the mirror of two fixed points.
    (
        "space 2d;\nfixed point P = (1, 2);\nfixed point Q = (3, 0);\n\
         line L = (0, 0.2) -> (1, 1.1);\n",
        "symmetric(P, Q, L);",
        2,
    ),
    // A free segment as that mirror: it may still slide along it and change its length.
    (
        "space 2d;\nfixed point P = (1, 2);\nfixed point Q = (3, 0);\n\
         segment L = (0, 0.2) -> (1, 1.1);\n",
        "symmetric(P, Q, L);",
        2,
    ),
];

#[test]
fn each_constraint_removes_the_freedom_it_says() {
    for &(model, constraint, removes) in CASES {
        let without = mobility(model);
        let with = mobility(&format!("{model}{constraint}\n"));
        assert_eq!(
            without - with,
            removes,
            "{constraint} removes {} DOF, not {removes}:\n{model}",
            without - with
        );
        // The nominal count says the same.
        let c = compiled(&format!("{model}{constraint}\n"));
        let last = c.model.constraints.iter().last().expect("the constraint").0;
        assert_eq!(c.model.nominal_dof_removed(last), removes, "{constraint}");
    }
}

#[test]
fn a_segment_pinned_at_its_midpoint_keeps_two_dof_in_its_record() {
    let free = "space 2d;\nfixed point M = (2, 1);\nsegment S = (0.1, 0.1) -> (3.7, 2.1);\n";
    assert_eq!(record_dof(free, "S"), 4);
    let pinned = format!("{free}midpoint(M, S);\n");
    assert_eq!(record_dof(&pinned, "S"), 2);
    assert_eq!(record_dof(&format!("{pinned}horizontal(S);\n"), "S"), 1);
    assert_eq!(record_dof(&format!("{pinned}length(S) = 5;\n"), "S"), 1);
    // Its defaults are its angle about the midpoint and its length.
    let c = compiled(&pinned);
    let names: Vec<&str> = (c.analysis.plan.defaults.iter())
        .map(|d| d.name.as_str())
        .collect();
    assert_eq!(names, ["S_angle", "S_length"]);
}

#[test]
fn an_equal_length_is_not_a_known_length() {
    // Two free segments of equal length: nothing else fixes either, so both stay as free as
    // before but for the one DOF equal ties, and neither is sized by it.
    let text = "space 2d;\nsegment A = (0, 0) -> (2, 0);\nsegment B = (0, 1) -> (2.5, 1);\n\
                equal(A, B);\n";
    let c = compiled(text);
    assert!(c.analysis.unsolved.is_empty());
    // A is held where it is sketched (the model fixes nothing) but its length stays free;
    // B keeps its position and angle free, and its length follows A's: 1 + 4 - 1.
    assert_eq!(c.analysis.free_defaults().len(), 4);
    let s =
        gcs_compiler::solve(&c.model, &c.analysis, &c.model.default_params(), &[]).expect("solves");
    assert!(s.max_residual < 1e-12);
    // Without a known side, equal alone sizes nothing: the first step is a default.
    let one = "space 2d;\nfixed point O = (0, 0);\nsegment A = (0, 0) -> (2, 0);\n\
               segment B = (0, 1) -> (2.5, 1);\ncoincident(A.start, O);\nequal(A, B);\n";
    let c = compiled(one);
    let first_size = (c.analysis.plan.steps.iter())
        .position(|s| matches!(s.op, gcs_compiler::plan::Op::SetDim { .. }))
        .expect("a sizing");
    let first_default = (c.analysis.plan.steps.iter())
        .position(|s| matches!(s.op, gcs_compiler::plan::Op::Default(_)))
        .expect("a default");
    assert!(first_default < first_size, "{:#?}", c.analysis.plan.steps);
}

/// Solves `text` with `param` set to `value`: the error, or the solution checked finite.
fn solve_at(text: &str, param: &str, value: f64) -> Result<f64, gcs_runtime::error::SolveError> {
    let c = compiled(text);
    let mut params = c.model.default_params();
    let i = (c.model.params.iter())
        .position(|(_, p)| p.name == param)
        .expect("the param");
    params[i] = value;
    let branches: Vec<usize> = c.analysis.plan.branches.iter().map(|b| b.default).collect();
    let s = gcs_compiler::solve(&c.model, &c.analysis, &params, &branches)?;
    for (n, x) in s.points.iter().chain(&s.vectors) {
        assert!(x.iter().all(|v| v.is_finite()), "{n} = {x:?}");
    }
    for (n, x) in &s.scalars {
        assert!(x.is_finite(), "{n} = {x}");
    }
    Ok(s.max_residual)
}

#[test]
fn degenerate_cases_are_errors_naming_the_constraint() {
    // The mirror line of two points that coincide: no direction.
    let mirror = "space 2d;\nparam qy = 0;\nfixed point P = (1, 2);\nfixed point Q = (1, qy);\n\
                  line L = (0, 0.2) -> (1, 1.1);\nm: symmetric(P, Q, L);\n";
    assert!(solve_at(mirror, "qy", 0.0).expect("solves") < 1e-12);
    let e = solve_at(mirror, "qy", 2.0).expect_err("no mirror line");
    assert_eq!((e.label.as_ref(), e.kind), ("m", ErrorKind::Degenerate));
    // A segment pinned at its end whose midpoint is that end: zero length.
    let midpoint = "space 2d;\nparam my = 1;\nfixed point O = (0, 0);\nfixed point M = (0, my);\n\
                    segment S = (0.1, 0.1) -> (0.2, 2.1);\na: coincident(S.end, O);\n\
                    c: midpoint(M, S);\n";
    assert!(solve_at(midpoint, "my", 1.0).expect("solves") < 1e-12);
    let e = solve_at(midpoint, "my", 0.0).expect_err("zero length");
    assert_eq!((e.label.as_ref(), e.kind), ("c", ErrorKind::Degenerate));
    // A segment pinned at its midpoint whose end is brought onto it.
    let onto = "space 2d;\nparam ex = 3;\nfixed point M = (0, 0);\nfixed point E = (ex, 1);\n\
                segment S = (-2.9, -1.1) -> (3.1, 0.9);\na: midpoint(M, S);\n\
                b: coincident(S.end, E);\n";
    assert!(solve_at(onto, "ex", 3.0).expect("solves") < 1e-12);
    let e = solve_at(&onto.replace("(ex, 1)", "(ex, 0)"), "ex", 0.0).expect_err("zero length");
    assert_eq!((e.label.as_ref(), e.kind), ("b", ErrorKind::Degenerate));
    // A point on the mirror is its own image: no error.
    let on_line = "space 2d;\nparam py = 1;\nfixed line L = (0, 0) -> (1, 0);\n\
                   fixed point P = (1, py);\npoint Q = (2, -1);\nsymmetric(P, Q, L);\n";
    assert!(solve_at(on_line, "py", 0.0).expect("solves") < 1e-12);
    // An equal radius taken from a circle of zero radius is zero, and valid.
    let zero =
        "space 2d;\nparam r = 1;\nfixed point A = (0, 0);\ncircle C = center (0, 0) radius 1;\n\
                circle D = center (3, 0) radius 1;\ncoincident(C.center, A);\nradius(C) = r;\n\
                equal(C, D);\ndistance(A, D.center) = 3;\n";
    assert!(solve_at(zero, "r", 0.0).is_ok());
}
