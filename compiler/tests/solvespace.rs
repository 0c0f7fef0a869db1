//! SolveSpace's own constraint-test sketches (its `test/constraint/*/`, `test/request/*/`, and
//! the two sketch fixtures of `test/core/prune/` and `test/analysis/contour_area/`), translated
//! into `.gcs` in `tests/solvespace/`, with the four cases of issue 37 (`issue_*.gcs`). What
//! could not be translated, and why, is in `tests/solvespace/README.md`.
//!
//! Each file says in its header what SolveSpace expects, as `// expect:` lines:
//!
//! - `solved`: SolveSpace's test loads the sketch, solves it and saves it unchanged
//!   (`CHECK_LOAD`, `CHECK_SAVE`): it solves, and moves nothing. gcs must solve it (as
//!   `gcs solve` does, from the sketch), every constraint re-checked by the verifier within
//!   1e-9 of the model's size, and leave every point where the sketch has it (the same
//!   tolerance).
//! - `dof N`: SolveSpace's degrees of freedom (its parameters less the rank of its equations,
//!   placement included: a SolveSpace sketch is not grounded). gcs's is its mobility (the free
//!   defaults) plus the placement its grounding holds, which is counted here independently:
//!   the rank of the rigid motions' action on the solved points and directions, less the turn
//!   when a constraint is horizontal or vertical (those hold the turn); nothing when a geom is
//!   fixed (nothing is grounded).
//! - `redundant N`: the constraints implied by the others (default 0): gcs's redundant
//!   constraints and those implied in part, each kept as a run-time check.
//! - `conflict NAME=GAP … [names NAME …]`: SolveSpace fails. gcs must refuse it at the
//!   default params (the first check that fails, or what stops the run), on one of the
//!   constraints listed (those whose removal makes the sketch consistent, each with the gap
//!   computed by hand in the file's header: how far its value is from the nearest it could
//!   take), by that gap within 1e-9; and its error must name the constraints after `names`.
//!
//! Where gcs disagrees with SolveSpace, the disagreement is listed in [`KNOWN`]: the test
//! asserts that the disagreements found are exactly those, so that one fixed fails it too.

use gcs_compiler::solution::Solution;
use std::collections::BTreeSet;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// Where gcs disagrees with SolveSpace: (file, the disagreement as [`check`] words it). Each is
/// described in `tests/solvespace/README.md`.
const KNOWN: &[(&str, &str)] = &[];

#[derive(Debug, Default)]
struct Expect {
    solved: bool,
    dof: Option<usize>,
    redundant: usize,
    /// The constraints whose removal makes the sketch consistent, each with its gap (where
    /// one is computed), and the constraints the error must name.
    conflict: Option<Conflict>,
}

/// A conflict: each constraint whose removal makes the sketch consistent with its gap, and the
/// constraints its error must name.
type Conflict = (Vec<(String, f64)>, Vec<String>);

fn expect_of(text: &str) -> Expect {
    let mut e = Expect::default();
    for line in text.lines() {
        let Some(rest) = line.strip_prefix("// expect: ") else {
            continue;
        };
        let words: Vec<&str> = rest.split_whitespace().collect();
        match words.as_slice() {
            ["solved"] => e.solved = true,
            ["dof", n] => e.dof = Some(n.parse().expect("a DOF")),
            ["redundant", n] => e.redundant = n.parse().expect("a count"),
            ["conflict", rest @ ..] => {
                let n = rest
                    .iter()
                    .position(|w| *w == "names")
                    .unwrap_or(rest.len());
                let gaps = (rest[..n].iter())
                    .map(|w| {
                        let (name, gap) = w.split_once('=').expect("NAME=GAP");
                        (name.to_string(), gap.parse().expect("a gap value"))
                    })
                    .collect();
                let names = rest[(n + 1).min(rest.len())..]
                    .iter()
                    .map(|s| s.to_string())
                    .collect();
                e.conflict = Some((gaps, names));
            }
            _ => panic!("unknown expectation `{rest}`"),
        }
    }
    assert!(
        e.solved != e.conflict.is_some(),
        "either solved or a conflict: {e:?}"
    );
    e
}

