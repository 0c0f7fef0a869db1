//! What `gcs check` and `gcs solve` tell a user about an analysed model: its problems as
//! diagnostics (constraints without a plan, geoms left free, constraints that conflict at the
//! default params), the DOF summary, and a solution as text.
//!
//! Redundancy is reported completely: each redundant constraint with what implies it (the
//! support of its run-time check, [`Plan::support`]: the constraints whose steps placed what
//! the check reads, and the fixed geoms it reads), and, at the default params, every
//! inconsistent redundant set (every check that fails, the plan run past them by
//! [`crate::interp::audit`]) as one diagnostic with its magnitude and a label on each member.

use crate::analysis::Analysis;
use crate::interp::Failure;
use crate::plan::{nearest, support_words, Op, Plan, Residual, Support, Supporter};
use crate::solution::Solution;
use gcs_lang::model::GeomId;
use gcs_lang::{Diagnostic, Model};
use gcs_runtime::error::SolveError;
use gcs_runtime::num::Shown;
use std::collections::HashMap;
use std::fmt::Write as _;

/// The (first) cluster holding each top-level geom.
fn cluster_of(a: &Analysis) -> HashMap<GeomId, usize> {
    let mut of = HashMap::new();
    for (k, c) in a.clusters.iter().enumerate() {
        for &g in &c.geoms {
            of.entry(g).or_insert(k);
        }
    }
    of
}

/// What freedom the cluster of `g` leaves, in words.
fn freedom(a: &Analysis, of: &HashMap<GeomId, usize>, g: GeomId) -> String {
    of.get(&g)
        .map_or_else(String::new, |&k| a.clusters[k].freedom.clone())
}

/// The problems of an analysed model: constraints no fragment covers yet, geoms left free
/// (under-constrained), and, run at the default params with the sketch's branches,
/// constraints that cannot be met.
pub fn problems(model: &Model, a: &Analysis) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    let free = a.free_geoms();
    let nominal = crate::nominal::count(model);
    // A motion the constraints leave free, parameterized by a default: the model solves
    // with it where the sketch has it (least motion), which a user should know.
    for d in a.free_defaults() {
        let var = &a.plan.defaults[d.0 as usize];
        let span = var.geom.map(|g| model.geoms[g].span).unwrap_or_default();
        let subject = var
            .geom
            .map_or_else(String::new, |g| format!("`{}` ", model.geoms[g].name));
        out.push(
            Diagnostic::warning(
                span,
                format!("{subject}is under-constrained: default `{}` fixes {}", var.name, var.meaning),
            )
            .with_label(format!("free: `{}`, the sketch's {} unless given", var.name, Shown(var.sketch)))
            .with_note(
                "the solve keeps it where the sketch has it (least motion); add a constraint to fix it, or give the default (`--default NAME=VALUE`, the generated solver's `Defaults`)",
            ),
        );
    }
    // More freedom than the constraints nominally remove and no default for it: the model is
    // under-constrained, and the constraints left unsolved wait on that freedom.
    let under = !free.is_empty() && (nominal.balance() > 0 || a.unsolved.is_empty());
    if under {
        let waiting: Vec<String> = a
            .unsolved
            .iter()
            .map(|u| model.constraints[u.constraint].name.clone())
            .collect();
        let of = cluster_of(a);
        for (g, dof) in &free {
            let geom = &model.geoms[*g];
            let mut d = Diagnostic::error(geom.span, format!("`{}` is under-constrained: {dof} DOF left", geom.name))
                .with_label(freedom(a, &of, *g))
                .with_note(format!(
                    "the model has {} DOF and its constraints remove {} (nominally): add constraints, or declare geoms `fixed`",
                    nominal.total_dof, nominal.total_removed
                ));
            if !waiting.is_empty() {
                d = d.with_note(format!(
                    "constraints that wait on this freedom: {}",
                    waiting.join(", ")
                ));
            }
            out.push(d);
        }
    } else {
        for u in &a.unsolved {
            let c = &model.constraints[u.constraint];
            out.push(
                Diagnostic::error(
                    c.span,
                    format!("no assembly plan satisfies `{}` yet", c.name),
                )
                .with_label(u.reason.clone())
                .with_note(
                    "this model needs a plan fragment or a loop analysis gcs does not have yet",
                ),
            );
        }
    }
    if !out.iter().any(Diagnostic::is_error) {
        let params = model.default_params();
        let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
        // An iterated plan fails here only if no assembly exists on these branches, wherever
        // the iteration starts.
        let solved = if a.plan.iterations.is_empty() {
            let choice = crate::interp::Choice::Given(branches.clone());
            crate::interp::runs(model, &a.plan, &params, &choice)
        } else {
            let all = a.plan.touched(model);
            let defaults = a.plan.sketch_defaults();
            crate::all::least_motion(model, &a.plan, &all, &params, &branches, &defaults)
                .map(|_| ())
        };
        if let Err(e) = solved {
            // The constraints may yet be met on other branches: then the model solves, and is
            // told that the sketch's cannot be kept.
            let all = a.plan.touched(model);
            let (held, defaults) = (vec![false; branches.len()], a.plan.sketch_defaults());
            let kept = crate::solve::solve_near_sketch(
                model, &a.plan, &all, &params, &branches, &held, &defaults, false,
            );
            match kept {
                Ok(kept) if kept.changed() => {
                    let at = if model.params.is_empty() {
                        ""
                    } else {
                        "with the default params"
                    };
                    out.push(sketch_branches(model, &a.plan, &kept, at))
                }
                _ => out.extend(conflicts(model, &a.plan, &params, branches, e)),
            }
        }
    }
    out
}

