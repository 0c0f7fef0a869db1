//! Redundancy, completely: every redundant constraint is reported with what implies it (the
//! support of its run-time check), and every inconsistent redundant set at the default params
//! is one diagnostic: the checked constraint with the size of the conflict, and a secondary
//! label on each constraint and fixed geom that implies it. What stops the plan (loci that
//! miss) is still reported, after the checks that failed before it, with what it builds on.

use expect_test::expect;
use gcs_compiler::interp::{self, Audit, Choice};
use gcs_compiler::pipeline::Compiled;
use gcs_compiler::plan::Op;
use gcs_lang::Diagnostic;
use gcs_runtime::error::ErrorKind;

fn compiled(text: &str) -> Compiled {
    match gcs_compiler::compile("model.gcs", text.as_bytes()) {
        Ok(c) => c,
        Err(e) => panic!("does not compile: {e:?}\n{text}"),
    }
}

/// The plan run at the default params on the sketch's branches, past its failed checks.
fn audit(c: &Compiled) -> Audit {
    let plan = &c.analysis.plan;
    let branches = plan.branches.iter().map(|b| b.default).collect();
    interp::audit(
        &c.model,
        plan,
        &c.model.default_params(),
        &plan.sketch_defaults(),
        &Choice::Given(branches),
    )
}

/// The support of the check of `constraint`'s last relation: its constraints' and fixed
/// geoms' names, each sorted.
fn support(c: &Compiled, constraint: &str) -> (Vec<String>, Vec<String>) {
    let plan = &c.analysis.plan;
    let i = (plan.steps.iter())
        .position(|s| match s.op {
            Op::Check { constraint: k, .. } => {
                c.model.constraints[k].name == constraint && s.satisfies.contains(&k)
            }
            _ => false,
        })
        .unwrap_or_else(|| panic!("no check of {constraint}"));
    let s = plan.support(&c.model, i);
    let mut constraints: Vec<String> = (s.constraints.iter())
        .map(|&k| c.model.constraints[k].name.clone())
        .collect();
    let mut fixed: Vec<String> = (s.fixed.iter())
        .map(|&g| c.model.geoms[g].name.clone())
        .collect();
    constraints.sort();
    fixed.sort();
    (constraints, fixed)
}