/// The translated sketches, by file name, sorted.
fn sketches() -> Vec<(String, String)> {
    let dir = format!("{}/tests/solvespace", env!("CARGO_MANIFEST_DIR"));
    let mut out: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{dir}: {e}"))
        .map(|e| e.expect("an entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "gcs"))
        .map(|p| {
            let name = p.file_name().expect("a name").to_string_lossy().to_string();
            (name, std::fs::read_to_string(&p).expect("a file"))
        })
        .collect();
    out.sort();
    out
}

/// The largest absolute coordinate or dimension of a solution: the model's size.
fn size(s: &Solution) -> f64 {
    (s.points.iter().flat_map(|(_, p)| p.iter()))
        .chain(s.scalars.iter().map(|(_, x)| x))
        .fold(0.0f64, |m, x| m.max(x.abs()))
}

/// The placement a grounding holds, in DOF: what the grounded geom's place and turn take
/// (a point or a circle has no turn of its own: its place; a segment, a line, a body: all of
/// it), with the direction to a second point and the plane of a third when those are held
/// too, less the turn in the plane when a constraint is horizontal or vertical (those hold it,
/// and the grounding only the place).
fn placement(model: &gcs_lang::Model, plan: &gcs_compiler::plan::Plan) -> usize {
    use gcs_lang::model::GeomKind as K;
    let Some(g) = plan.grounded else { return 0 };
    let d3 = matches!(model.space, gcs_lang::model::Space::D3);
    let kind = model.geoms[g].kind;
    let turnless = matches!(kind, K::Point | K::Circle);
    let mut held = match (d3, turnless) {
        (false, true) => 2,
        (false, false) => 3,
        (true, true) if kind == K::Point => 3,
        (true, true) => 5,
        (true, false) if matches!(kind, K::Segment | K::Line) => 5,
        (true, false) => 6,
    };
    if plan.grounded_direction.is_some() {
        held += if d3 { 2 } else { 1 };
    }
    if plan.grounded_plane.is_some() {
        held += 1;
    }
    let aligned = (model.constraints.iter())
        .any(|(_, c)| c.text.starts_with("horizontal(") || c.text.starts_with("vertical("));
    if !d3 && aligned && held == 3 {
        held -= 1;
    }
    held
}

/// Every way `name` (text `text`) departs from what its header expects, as words; a panic is
/// one of them.
fn check(name: &str, text: &str) -> Vec<String> {
    let e = expect_of(text);
    match catch_unwind(AssertUnwindSafe(|| check_inner(name, text, &e))) {
        Ok(v) => v,
        Err(p) => {
            let msg = (p.downcast_ref::<String>().cloned())
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            vec![format!("panics: {msg}")]
        }
    }
}

fn check_inner(name: &str, text: &str, e: &Expect) -> Vec<String> {
    let mut out = Vec::new();
    let c = match gcs_compiler::compile(name, text.as_bytes()) {
        Ok(c) => c,
        Err(err) => return vec![format!("does not compile: {err:?}")],
    };
    let (model, a) = (&c.model, &c.analysis);
    let errors: Vec<&gcs_lang::Diagnostic> =
        c.diagnostics.iter().filter(|d| d.is_error()).collect();
    if let Some((gaps, named)) = &e.conflict {
        // Refused: the run at the default params on the sketch's branches stops or fails a
        // check, on a constraint of the conflict, by the gap.
        let plan = &a.plan;
        let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
        let audit = gcs_compiler::interp::audit(
            model,
            plan,
            &model.default_params(),
            &plan.sketch_defaults(),
            &gcs_compiler::interp::Choice::Given(branches),
        );
        let first = audit.failed.first().or(audit.stopped.as_ref());
        match first {
            None => out.push("solves, where SolveSpace finds a conflict".to_string()),
            Some(f) => {
                let (label, m) = (f.error.label.to_string(), f.error.magnitude);
                match gaps.iter().find(|(n, _)| *n == label) {
                    None => out.push(format!(
                        "blames `{label}` ({:?}, {m}), not a constraint of the conflict",
                        f.error.kind
                    )),
                    // A profile that cannot close with its segments as sketched measures the
                    // length its closure would need (negative), not one constraint's gap.
                    Some(_) if f.error.kind == gcs_runtime::error::ErrorKind::CannotClose => {
                        if m >= 0.0 {
                            out.push(format!("`{label}` cannot close with a length of {m}"));
                        }
                    }
                    Some((_, gap)) if (m - gap).abs() > 1e-9 * (1.0 + gap.abs()) => out.push(
                        format!("`{label}` off by {m} ({:?}), not {gap}", f.error.kind),
                    ),
                    Some(_) => {}
                }
            }
        }
        if errors.is_empty() {
            out.push("no error reported".to_string());
        }
        // The error names the constraints asked (its labels or its notes).
        let said: String = (errors.iter())
            .flat_map(|d| {
                (d.secondary.iter())
                    .map(|l| c.source.text()[l.span.range()].to_string())
                    .chain(std::iter::once(
                        c.source.text()[d.primary.span.range()].to_string(),
                    ))
                    .chain(d.notes.iter().cloned())
            })
            .collect::<Vec<_>>()
            .join("\n");
        for n in named {
            let word = |w: &str| w.trim_matches(|ch: char| !ch.is_alphanumeric() && ch != '_') == n;
            if !said.split_whitespace().any(word) {
                out.push(format!("the error does not name `{n}`"));
            }
        }
        return out;
    }
    if !errors.is_empty() {
        let first = &errors[0];
        let why = first.notes.last().cloned().unwrap_or_default();
        return vec![format!("refused: {} ({why})", first.message)];
    }
    // Solved as `gcs solve` solves: from the sketch, on its branches.
    let all: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let params = model.default_params();
    let plan = &a.plan;
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let held = vec![false; plan.branches.len()];
    let kept = gcs_compiler::solve_near_sketch(
        model,
        plan,
        &all,
        &params,
        &branches,
        &held,
        &plan.sketch_defaults(),
        false,
    );
    let s = match kept {
        Ok(k) => k.solution,
        Err(err) => return vec![format!("does not solve: {err}")],
    };
    let tol = 1e-9 * (1.0 + size(&s));
    let residual =
        gcs_compiler::verify::max_residual(&gcs_compiler::verify::residuals(model, &s, &params));
    if residual.is_nan() || residual > tol {
        out.push(format!("residual {residual:e}"));
    }
    // SolveSpace moves nothing: the sketch is a solution.
    let sketch = Solution::of_sketch(model, &params, &all).expect("a sketch");
    let moved = (s.points.iter())
        .map(|(n, p)| {
            let q = &sketch
                .points
                .iter()
                .find(|(m, _)| m == n)
                .expect("a point")
                .1;
            p.iter()
                .zip(q)
                .map(|(a, b)| (a - b) * (a - b))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0f64, f64::max);
    if moved > tol {
        out.push(format!("moves a point by {moved:.6}"));
    }
    let mobility = a.free_defaults().len() + a.free_geoms().iter().map(|(_, d)| d).sum::<usize>();
    let placed = placement(model, plan);
    if let Some(dof) = e.dof {
        if mobility + placed != dof {
            out.push(format!(
                "dof {} (mobility {mobility}, placement {placed}), SolveSpace {dof}",
                mobility + placed
            ));
        }
    }
    // Redundant whole, or in part (a checked relation, the half of a coincidence a one-DOF
    // motion cannot reach), as `gcs check` reports them.
    let mut implied: BTreeSet<_> = a.redundant.iter().copied().collect();
    implied.extend(gcs_compiler::report::implied(model, a).partly);
    if implied.len() != e.redundant {
        out.push(format!(
            "{} redundant, SolveSpace {}",
            implied.len(),
            e.redundant
        ));
    }
    out
}

#[test]
fn every_translated_sketch_does_what_solvespace_does_but_the_known_disagreements() {
    let all = sketches();
    assert!(all.len() >= 50, "{} sketches", all.len());
    let mut found: Vec<(String, String)> = Vec::new();
    for (name, text) in &all {
        let v = check(name, text);
        println!(
            "{name}: {}",
            if v.is_empty() {
                "agrees".to_string()
            } else {
                v.join("; ")
            }
        );
        found.extend(v.into_iter().map(|w| (name.clone(), w)));
    }
    let known: Vec<(String, String)> = (KNOWN.iter())
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    let new: Vec<_> = found.iter().filter(|f| !known.contains(f)).collect();
    let fixed: Vec<_> = known.iter().filter(|k| !found.contains(k)).collect();
    assert!(
        new.is_empty() && fixed.is_empty(),
        "new disagreements: {new:#?}\nknown ones no longer found (fixed? update KNOWN and the \
         README): {fixed:#?}"
    );
}

#[test]
fn the_expectations_can_fail() {
    // A solved sketch whose DOF is misstated, and a conflict whose gap is: both are caught.
    let text = "// expect: solved\n// expect: dof 4\nspace 2d;\npoint p = (0, 0);\n";
    assert_eq!(
        check("p.gcs", text),
        ["dof 2 (mobility 0, placement 2), SolveSpace 4"]
    );
    let text = "// expect: conflict k=2\nspace 2d;\nfixed point a = (0, 0);\n\
                fixed point b = (3, 0);\nk: distance(a, b) = 4;\n";
    let v = check("k.gcs", text);
    assert_eq!(v, ["`k` off by 1 (Inconsistent), not 2"]);
}