/// The headline of [`sketch_branches`], by which a caller knows the diagnostic.
pub const SKETCH_BRANCHES: &str = "the constraints cannot be met on the sketch's branches";

/// The headline of [`sketch_branches`] where the sketch's assembly, followed to the params
/// given, passed a tangency onto another root ([`crate::solve::Kept::passed`]): the branches
/// changed on the way, not because the sketch's could not be met.
pub const SKETCH_BRANCHES_PASSED: &str =
    "the sketch's assembly changes branches on its way to the params given";

/// The headline of [`sketch_assembly_ended`].
pub const SKETCH_ASSEMBLY_ENDED: &str = "the sketch's assembly ends on the way to the params given";

/// Whether `d` is the warning of [`sketch_branches`] or [`sketch_assembly_ended`] (`--deny
/// sketch-branch` makes either an error).
pub fn is_sketch_branches(d: &Diagnostic) -> bool {
    [
        SKETCH_BRANCHES,
        SKETCH_BRANCHES_PASSED,
        SKETCH_ASSEMBLY_ENDED,
    ]
    .iter()
    .any(|h| d.message.starts_with(h))
}

/// The warning of a solve whose assembly is not the sketch's because the sketch's, followed
/// from the model's params, ended on the way ([`crate::solution::Solution`]'s
/// `sketch_assembly_ended`), on the first constraint the iteration closes: where it ended,
/// what the solution is instead, and how far its points lie from their sketch. `None` when it
/// did not end.
pub fn sketch_assembly_ended(model: &Model, plan: &Plan, s: &Solution) -> Option<Diagnostic> {
    /// The points listed, farthest first; the rest are counted.
    const LISTED: usize = 4;
    let at = s.sketch_assembly_ended.as_ref()?;
    let values: Vec<f64> = at.iter().map(|(_, v)| *v).collect();
    let near = params_moved(model, &values).map_or(String::new(), |p| format!(" near {p}"));
    let closes = (plan.iterations.iter())
        .flat_map(|it| plan.closes(it))
        .next();
    let span = closes.map_or(gcs_lang::Span::default(), |c| model.constraints[c].span);
    let label = closes.map_or_else(String::new, |c| {
        format!(
            "`{}` closes by an iteration, whose assembly followed from the sketch comes to a fold{near}",
            model.constraints[c].name
        )
    });
    let mut d = Diagnostic::warning(span, SKETCH_ASSEMBLY_ENDED.to_string()).with_label(label);
    d = d.with_note(format!(
        "followed from the model's params as a sweep would follow it, the sketch's assembly comes{near} to where its closing errors stop closing: no step past there stays on it (a fold, where that assembly meets another and both end)"
    ));
    let drawn = Solution::of_sketch(model, &model.default_params(), &plan.touched(model));
    let by_name = drawn.as_ref().map(Solution::by_name);
    let mut far: Vec<(&str, f64)> = match &by_name {
        Some(at) => (s.points.iter())
            .filter_map(|(n, p)| {
                let q = at.point(n)?;
                let d2: f64 = p.iter().zip(q.iter()).map(|(a, b)| (a - b) * (a - b)).sum();
                Some((n.as_str(), d2.sqrt()))
            })
            .collect(),
        None => Vec::new(),
    };
    far.sort_by(|a, b| b.1.total_cmp(&a.1));
    let listed: Vec<String> = (far.iter().take(LISTED))
        .map(|(p, d)| format!("{p} {}", rounded(*d)))
        .collect();
    let more = far.len().saturating_sub(LISTED);
    let points = if listed.is_empty() {
        String::new()
    } else {
        format!(
            "; its points lie from their sketch: {}{}",
            listed.join(", "),
            if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            }
        )
    };
    d = d.with_note(format!(
        "solved on the assembly nearest the sketch in the sketch's assembly mode, which no motion from the sketch reaches without passing that fold{points}"
    ));
    Some(d.with_note(
        "give the defaults of the assembly wanted with `--default NAME=VALUE` (a sweep's last answer), or list every assembly with `--all-solutions`; `--deny sketch-branch` makes this an error",
    ))
}