fn names(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

fn errors(c: &Compiled) -> Vec<&Diagnostic> {
    c.diagnostics.iter().filter(|d| d.is_error()).collect()
}

/// The source text under each secondary label of `d`, in order.
fn secondary_texts(c: &Compiled, d: &Diagnostic) -> Vec<String> {
    (d.secondary.iter())
        .map(|l| c.source.text()[l.span.range()].to_string())
        .collect()
}

/// The line `gcs check` prints for redundant constraint `name`.
fn redundant_line(c: &Compiled, name: &str) -> String {
    let report = gcs_compiler::report::check_report(&c.model, &c.analysis);
    (report.lines())
        .find(|l| l.trim_start().starts_with(&format!("redundant: {name} ")))
        .unwrap_or_else(|| panic!("no redundant {name} in\n{report}"))
        .trim()
        .to_string()
}

/// Two conflicts that have nothing to do with each other: `x` asks `C`, which `b` and `c`
/// place from `A` and `B`, to be 3.5 from `L`; `g` asks `E`, which `e` and `f` place from `D`
/// and `L`, to be 11.5 from `A`.
const TWO: &str = "space 2d;
fixed point A = (0, 0);
fixed point B = (3, 0);
point C = (1, 2);
fixed point D = (10, 0);
fixed line L = (0, -1) -> (1, -1);
point E = (11, 2);
b: distance(A, C) = 2;
c: distance(B, C) = 2.5;
x: distance(C, L) = 3.5;
e: distance(D, E) = 2;
f: on(E, L);
g: distance(E, A) = 11.5;
";

#[test]
fn two_independent_conflicts_are_both_reported_with_their_supports_and_sizes() {
    let c = compiled(TWO);
    // C is where the circles of b and c cross above AB; E where f's line meets e's circle
    // nearer the sketch, to the right of D.
    let cx: f64 = (4.0 - 6.25 + 9.0) / 6.0;
    let cy = (4.0 - cx * cx).sqrt();
    let x_off = 3.5 - (cy + 1.0);
    let ex = 10.0 + 3f64.sqrt();
    let g_off = (ex * ex + 1.0).sqrt() - 11.5;
    assert!((x_off - 0.846_405_430_584_630_9).abs() < 1e-12);
    assert!((g_off - 0.274_591_973_880_774_3).abs() < 1e-12);

    let f = c.analysis.plan.branches.iter().find(|b| b.name == "f");
    assert_eq!(
        f.map(|b| b.default),
        Some(1),
        "E's sketch branch, failed checks or not"
    );

    let audit = audit(&c);
    assert_eq!(audit.stopped, None);
    let failed: Vec<(&str, ErrorKind, f64)> = (audit.failed.iter())
        .map(|f| (&*f.error.label, f.error.kind, f.error.magnitude))
        .collect();
    assert_eq!(failed.len(), 2, "{failed:?}");
    let by = |name: &str| failed.iter().find(|f| f.0 == name).copied();
    let (_, kind, m) = by("x").expect("x fails");
    assert_eq!(kind, ErrorKind::Inconsistent);
    assert!((m - x_off).abs() < 1e-12, "x off by {m}, not {x_off}");
    let (_, kind, m) = by("g").expect("g fails");
    assert_eq!(kind, ErrorKind::Inconsistent);
    assert!((m - g_off).abs() < 1e-12, "g off by {m}, not {g_off}");

    assert_eq!(
        support(&c, "x"),
        (names(&["b", "c"]), names(&["A", "B", "L"]))
    );
    assert_eq!(
        support(&c, "g"),
        (names(&["e", "f"]), names(&["A", "D", "L"]))
    );

    // One diagnostic a set, in source order, each on its constraint with its size and a
    // label on every member of its support.
    let errs = errors(&c);
    assert_eq!(errs.len(), 2, "{errs:#?}");
    let text = |d: &Diagnostic| c.source.text()[d.primary.span.range()].to_string();
    assert_eq!(text(errs[0]), "x: distance(C, L) = 3.5;");
    assert_eq!(
        errs[0].primary.message,
        "conflicting constraint: it is off by 0.846405"
    );
    assert_eq!(
        secondary_texts(&c, errs[0]),
        [
            "A",
            "B",
            "L",
            "b: distance(A, C) = 2;",
            "c: distance(B, C) = 2.5;"
        ]
    );
    assert_eq!(text(errs[1]), "g: distance(E, A) = 11.5;");
    assert_eq!(
        errs[1].primary.message,
        "conflicting constraint: it is off by 0.274592"
    );
    assert_eq!(
        secondary_texts(&c, errs[1]),
        ["A", "D", "L", "e: distance(D, E) = 2;", "f: on(E, L);"]
    );
    assert_eq!(
        errs[1].notes[0],
        "`g` is implied by e and f (with fixed A, fixed D and fixed L), and disagrees with \
         them by 0.274592: change or remove one of them"
    );
}

#[test]
fn the_conflicts_render_as_one_diagnostic_each() {
    let c = compiled(TWO);
    let text = gcs_lang::diagnostic::render_plain(&c.source, &c.diagnostics);
    expect![[r#"
        error: `x` conflicts with the constraints that imply it
           ┌─ model.gcs:10:1
           │
         2 │ fixed point A = (0, 0);
           │             - fixed: part of what implies `x`
         3 │ fixed point B = (3, 0);
           │             - fixed: part of what implies `x`
           ·
         6 │ fixed line L = (0, -1) -> (1, -1);
           │            - fixed: part of what implies `x`
         7 │ point E = (11, 2);
         8 │ b: distance(A, C) = 2;
           │ ---------------------- part of what implies `x`
         9 │ c: distance(B, C) = 2.5;
           │ ------------------------ part of what implies `x`
        10 │ x: distance(C, L) = 3.5;
           │ ^^^^^^^^^^^^^^^^^^^^^^^^ conflicting constraint: it is off by 0.846405
           │
           = `x` is implied by b and c (with fixed A, fixed B and fixed L), and disagrees with them by 0.846405: change or remove one of them
           = constraint `x` (distance(C, L) = 3.5) cannot be met: it is inconsistent with the constraints already met, by 0.8464054305846309

        error: `g` conflicts with the constraints that imply it
           ┌─ model.gcs:13:1
           │
         2 │ fixed point A = (0, 0);
           │             - fixed: part of what implies `g`
           ·
         5 │ fixed point D = (10, 0);
           │             - fixed: part of what implies `g`
         6 │ fixed line L = (0, -1) -> (1, -1);
           │            - fixed: part of what implies `g`
           ·
        11 │ e: distance(D, E) = 2;
           │ ---------------------- part of what implies `g`
        12 │ f: on(E, L);
           │ ------------ part of what implies `g`
        13 │ g: distance(E, A) = 11.5;
           │ ^^^^^^^^^^^^^^^^^^^^^^^^^ conflicting constraint: it is off by 0.274592
           │
           = `g` is implied by e and f (with fixed A, fixed D and fixed L), and disagrees with them by 0.274592: change or remove one of them
           = constraint `g` (distance(E, A) = 11.5) cannot be met: it is inconsistent with the constraints already met, by 0.2745919738807743

    "#]]
    .assert_eq(&text);
}

#[test]
fn the_three_sides_of_a_triangle_miss_the_triangle_inequality_by_its_size() {
    // Nothing fixed: A is grounded, B placed 3 from it by `ab`, C 1 from A by `ac`; `bc` asks
    // 1.7 from B, and 1 + 1.7 falls 0.3 short of 3.
    let c = compiled(
        "space 2d;\npoint A = (0, 0);\npoint B = (3, 0.2);\npoint C = (1.5, 0.5);\n\
         ab: distance(A, B) = 3;\nac: distance(A, C) = 1;\nbc: distance(B, C) = 1.7;\n",
    );
    let audit = audit(&c);
    assert!(audit.failed.is_empty(), "{:?}", audit.failed);
    let stop = audit.stopped.expect("the loci miss");
    assert_eq!(&*stop.error.label, "bc");
    assert_eq!(stop.error.kind, ErrorKind::NoIntersection);
    assert!((stop.error.magnitude - 0.3).abs() < 1e-12, "{}", stop.error);
    let errs = errors(&c);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert_eq!(errs[0].primary.message, "no assembly: the loci miss by 0.3");
    assert_eq!(
        secondary_texts(&c, errs[0]),
        ["ab: distance(A, B) = 3;", "ac: distance(A, C) = 1;"]
    );
    assert_eq!(
        errs[0].notes[0],
        "`bc` builds on ab and ac: with them its loci miss by 0.3; change one of them"
    );

    // Two sides fixed, the third redundant: the check is off by the same kind of miss.
    let c = compiled(
        "space 2d;\nfixed point A = (0, 0);\nfixed point B = (3, 0);\npoint C = (1, 2);\n\
         a: distance(A, B) = 3.3;\nb: distance(A, C) = 2;\nc: distance(B, C) = 2.5;\n",
    );
    let errs = errors(&c);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert_eq!(
        errs[0].message,
        "`a` conflicts with the constraints that imply it"
    );
    assert_eq!(
        errs[0].primary.message,
        "conflicting constraint: it is off by 0.3"
    );
    assert_eq!(secondary_texts(&c, errs[0]), ["A", "B"]);
    assert_eq!(support(&c, "a"), (names(&[]), names(&["A", "B"])));
    let failed = audit_failed(&c);
    assert_eq!(failed.len(), 1);
    assert!((failed[0].1 - 0.3).abs() < 1e-12, "{failed:?}");
}

/// The failed checks of a run at the default params: label and magnitude.
fn audit_failed(c: &Compiled) -> Vec<(String, f64)> {
    (audit(c).failed.iter())
        .map(|f| (f.error.label.to_string(), f.error.magnitude))
        .collect()
}

#[test]
fn a_consistent_duplicate_names_what_implies_it() {
    let c = compiled(
        "space 2d;\nfixed point A = (0, 0);\nfixed point C = (5, 0);\npoint B = (2, 2);\n\
         orig: distance(A, B) = 3;\ndistance(C, B) = 4;\nz_again: distance(A, B) = 3;\n",
    );
    assert!(errors(&c).is_empty(), "{:#?}", c.diagnostics);
    assert_eq!(
        support(&c, "z_again"),
        (names(&["distance_C_B", "orig"]), names(&["A", "C"]))
    );
    assert_eq!(
        redundant_line(&c, "z_again"),
        "redundant: z_again (distance(A, B) = 3, line 7) is implied by orig and distance_C_B \
         (with fixed A and fixed C); it is kept as a run-time check"
    );
}

#[test]
fn a_redundant_angle_sum_is_implied_by_its_two_terms() {
    let model = "space 2d;\nparam a = 20 deg;\nparam b = 30 deg;\nfixed vector X = (1, 0);\n\
                 vector u = (1, 0.3);\nvector v = (0.5, 1);\n\
                 xu: angle(X, u) = a;\nuv: angle(u, v) = b;\nxv: angle(X, v) = a + b{extra};\n";
    let c = compiled(&model.replace("{extra}", ""));
    assert!(errors(&c).is_empty(), "{:#?}", c.diagnostics);
    assert_eq!(support(&c, "xv"), (names(&["uv", "xu"]), names(&["X"])));
    assert_eq!(
        redundant_line(&c, "xv"),
        "redundant: xv (angle(X, v) = a + b, line 9) is implied by xu and uv (with fixed X); \
         it is kept as a run-time check"
    );

    // Five degrees more than the two terms make.
    let c = compiled(&model.replace("{extra}", " + 5 deg"));
    let failed = audit_failed(&c);
    assert_eq!(failed.len(), 1, "{failed:?}");
    assert_eq!(failed[0].0, "xv");
    assert!(
        (failed[0].1 - 5f64.to_radians()).abs() < 1e-12,
        "{failed:?}"
    );
    let errs = errors(&c);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert_eq!(
        errs[0].primary.message,
        "conflicting constraint: it is off by 0.0872665 rad (5 deg)"
    );
    assert_eq!(
        secondary_texts(&c, errs[0]),
        ["X", "xu: angle(X, u) = a;", "uv: angle(u, v) = b;"]
    );
}

#[test]
fn the_checks_before_a_stop_are_reported_with_it() {
    // `ab` is off by 0.5 (a check); then `c`'s circles miss by 1 and the plan stops there.
    let c = compiled(
        "space 2d;\nfixed point A = (0, 0);\nfixed point B = (3, 0);\nfixed point D = (10, 0);\n\
         point C = (1, 2);\npoint E = (11, 1);\nab: distance(A, B) = 3.5;\n\
         b: distance(A, C) = 1;\nc: distance(B, C) = 1;\ne: distance(D, E) = 1;\n",
    );
    let audit = audit(&c);
    assert_eq!(audit.failed.len(), 1, "{:?}", audit.failed);
    assert_eq!(&*audit.failed[0].error.label, "ab");
    assert!((audit.failed[0].error.magnitude - 0.5).abs() < 1e-12);
    let stop = audit.stopped.expect("c stops the plan");
    assert_eq!(
        (&*stop.error.label, stop.error.kind),
        ("c", ErrorKind::NoIntersection)
    );
    assert!((stop.error.magnitude - 1.0).abs() < 1e-12, "{}", stop.error);
    let errs = errors(&c);
    let heads: Vec<(&str, &str)> = (errs.iter())
        .map(|d| (d.message.as_str(), d.primary.message.as_str()))
        .collect();
    assert_eq!(
        heads,
        [
            (
                "`ab` conflicts with the constraints that imply it",
                "conflicting constraint: it is off by 0.5"
            ),
            (
                "`c` cannot be met with the default params",
                "no assembly: the loci miss by 1"
            ),
        ]
    );
    assert_eq!(
        secondary_texts(&c, errs[1]),
        ["A", "B", "b: distance(A, C) = 1;"]
    );
}

#[test]
fn a_marker_pinned_by_a_revolute_implies_through_the_revolute() {
    // The plan reads `P.k` from the register of `G0.m`, where `p0` pinned it: the point-line
    // part of `z` rests on `p0` although no register it reads measures `P`.
    let c = compiled(
        "space 2d;\nfixed body G0 { marker m = (2, 1) x (1, 0); }\n\
         fixed body G1 { marker r = (0, 0) x (1, 0); }\n\
         body P at (1, 1) { marker k = (0, 0) x (0, 1); }\n\
         p0: revolute(P.k, G0.m);\nz: prismatic(P.k, G1.r);\n",
    );
    let failed = audit_failed(&c);
    assert_eq!(failed, [("z".to_string(), 1.0)]);
    let errs = errors(&c);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert_eq!(
        errs[0].notes[0],
        "`z` is implied by p0 (with fixed G0 and fixed G1), and disagrees with them by 1: \
         change or remove one of them"
    );
}

#[test]
fn an_iterated_model_reports_every_conflict_and_nothing_else() {
    // The triad six-bar iterates on a default; two distances between its fixed pivots
    // conflict with where they are. A failed check used to stop the sketch run that chooses
    // the default's start, and the iteration then failed from the wrong start as well.
    let path = format!(
        "{}/../examples/triad_sixbar.gcs",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("the example");
    let c = compiled(&format!(
        "{text}\nbad: distance(O1, O3) = 3;\nzz: distance(O1, O2) = 7;\n"
    ));
    assert!(!c.analysis.plan.iterations.is_empty(), "the plan iterates");
    let errs = errors(&c);
    let heads: Vec<&str> = errs.iter().map(|d| d.message.as_str()).collect();
    assert_eq!(
        heads,
        [
            "`bad` conflicts with the constraints that imply it",
            "`zz` conflicts with the constraints that imply it"
        ]
    );
    let mut failed = audit_failed(&c);
    failed.sort_by(|a, b| a.0.cmp(&b.0));
    assert_eq!(failed.len(), 2, "{failed:?}");
    assert!(
        (failed[0].1 - (3.0 - 5f64.sqrt())).abs() < 1e-12,
        "{failed:?}"
    );
    assert!(
        (failed[1].1 - (52f64.sqrt() - 7.0)).abs() < 1e-12,
        "{failed:?}"
    );
    assert_eq!(support(&c, "bad"), (names(&[]), names(&["O1", "O3"])));
}

#[test]
fn a_normal_run_still_stops_at_the_first_failed_check() {
    let c = compiled(TWO);
    let plan = &c.analysis.plan;
    let branches = plan.branches.iter().map(|b| b.default).collect();
    let e = interp::run(
        &c.model,
        plan,
        &c.model.default_params(),
        &Choice::Given(branches),
    )
    .expect_err("inconsistent");
    // The first of the two in plan order.
    let first = audit(&c).failed[0].error.clone();
    assert_eq!(e, first);
}

#[test]
fn every_redundant_check_of_the_test_model_names_its_support() {
    let path = format!(
        "{}/../tests/models/redundant_checks.gcs",
        env!("CARGO_MANIFEST_DIR")
    );
    let c = compiled(&std::fs::read_to_string(&path).expect("the model"));
    assert!(errors(&c).is_empty(), "{:#?}", c.diagnostics);
    assert_eq!(c.analysis.redundant.len(), 9);
    assert_eq!(support(&c, "q_r"), (names(&[]), names(&["R"])));
    assert_eq!(
        support(&c, "c_flat"),
        (names(&["a_start", "b_end", "d_long"]), names(&["A", "B"]))
    );
    assert_eq!(
        support(&c, "o_q"),
        (
            names(&["a_start", "b_end", "d_long", "h_p", "i_p"]),
            names(&["A", "B", "Q"])
        )
    );
    let report = gcs_compiler::report::check_report(&c.model, &c.analysis);
    assert!(!report.contains("implied by the others"), "{report}");
}

#[test]
fn a_closure_that_cannot_close_names_what_it_builds_on() {
    // The triad six-bar with a third link too short to reach the platform: its iteration
    // cannot close `j3` anywhere on the turn (no assembly), and the error names the loop that
    // `j3` closes.
    let path = format!(
        "{}/../examples/triad_sixbar.gcs",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).expect("the example");
    let short = "point p = (0, 0.3); }";
    let text = text.replacen("point p = (0, 3); }", short, 1);
    assert!(text.contains(short), "the model changed");
    let c = compiled(&text);
    let audit = audit(&c);
    assert!(audit.failed.is_empty(), "{:?}", audit.failed);
    let stop = audit.stopped.expect("it does not close");
    assert_eq!(
        (&*stop.error.label, stop.error.kind),
        ("j3", ErrorKind::NoAssembly)
    );
    let step = stop.step.expect("its last close");
    assert!(matches!(c.analysis.plan.steps[step].op, Op::Close { .. }));
    let support = c.analysis.plan.support(&c.model, step);
    let mut named: Vec<&str> = (support.constraints.iter())
        .map(|&k| c.model.constraints[k].name.as_str())
        .collect();
    named.sort();
    assert_eq!(
        named,
        [
            "coincident_crank_o_O1",
            "coincident_link1_o_O2",
            "coincident_link2_o_O3",
            "coincident_link3_o_crank_t",
            "drive",
            "j1",
            "j2"
        ]
    );
    let errs = errors(&c);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert!(
        (errs[0].primary.message).starts_with(
            "no assembly: over the whole turn of the iterated angle it stays at least "
        ),
        "{errs:#?}"
    );
    assert_eq!(errs[0].secondary.len(), 7 + 4, "{errs:#?}");
}

/// `gcs explain` says what implies each run-time check, as `gcs check` does.
#[test]
fn explain_names_what_implies_each_check() {
    let text = std::fs::read_to_string(format!(
        "{}/../tests/models/redundant_checks.gcs",
        env!("CARGO_MANIFEST_DIR")
    ))
    .expect("the test model");
    let c = compiled(&text);
    let words = gcs_compiler::explain::explain(&c.model, &c.analysis.plan);
    for line in [
        "Check that q_r: radius(R) = rr holds: it is implied by fixed R.",
        "Check that c_flat: horizontal(s) holds: it is implied by a_start, b_end and d_long (with fixed A and fixed B).",
    ] {
        assert!(words.contains(line), "no `{line}` in:\n{words}");
    }
    assert!(!words.contains("the steps before"), "{words}");
}

#[test]
fn redundant_sketcher_constraints_name_their_support() {
    let path = format!(
        "{}/../tests/models/redundant_sketcher.gcs",
        env!("CARGO_MANIFEST_DIR")
    );
    let c = compiled(&std::fs::read_to_string(&path).expect("the model"));
    assert!(errors(&c).is_empty(), "{:#?}", c.diagnostics);
    let mut redundant: Vec<String> = (c.analysis.redundant.iter())
        .map(|&k| c.model.constraints[k].name.clone())
        .collect();
    redundant.sort();
    assert_eq!(redundant, names(&["c_mid", "d_mirror", "e_equal"]));
    let ends = names(&["a_start", "b_end"]);
    assert_eq!(
        support(&c, "c_mid"),
        (ends.clone(), names(&["A", "B", "M"]))
    );
    assert_eq!(
        support(&c, "d_mirror"),
        (ends.clone(), names(&["A", "B", "axis"]))
    );
    assert_eq!(support(&c, "e_equal"), (ends, names(&["A", "B", "T"])));
    // Moved off, each is a conflict of its own size.
    for (param, value, name, size) in [("gap", 0.25, "c_mid", 0.25), ("other", 4.5, "e_equal", 0.5)]
    {
        let text = std::fs::read_to_string(&path).expect("the model").replace(
            &format!("param {param} = "),
            &format!("param {param} = {value} + 0 * "),
        );
        let failed = audit_failed(&compiled(&text));
        assert_eq!(failed.len(), 1, "{failed:?}");
        assert_eq!(failed[0].0, name);
        assert!((failed[0].1 - size).abs() < 1e-12, "{failed:?}");
    }
}

/// A square not tied to anything, both widths dimensioned: its height is a free motion. The
/// coincidence that closes it depends on the height's default on paper (the closing corner
/// is placed after it), but moves with it along the very line it must lie on, so its error
/// does not change: the default is a free motion (mobility 1), never an iteration on a length
/// whose every value solves; any height solves, and an inconsistent second width is refused.
#[test]
fn a_check_a_default_moves_along_its_own_line_is_no_iteration() {
    let square = |top: &str| {
        format!(
            "space 2d;
segment s1 = (0.1, 0) -> (20, 0.2);
segment s2 = (20, 0.2) -> (20.1, 19.8);
segment s3 = (20.1, 19.8) -> (0, 20);
segment s4 = (0, 20) -> (0.1, 0);
coincident(s1.end, s2.start);
coincident(s2.end, s3.start);
coincident(s3.end, s4.start);
coincident(s4.end, s1.start);
horizontal(s1); horizontal(s3); vertical(s2); vertical(s4);
length(s1) = 20;
length(s3) = {top};
"
        )
    };
    let c = compiled(&square("20"));
    let plan = &c.analysis.plan;
    assert!(
        plan.iterations.is_empty(),
        "an iteration: {:?}",
        plan.iterations
    );
    let free: Vec<&str> = (c.analysis.free_defaults().iter())
        .map(|d| plan.defaults[d.0 as usize].name.as_str())
        .collect();
    assert_eq!(free, ["s2_length"]);
    let at = |height: f64| {
        let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
        let all = c.model.top_level().map(|(id, _)| id).collect();
        gcs_compiler::solve_plan_with(
            &c.model,
            plan,
            &all,
            &c.model.default_params(),
            &branches,
            &[height],
        )
    };
    for height in [5.0, 19.6, 40.0] {
        let s = at(height).unwrap_or_else(|e| panic!("height {height}: {e}"));
        assert!(
            s.max_residual < 1e-12,
            "height {height}: {}",
            s.max_residual
        );
    }
    // The second width 21: the coincidence's implied part is off by one, whatever the height.
    let c = compiled(&square("21"));
    assert!(c.analysis.plan.iterations.is_empty());
    let errs = errors(&c);
    assert_eq!(errs.len(), 1, "{errs:#?}");
    assert!(
        errs[0].message.contains("coincident_s3_end_s4_start"),
        "{errs:#?}"
    );
}

/// A closed profile of segments and fillet circles, its last corner's coincidences and
/// tangencies left to close it. It once took a default closed by a point's distance from the
/// line it was just slid along (zero for every value), then by the tangency that default
/// displaced (a double root); its directions are all known, so a linear stage now closes it
/// with no default at all (`profiles.rs` covers the family).
#[test]
fn a_closed_profile_closes_with_no_default() {
    let c = compiled(
        "space 2d;
param r = 1;
fixed point P = (1, 0);
segment L0 = (1, 0) -> (5, 0);
segment L1 = (6, 1) -> (6, 3);
segment L2 = (5, 4) -> (1, 4);
segment L3 = (0, 3) -> (0, 1);
circle F1 = center (5, 1) radius 1;
circle F2 = center (5, 3) radius 1;
circle F3 = center (1, 3) radius 1;
circle F0 = center (1, 1) radius 1;
coincident(L0.start, P);
horizontal(L0); vertical(L1); horizontal(L2); vertical(L3);
radius(F1) = r; radius(F2) = r; radius(F3) = r; radius(F0) = r;
on(L0.end, F1); on(L1.start, F1); tangent(L0, F1); tangent(L1, F1);
on(L1.end, F2); on(L2.start, F2); tangent(L1, F2); tangent(L2, F2);
on(L2.end, F3); on(L3.start, F3); tangent(L2, F3); tangent(L3, F3);
on(L3.end, F0); on(L0.start, F0); tangent(L3, F0); tangent(L0, F0);
length(L1) = 2; length(L2) = 4;
",
    );
    let plan = &c.analysis.plan;
    assert!(plan.defaults.is_empty(), "{:?}", plan.defaults);
    assert!(plan
        .steps
        .iter()
        .any(|s| matches!(s.op, Op::Planar(gcs_compiler::plan::PlanarOp::Linear(_)))));
    assert!(errors(&c).is_empty(), "{:#?}", errors(&c));
}

/// A square with nothing fixed, both widths dimensioned: its place (two translations: the
/// horizontal and vertical constraints anchor its turn) and its height are free, and one of
/// the four coincidences' equations is implied by the other width. SolveSpace reports 3 DOF.
const SQUARE: &str = "space 2d;
segment s1 = (0, 0) -> (20, 0);
segment s2 = (20, 0) -> (20, 20);
segment s3 = (20, 20) -> (0, 20);
segment s4 = (0, 20) -> (0, 0);
coincident(s1.end, s2.start); coincident(s2.end, s3.start);
coincident(s3.end, s4.start); coincident(s4.end, s1.start);
horizontal(s1); vertical(s2); horizontal(s3); vertical(s4);
length(s1) = 20;
length(s3) = 20;
";

#[test]
fn a_doubly_dimensioned_square_has_mobility_three_and_one_redundancy() {
    let c = compiled(SQUARE);
    let plan = &c.analysis.plan;
    assert!(
        plan.iterations.is_empty(),
        "a free motion is a default, never an iteration"
    );
    assert_eq!(
        plan.grounded_dof, 2,
        "only the place is grounded: the turn is anchored"
    );
    assert_eq!(c.analysis.free_defaults().len(), 1);
    let report = gcs_compiler::report::check_report(&c.model, &c.analysis);
    let status: Vec<&str> = (report.lines())
        .skip_while(|l| !l.starts_with("analysis:"))
        .collect();
    expect![[r#"
        analysis: under-constrained, with redundant constraints (1 redundant equation): mobility 3: 2 of its placement, held where the sketch has it (nothing is fixed), and 1 held by a default at its sketch value
          default s2_length (sketch 20): the length of s2
          implied in part: coincident_s3_end_s4_start (coincident(s3.end, s4.start), line 7) is partly implied by coincident_s1_end_s2_start, coincident_s2_end_s3_start, coincident_s4_end_s1_start, horizontal_s1, vertical_s2, horizontal_s3, vertical_s4, length_s1 and length_s3; that part is kept as a run-time check"#]]
    .assert_eq(&status.join("\n"));
    // Every height solves, and the square keeps its widths.
    let all = c.model.top_level().map(|(id, _)| id).collect();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    for h in [5.0, 20.0, 31.0] {
        let params = c.model.default_params();
        let s =
            gcs_compiler::solve::solve_plan_with(&c.model, plan, &all, &params, &branches, &[h]);
        let s = s.unwrap_or_else(|e| panic!("height {h}: {e}"));
        assert!(
            s.max_residual < 1e-12,
            "height {h}: residual {}",
            s.max_residual
        );
    }
    // Widths of 20 and 25 conflict: the coincidence the other width implies in part is off
    // by 5.
    let c = compiled(&SQUARE.replace("length(s3) = 20", "length(s3) = 25"));
    let a = audit(&c);
    let f = (a.failed.first().or(a.stopped.as_ref())).expect("the widths conflict");
    assert_eq!(f.error.kind, ErrorKind::Inconsistent);
    assert_eq!(f.error.label, "coincident_s3_end_s4_start");
    assert!(
        (f.error.magnitude - 5.0).abs() < 1e-9,
        "{}",
        f.error.magnitude
    );
}