/// The warning of a solve that could not keep the sketch's branches ([`Kept`] with
/// branches changed), `at` saying with what (`with the default params`; empty for a model
/// without params): a label on each changed branch's constraint with the index taken, the
/// sketch's, the meaning of the one taken and the point it places farthest from its sketch;
/// notes with the error on the branches asked, how far each point the changed branches place
/// lies from its sketch, and what to do.
///
/// [`Kept`]: crate::solve::Kept
pub fn sketch_branches(
    model: &Model,
    plan: &Plan,
    kept: &crate::solve::Kept,
    at: &str,
) -> Diagnostic {
    /// The points listed in the note, farthest first; the rest are counted.
    const LISTED: usize = 8;
    let changed = &kept.solution.branches_changed;
    let mut labels: Vec<(gcs_lang::Span, String)> = (changed.iter().zip(&kept.moved))
        .map(|(c, m)| {
            let from_sketch = (plan.branches.iter())
                .find(|b| b.name == c.name)
                .is_some_and(|b| b.from_sketch);
            let was = if from_sketch {
                format!("not the sketch's {}", c.sketch)
            } else {
                format!(
                    "not its default {} (the sketch does not reach it)",
                    c.sketch
                )
            };
            let far = m.points.first().map_or_else(String::new, |(p, d)| {
                format!("; {p} lies {} from its sketch", rounded(*d))
            });
            (
                model.constraints[m.constraint].span,
                format!("`{}` = {}, {was}: {}{far}", c.name, c.used, c.meaning),
            )
        })
        .collect();
    labels.sort_by_key(|(span, _)| span.start);
    let n = changed.len();
    let plural = if n == 1 { "" } else { "es" };
    let message = if kept.passed.is_empty() {
        format!(
            "{SKETCH_BRANCHES}{}{at}: {n} branch{plural} changed",
            if at.is_empty() { "" } else { " " },
        )
    } else {
        format!("{SKETCH_BRANCHES_PASSED}: {n} branch{plural} changed")
    };
    let mut labels = labels.into_iter();
    let (span, first) = labels.next().unwrap_or_default();
    let mut d = Diagnostic::warning(span, message).with_label(first);
    for (span, label) in labels {
        d = d.with_secondary(span, label);
    }
    if let Some(e) = &kept.not_kept {
        d = d.with_note(format!("on those branches, {e}"));
    }
    for t in &kept.passed {
        d = d.with_note(passed_tangency(model, plan, t));
    }
    // Each point once, at its distance (the same whichever branch places it).
    let mut seen = std::collections::HashSet::new();
    let mut points: Vec<(&str, f64)> = (kept.moved.iter().flat_map(|m| &m.points))
        .filter(|(p, _)| seen.insert(p.as_str()))
        .map(|(p, far)| (p.as_str(), *far))
        .collect();
    points.sort_by(|a, b| b.1.total_cmp(&a.1));
    if !points.is_empty() {
        let listed: Vec<String> = (points.iter().take(LISTED))
            .map(|(p, far)| format!("{p} {}", rounded(*far)))
            .collect();
        let more = points.len().saturating_sub(LISTED);
        d = d.with_note(format!(
            "solved on the branches nearest the sketch; the points the changed branches place lie from their sketch: {}{}",
            listed.join(", "),
            if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            }
        ));
    }
    d.with_note(
        "choose the branches with `--branch NAME=INDEX` (`gcs explain` says what each index means), or move the sketch to the assembly wanted; `--deny sketch-branch` makes this an error",
    )
}

/// What a model that does not solve at the default params is told, after `first`, the error
/// its solve stopped with: every inconsistent redundant set (each failed check, one
/// diagnostic each, with the constraints and fixed geoms that imply the one it holds), and
/// what stopped the plan, if something did, with what its step builds on. In source order.
fn conflicts(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    branches: Vec<usize>,
    first: SolveError,
) -> Vec<Diagnostic> {
    let choice = crate::interp::Choice::Given(branches);
    let audit = crate::interp::audit(model, plan, params, &plan.sketch_defaults(), &choice);
    let mut failures = audit.failed;
    match audit.stopped {
        Some(f) => failures.push(f),
        // An iterated plan whose assemblies all fail somewhere the run from the sketch does not.
        None if failures.is_empty() => failures.push(Failure {
            step: None,
            error: first,
        }),
        None => {}
    }
    let steps: Vec<usize> = failures.iter().filter_map(|f| f.step).collect();
    let supports: HashMap<usize, Support> = steps
        .iter()
        .copied()
        .zip(plan.supports(model, &steps))
        .collect();
    let mut out: Vec<Diagnostic> = (failures.iter())
        .map(|f| failure(model, plan, f, f.step.and_then(|i| supports.get(&i))))
        .collect();
    out.sort_by_key(|d| d.primary.span.start);
    out
}

/// A magnitude as a diagnostic's label says it: six significant digits (`0.3`, not
/// `0.2999999999999998`); its note has the exact value.
/// The note of a tangency the sketch's assembly passed on its way to the params solved: which
/// intersection, where (the params that differ from the model's), and which root it took.
fn passed_tangency(model: &Model, plan: &Plan, t: &crate::all::Tangency) -> String {
    let name = &plan.branches[t.branch].name;
    let at = params_moved(model, &t.params).map_or(String::new(), |p| format!(", near {p}"));
    format!(
        "the sketch's assembly, followed from the model's params to those given, comes to where the loci of `{name}` touch{at}: its root on `{name}` = {} ends there, and it goes on along `{name}` = {}",
        t.left, t.took
    )
}

/// The params whose value in `at` (indexed like the model's) is not the model's own, each
/// `name = value`: where on the way from the model's params a followed assembly was. `None`
/// when none moved.
fn params_moved(model: &Model, at: &[f64]) -> Option<String> {
    let sketch = model.default_params();
    let moved: Vec<String> = (model.params.iter().zip(at.iter().zip(&sketch)))
        .filter(|(_, (v, s))| v != s)
        .map(|((_, p), (v, _))| format!("{} = {}", p.name, rounded(*v)))
        .collect();
    (!moved.is_empty()).then(|| moved.join(", "))
}

fn rounded(x: f64) -> Shown {
    if !x.is_finite() || x == 0.0 {
        return Shown(x);
    }
    Shown(format!("{x:.5e}").parse::<f64>().unwrap_or(x))
}

/// The diagnostic of a failed check (an inconsistent redundant set) or of the error that
/// stopped the plan: on the constraint it names, with its size; then, with `support` (that of
/// its step, when known), the constraints and fixed geoms its step builds on as secondary
/// labels and in a note.
fn failure(model: &Model, plan: &Plan, f: &Failure, support: Option<&Support>) -> Diagnostic {
    use gcs_runtime::error::ErrorKind;
    let e = &f.error;
    // The constraint its step names (a check's), else the one the error is labelled with.
    let named = (f.step.and_then(|i| plan.steps.get(i)))
        .and_then(|s| s.op.constraint())
        .filter(|&k| model.constraints[k].name == e.label)
        .map(|k| (k, &model.constraints[k]));
    let found = named.or_else(|| model.constraints.iter().find(|(_, c)| c.name == e.label));
    let Some((id, c)) = found else {
        return Diagnostic::error(gcs_lang::Span::default(), e.to_string());
    };
    let m = rounded(e.magnitude);
    let check = f
        .step
        .and_then(|i| plan.steps.get(i))
        .is_some_and(|s| matches!(s.op, Op::Check { .. }));
    // An angle's residual is in radians; its degrees say it better.
    let angle = f.step.and_then(|i| plan.steps.get(i)).is_some_and(|s| {
        matches!(
            s.op,
            Op::Check {
                residual: Residual::Angle { .. },
                ..
            }
        )
    });
    let m_words = if angle {
        format!("{m} rad ({} deg)", rounded(e.magnitude.to_degrees()))
    } else {
        m.to_string()
    };
    let what = match e.kind {
        ErrorKind::Inconsistent => format!("conflicting constraint: it is off by {m_words}"),
        ErrorKind::NoIntersection => format!("no assembly: the loci miss by {m}"),
        ErrorKind::InvalidValue => format!("an invalid value: {}", Shown(e.magnitude)),
        ErrorKind::NoConvergence => {
            format!("the iteration did not converge: it stays {m} from closing it")
        }
        ErrorKind::NoAssembly => format!(
            "no assembly: over the whole turn of the iterated angle it stays at least {m} from closing"
        ),
        ErrorKind::NoAssemblyNear => format!(
            "no assembly near where the iteration starts: it stays at least {m} from closing there"
        ),
        ErrorKind::NoSuchBranch => "no root on the branch chosen".to_string(),
        ErrorKind::OtherMode => format!(
            "no assembly in the sketch's mode: the {m} closure(s) found here are in the other, across a fold"
        ),
        ErrorKind::CannotClose => {
            format!("the profile cannot close: it would give a segment a length of {m}")
        }
        _ => "a degenerate configuration".to_string(),
    };
    let message = if check {
        format!("`{}` conflicts with the constraints that imply it", c.name)
    } else {
        format!("`{}` cannot be met with the default params", c.name)
    };
    let mut d = Diagnostic::error(c.span, message).with_label(what);
    // The segment a profile that cannot close would reverse.
    if let Some(Op::SetDim { geom, .. }) = (f.step.and_then(|i| plan.steps.get(i))).map(|s| &s.op) {
        if e.kind == ErrorKind::CannotClose {
            d = d.with_note(format!(
                "closing the profile gives `{}` a length of {m}: it would run against its sketch's direction",
                model.geoms[*geom].name
            ));
        }
    }
    let support =
        support.filter(|_| !matches!(e.kind, ErrorKind::InvalidValue | ErrorKind::InvalidInput));
    if let Some(support) = support {
        let secondary = if check {
            format!("part of what implies `{}`", c.name)
        } else {
            format!("part of what `{}` builds on", c.name)
        };
        // The members nearest it; the note counts the others.
        let (shown, _) = nearest(model, support, c.span);
        for (span, who) in shown {
            // A constraint's own statement is its primary label already.
            if matches!(who, Supporter::Constraint(x) if x == id) {
                continue;
            }
            let label = match who {
                Supporter::Fixed(_) => format!("fixed: {secondary}"),
                Supporter::Constraint(_) => secondary.clone(),
            };
            d = d.with_secondary(span, label);
        }
        if let Some(words) = support_words(model, support, c.span) {
            d = d.with_note(if check {
                format!(
                    "`{}` is implied by {words}, and disagrees with them by {m_words}: change or remove one of them",
                    c.name
                )
            } else {
                let how = match e.kind {
                    ErrorKind::NoIntersection => format!("its loci miss by {m}"),
                    ErrorKind::Inconsistent => format!("it is off by {m}"),
                    ErrorKind::NoConvergence => format!("it stays {m} from closing"),
                    ErrorKind::NoAssembly | ErrorKind::NoAssemblyNear => {
                        format!("it stays at least {m} from closing")
                    }
                    ErrorKind::OtherMode => {
                        "it closes only in another assembly mode than the sketch's".to_string()
                    }
                    ErrorKind::CannotClose => {
                        format!("it would give a segment a length of {m}")
                    }
                    _ => "it cannot be met".to_string(),
                };
                format!(
                    "`{}` builds on {words}: with them {how}; change one of them",
                    c.name
                )
            });
        }
    }
    d.with_note(e.to_string())
}

/// What a model's constraints imply of each other, by count and by constraint.
#[derive(Clone, Debug, PartialEq)]
pub struct Implied {
    /// Constraints implied in part: a relation a run-time check measures while another is
    /// constructed, or (where the count shows redundancy the checks do not account for) the
    /// half of a coincidence a one-DOF motion cannot reach, measured as its gap (an `Onto`).
    /// [`Analysis::redundant`] lists the constraints implied whole.
    pub partly: Vec<gcs_lang::model::ConstraintId>,
    /// Equations stated beyond the DOF they remove: the mobility less the nominal DOF (0 when
    /// a geom is left free, whose count says nothing).
    pub excess: i64,
    /// The mobility: the placement a grounding holds plus the free defaults.
    pub mobility: usize,
}

/// [`Implied`] of an analysed model.
pub fn implied(model: &Model, a: &Analysis) -> Implied {
    let nominal = crate::nominal::count(model);
    let mut partly: Vec<gcs_lang::model::ConstraintId> = Vec::new();
    // Constraints implied in part: a relation checked, another constructed (a revolute joint
    // of a planar mechanism modelled in space: its parallel axes). A guard is no redundancy.
    for s in &a.plan.steps {
        if let Op::Check {
            constraint,
            guard: false,
            ..
        } = s.op
        {
            if !a.redundant.contains(&constraint) && !partly.contains(&constraint) {
                partly.push(constraint);
            }
        }
    }
    // The placement a grounding holds is mobility too (what a sketcher counts as free), said
    // apart from the motions the defaults hold.
    let mobility = a.plan.grounded_dof + a.free_defaults().len();
    // A point that a one-DOF motion must reach (an `Onto`) meets a two-equation constraint
    // with one freedom, and measures the other as its gap: where the count shows redundancy
    // the checks do not account for, those are where it lies. (Elsewhere an `Onto` measures a
    // tangency's double root, no redundant equation.)
    let excess = if a.free_geoms().is_empty() {
        mobility as i64 - nominal.balance()
    } else {
        0
    };
    if excess > 0 {
        for s in &a.plan.steps {
            if let Op::Onto { constraint, .. } = s.op {
                if !a.redundant.contains(&constraint) && !partly.contains(&constraint) {
                    partly.push(constraint);
                }
            }
        }
    }
    Implied {
        partly,
        excess,
        mobility,
    }
}

/// The summary `gcs check` prints after a successful analysis.
pub fn check_report(model: &Model, a: &Analysis) -> String {
    let nominal = crate::nominal::count(model);
    let mut out = String::new();
    let plural = |k: usize, w: &str| format!("{k} {w}{}", if k == 1 { "" } else { "s" });
    let _ = writeln!(
        out,
        "{}: space {}, {}, {}, {}",
        model.source.name(),
        model.space,
        plural(model.params.len(), "param"),
        plural(nominal.geoms.len(), "geom"),
        plural(nominal.constraints.len(), "constraint"),
    );
    let of = cluster_of(a);
    let left = |g: GeomId| -> usize { of.get(&g).map_or(0, |&k| a.clusters[k].dof) };
    let name_w = crate::nominal::column_width(&nominal.geoms, |g| &g.name);
    let kind_w = crate::nominal::column_width(&nominal.geoms, |g| &g.kind);
    let _ = writeln!(out, "\ngeoms{:>w$}  left", "DOF", w = name_w + kind_w + 4);
    for ((id, _), row) in model.top_level().zip(&nominal.geoms) {
        let _ = writeln!(
            out,
            "  {:name_w$}  {:kind_w$}  {:>3}  {:>4}",
            row.name,
            row.kind,
            row.dof,
            left(id)
        );
    }
    out.push_str(&crate::nominal::constraints_table(&nominal));
    if let Some(g) = a.plan.grounded {
        let _ = writeln!(
            out,
                        "grounded: {} (nothing is fixed: it is held at its sketch placement, and the rest is solved relative to it)",
            model.geoms[g].name
        );
    }
    if let Some((x, y)) = a.plan.grounded_direction {
        let _ = writeln!(
            out,
            "  and the direction from {} to {} is held as sketched (a point has no orientation of its own)",
            model.geoms[x].name, model.geoms[y].name
        );
        if let Some(z) = a.plan.grounded_plane {
            let _ = writeln!(
                out,
                "  and the plane through {}, {} and {} as sketched",
                model.geoms[x].name, model.geoms[y].name, model.geoms[z].name
            );
        }
    }
    let free = a.free_geoms();
    let free_defaults = a.free_defaults();
    let Implied {
        partly,
        excess,
        mobility,
    } = implied(model, a);
    let placement = a.plan.grounded_dof;
    let redundancy = if excess > 0 {
        format!(
            ", with redundant constraints ({excess} redundant equation{})",
            if excess == 1 { "" } else { "s" }
        )
    } else if !a.redundant.is_empty() || !partly.is_empty() {
        ", with redundant constraints".to_string()
    } else {
        String::new()
    };
    let status = if !free.is_empty() {
        "under-constrained".to_string()
    } else if !free_defaults.is_empty() && placement > 0 {
        format!(
            "under-constrained{redundancy}: mobility {mobility}: {placement} of its placement, held where the sketch has it (nothing is fixed), and {} held by {} at {} sketch value",
            free_defaults.len(),
            if free_defaults.len() == 1 { "a default" } else { "defaults" },
            if free_defaults.len() == 1 { "its" } else { "their" },
        )
    } else if !free_defaults.is_empty() {
        format!(
            "under-constrained{redundancy}: mobility {mobility}, each free motion held by a default at its sketch value"
        )
    } else if placement > 0 {
        format!(
            "well-constrained{redundancy} up to its placement: {placement} DOF held where the sketch has it (nothing is fixed)"
        )
    } else {
        format!("well-constrained{redundancy}")
    };
    let _ = writeln!(out, "analysis: {status}");
    for d in &free_defaults {
        let var = &a.plan.defaults[d.0 as usize];
        let _ = writeln!(
            out,
            "  default {} (sketch {}): {}",
            var.name,
            Shown(var.sketch),
            var.meaning
        );
    }
    for it in &a.plan.iterations {
        let closes: Vec<&str> = (a.plan.closes(it).into_iter())
            .map(|c| model.constraints[c].name.as_str())
            .collect();
        let _ = writeln!(
            out,
            "  no closed form: iterates on {} until {} close{}",
            a.plan.varied(it).join(", "),
            closes.join(", "),
            if closes.len() == 1 { "s" } else { "" }
        );
    }
    // Each redundant constraint's check: the step that checks its last relation.
    let check_of: HashMap<gcs_lang::model::ConstraintId, usize> = (a.plan.steps.iter())
        .enumerate()
        .filter_map(|(i, s)| match s.op {
            Op::Check { constraint, .. } if s.satisfies.contains(&constraint) => {
                Some((constraint, i))
            }
            _ => None,
        })
        .collect();
    let checks: Vec<usize> = (a.redundant.iter())
        .filter_map(|c| check_of.get(c).copied())
        .collect();
    let supports: HashMap<usize, Support> = checks
        .iter()
        .copied()
        .zip(a.plan.supports(model, &checks))
        .collect();
    for c in &a.redundant {
        let con = &model.constraints[*c];
        let by = (check_of.get(c))
            .and_then(|i| supports.get(i))
            .and_then(|s| support_words(model, s, con.span))
            .unwrap_or_else(|| "the others".to_string());
        let _ = writeln!(
            out,
            "  redundant: {} ({}, line {}) is implied by {by}; it is kept as a run-time check",
            con.name,
            con.text,
            model.line(con.span)
        );
    }
    // The step that measures each part implied: its check, or the gap of its `Onto`.
    let part_steps: Vec<usize> = (partly.iter())
        .map(|&c| {
            (a.plan.steps.iter())
                .position(|s| match s.op {
                    Op::Check {
                        constraint,
                        guard: false,
                        ..
                    }
                    | Op::Onto { constraint, .. } => constraint == c,
                    _ => false,
                })
                .unwrap_or(usize::MAX)
        })
        .collect();
    let found: Vec<usize> = part_steps
        .iter()
        .copied()
        .filter(|&i| i != usize::MAX)
        .collect();
    let part_supports: HashMap<usize, Support> = found
        .iter()
        .copied()
        .zip(a.plan.supports(model, &found))
        .collect();
    for (c, i) in partly.iter().zip(&part_steps) {
        let con = &model.constraints[*c];
        let by = (part_supports.get(i))
            .and_then(|s| support_words(model, s, con.span))
            .unwrap_or_else(|| "the others".to_string());
        let _ = writeln!(
            out,
            "  implied in part: {} ({}, line {}) is partly implied by {by}; that part is kept as a run-time check",
            con.name,
            con.text,
            model.line(con.span)
        );
    }
    for b in &a.plan.branches {
        if b.count > 1 {
            let _ = writeln!(
                out,
                "  branch {}: {} roots, {} {}: {}{}",
                b.name,
                b.count,
                if b.from_sketch {
                    "sketch takes"
                } else {
                    "the sketch does not reach it, default"
                },
                b.default,
                b.meanings.get(b.default).cloned().unwrap_or_default(),
                if b.symmetric {
                    " (the other root is the same assembly turned as a whole)"
                } else {
                    ""
                }
            );
        }
    }
    out
}

/// `x` with 12 decimals, and no sign on a value that rounds to zero (`-1e-17` is `0.000000000000`,
/// not `-0.000000000000`).
fn fixed12(x: f64) -> String {
    let text = format!("{x:.12}");
    match text.strip_prefix('-') {
        Some(rest) if rest.bytes().all(|b| b == b'0' || b == b'.') => rest.to_string(),
        _ => text,
    }
}

/// A solution as text: one line a value.
pub fn solution_text(s: &Solution) -> String {
    let mut out = String::new();
    let f = |v: &[f64]| v.iter().map(|&x| fixed12(x)).collect::<Vec<_>>().join(", ");
    for (n, v) in &s.points {
        let _ = writeln!(out, "point  {n} = ({})", f(v));
    }
    for (n, v) in &s.vectors {
        let _ = writeln!(out, "vector {n} = ({})", f(v));
    }
    for (n, v) in &s.scalars {
        let _ = writeln!(out, "scalar {n} = {}", fixed12(*v));
    }
    for (n, b) in &s.branches {
        let _ = writeln!(out, "branch {n} = {b}");
    }
    for (n, d) in &s.defaults {
        let _ = writeln!(out, "default {n} = {}", fixed12(*d));
    }
    if s.iterations > 0 {
        let _ = writeln!(out, "iterations {}", s.iterations);
    }
    if let Some(g) = &s.grounded {
        let _ = writeln!(out, "grounded {g}");
    }
    let _ = writeln!(out, "max residual {:.3e}", s.max_residual);
    out
}
