//! Every real assembly of a model at given params (`gcs solve --all-solutions`).
//!
//! A plan's assemblies differ by its branch variables and, where it iterates, by the roots of
//! its error functions. Every combination of branch indices is tried (up to
//! [`MAX_COMBINATIONS`]). For each:
//! - a plan without outer iterations has at most one assembly: the plan run;
//! - a plan with one outer iteration over one default has one assembly per root of the
//!   error function of that default. An angle's error function is periodic, and every root on
//!   the turn is found by the runtime's `iterate::all_roots` on a grid of [`ANGLE_SAMPLES`]
//!   samples, refined by bracketing, with double (tangent) roots found as minima of `|error|`
//!   and roots where the assembly stops existing found at that edge. Its module documentation
//!   says exactly which roots a grid can miss: two roots closer than a grid step with
//!   `|error|` above the tolerance between them. Each root is then assembled with the
//!   iteration started on it, and verified like any solution;
//! - a plan whose iteration varies a length, or several defaults, or that has several
//!   iterations, is started from a grid of its defaults ([`grid`] values of each) and each
//!   converged assembly kept: such a list is not known to be complete, and says so.
//!
//! Assemblies are listed once: one reached from two combinations (a branch the assembly never
//! reaches) or two roots is kept the first time.

use crate::interp::{self, Choice};
use crate::plan::{grid, Plan, MAX_COMBINATIONS};
use crate::solution::{BranchChange, Solution};
use gcs_lang::model::GeomId;
use gcs_lang::Model;
use std::collections::BTreeSet;

/// Samples of an angle's turn (half a degree apart): the runtime's, which generated
/// `solve_all` uses too.
pub use gcs_runtime::outer::ANGLE_SAMPLES;

/// Every real assembly found, and whether the list is known to be complete.
#[derive(Clone, Debug, Default)]
pub struct AllSolutions {
    /// The assemblies, each once.
    pub solutions: Vec<Solution>,
    /// Whether every real assembly is listed (see the module documentation).
    pub complete: bool,
}

impl AllSolutions {
    /// `{"complete": C, "solutions": [...]}`: whether the list is known to hold every real
    /// assembly, and each assembly as a plain solve prints it.
    pub fn to_json(&self) -> String {
        let objects: Vec<String> = (self.solutions.iter())
            .map(|s| {
                (s.to_json().lines())
                    .map(|l| format!("    {l}"))
                    .collect::<Vec<_>>()
                    .join("\n")
            })
            .collect();
        if objects.is_empty() {
            format!("{{\"complete\": {}, \"solutions\": []}}", self.complete)
        } else {
            format!(
                "{{\"complete\": {}, \"solutions\": [\n{}\n]}}",
                self.complete,
                objects.join(",\n")
            )
        }
    }
}

/// Every real assembly of `plan` (pruned to `scope`) at `params`; `defaults` gives the values
/// of the defaults no iteration varies (the free motions), which every assembly shares.
pub fn solve_all(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    defaults: &[f64],
) -> AllSolutions {
    // A symmetric branch stays the sketch's: its other roots are the same assemblies turned.
    let held: Vec<Option<usize>> = (plan.branches.iter())
        .map(|b| b.symmetric.then_some(b.default))
        .collect();
    solve_all_of(model, plan, scope, params, defaults, &held)
}

/// The assembly an iterated plan returns when no defaults are given (DESIGN, "Which assembly
/// an iterated plan returns"): the sketch's assembly, followed from the model's params to
/// `params` ([`followed_from_sketch`]), so that a cold solve lands where a sweep from the
/// sketch would. Where that assembly ends on the way (a fold), among the real assemblies on
/// `branches` in the sketch's assembly mode (each iteration's root of the orientation the
/// sketch's has, [`gcs_runtime::mode`]), the one that moves the points least from the sketch
/// ([`nearest_in_mode`]). With none in that mode, the solve from the sketch's defaults, which
/// keeps the mode or says it has no assembly here. A plan without iterations has one assembly
/// on given branches: the plan run.
pub fn least_motion(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
) -> Result<Solution, gcs_runtime::error::SolveError> {
    let held = vec![true; branches.len()];
    sketch_assembly(model, plan, scope, params, branches, defaults, &held).map(|f| f.solution)
}

/// The sketch's assembly at the params asked, as [`sketch_assembly`] finds it.
#[derive(Clone, Debug, PartialEq)]
pub struct Followed {
    /// The solution. Where the assembly ended on the way, the assembly nearest the sketch in
    /// the sketch's mode, which its `sketch_assembly_ended` says.
    pub solution: Solution,
    /// The tangencies the assembly passed on the way, each onto another root of a branch.
    pub passed: Vec<Tangency>,
}

/// [`least_motion`], where the sketch's assembly followed to `params` may go on along another
/// root of an intersection whose branch is not `held` (by the plan's branch order): where that
/// intersection's loci touch on the way (inside an iterated region, a sweep carries the
/// assembly through the tangency onto the other root). The solution lists the branches so
/// changed (`branches_changed`); the tangencies passed say where each changed. Where the
/// assembly ends on the way (a fold), the solution says where (`sketch_assembly_ended`): it
/// is then another assembly, which no motion from the sketch reaches without passing the fold.
pub fn sketch_assembly(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
    held: &[bool],
) -> Result<Followed, gcs_runtime::error::SolveError> {
    let alone = |solution| Followed {
        solution,
        passed: Vec::new(),
    };
    if plan.iterations.is_empty() {
        return crate::solve_plan_with(model, plan, scope, params, branches, defaults).map(alone);
    }
    let ended = match followed_from_sketch(model, plan, scope, params, branches, defaults, held) {
        Ok((solution, passed)) => return Ok(Followed { solution, passed }),
        Err(ended) => ended,
    };
    let mut s = nearest_in_mode(model, plan, scope, params, branches, defaults)?;
    s.sketch_assembly_ended = ended.map(|at| {
        (model.params.iter().zip(at))
            .map(|((_, p), v)| (p.name.clone(), v))
            .collect()
    });
    Ok(alone(s))
}

/// Where the sketch's assembly, followed from the model's params ([`sketch_assembly`]), passed
/// through a tangency of an intersection inside an iterated region and went on along its
/// other root: the branch (by the plan's order), the root it left and the one it took, and the
/// params where it did (the first point past the tangency that the following reached).
#[derive(Clone, Debug, PartialEq)]
pub struct Tangency {
    pub branch: usize,
    pub left: usize,
    pub took: usize,
    pub params: Vec<f64>,
}

/// The steps of [`followed_from_sketch`]: the first and longest fraction of the way, and the
/// shortest, below which the assembly is taken to end (a fold, or a step of the plan that
/// cannot be done partway).
const FIRST_STEP: f64 = 1.0 / 8.0;
const LONGEST_STEP: f64 = 1.0 / 4.0;
const SHORTEST_STEP: f64 = 1.0 / 4096.0;

/// The sketch's assembly at the model's params (the one nearest the sketch,
/// [`nearest_in_mode`]) followed along the straight path in param space to `params`: each
/// step solved from the last one's defaults, as a sweep does, halved where it fails and
/// lengthened where it solves. Where no step down to [`SHORTEST_STEP`] solves, the step is
/// tried with each branch not `held` on another root: the assembly may go on there through a
/// tangency of that intersection (each such [`Tangency`] is returned beside the solution).
/// Where the assembly ends on the way, the params of the last point it reached; `Err(None)`
/// where it is not found at the model's params.
fn followed_from_sketch(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    asked: &[usize],
    defaults: &[f64],
    held: &[bool],
) -> Result<(Solution, Vec<Tangency>), Option<Vec<f64>>> {
    let start = model.default_params();
    // Found once by the pipeline, on the sketch's branches: else searched for here.
    let stored = stored_assembly(plan, asked, defaults)
        .and_then(|d| crate::solve_plan_with(model, plan, scope, &start, asked, &d).ok());
    let at_sketch = match stored {
        Some(s) => s,
        None => nearest_in_mode(model, plan, scope, &start, asked, defaults).map_err(|_| None)?,
    };
    if start.as_slice() == params {
        return Ok((at_sketch, Vec::new()));
    }
    let mut branches = asked.to_vec();
    let mut passed: Vec<Tangency> = Vec::new();
    let along = |t: f64| -> Vec<f64> {
        (start.iter().zip(params))
            .map(|(a, b)| if t >= 1.0 { *b } else { a + t * (b - a) })
            .collect()
    };
    // How far a step moved the defaults, each in its scale (a radian, the model's size).
    let size = 1.0 + (start.iter().chain(params)).fold(0.0f64, |m, x| m.max(x.abs()));
    let moved = |a: &[f64], b: &[f64]| {
        (plan.defaults.iter().zip(a.iter().zip(b)))
            .map(|(d, (x, y))| {
                if d.is_angle() {
                    gcs_runtime::num::wrap_angle(x - y).abs()
                } else {
                    (x - y).abs() / size
                }
            })
            .fold(0.0f64, f64::max)
    };
    let mut last: Vec<f64> = at_sketch.defaults.iter().map(|(_, v)| *v).collect();
    let (mut t, mut step) = (0.0f64, FIRST_STEP);
    // One step from `last` on branches `b`: the solution and its defaults, unless it fails or
    // moves the defaults far: then it has jumped to a neighbouring assembly, the one followed
    // having ended or turned too fast for the step.
    let try_step = |b: &[usize], next: f64, last: &[f64]| {
        let solved = crate::solve_plan_with(model, plan, scope, &along(next), b, last);
        match solved {
            Ok(s) => {
                let at: Vec<f64> = s.defaults.iter().map(|(_, v)| *v).collect();
                if moved(&at, last) > LONGEST_MOVE {
                    Err(None)
                } else {
                    Ok((s, at))
                }
            }
            Err(e) => Err(Some(e)),
        }
    };
    loop {
        let mut next = (t + step).min(1.0);
        // Each branch not held on each of its other roots, from the last answer or beside it
        // (on the other root's side of a tangency its error is steep, a square root's, and
        // Newton's method converges only from near enough): the first that goes on.
        let flip = |branches: &[usize], at: f64| {
            (0..branches.len())
                .filter(|&b| !held.get(b).copied().unwrap_or(true))
                .flat_map(|b| (0..plan.branches[b].count).map(move |i| (b, i)))
                .filter(|&(b, i)| branches[b] != i)
                .find_map(|(b, i)| {
                    let mut other = branches.to_vec();
                    other[b] = i;
                    let beside = || {
                        nearby(plan, &last).into_iter().find_map(|start| {
                            let (s, found) = try_step(&other, at, &start).ok()?;
                            (moved(&found, &last) <= LONGEST_MOVE).then_some((s, found))
                        })
                    };
                    (try_step(&other, at, &last).ok())
                        .or_else(beside)
                        .map(|k| (other, k))
                })
        };
        let (mut s, at) = match try_step(&branches, next, &last) {
            Ok(taken) => taken,
            Err(_) if step > SHORTEST_STEP => {
                step *= 0.5;
                continue;
            }
            Err(_) => {
                // As short as steps go: the assembly goes on along another root past a
                // tangency (just beyond the stall, or a little further: the stall may come
                // before the tangency, where the error is too steep to follow), or ends.
                let flipped = (0..=12).find_map(|k| {
                    let further = (t + SHORTEST_STEP * f64::from(1u32 << k)).min(1.0);
                    flip(&branches, further).map(|(b, taken)| (b, taken, further))
                });
                let Some((other, taken, further)) = flipped else {
                    return Err(Some(along(t)));
                };
                for (b, (&left, &took)) in branches.iter().zip(&other).enumerate() {
                    if left != took {
                        passed.push(Tangency {
                            branch: b,
                            left,
                            took,
                            params: along(further),
                        });
                    }
                }
                branches = other;
                next = further;
                taken
            }
        };
        if next >= 1.0 {
            s.branches_changed = crate::solution::BranchChange::of(plan, asked, &branches);
            return Ok((s, passed));
        }
        last = at;
        t = next;
        step = (2.0 * step).min(LONGEST_STEP);
    }
}

/// `defaults` with each iterated one at its value in the sketch's assembly at the model's
/// params, as the pipeline stored it ([`crate::plan::DefaultVar::assembled`]), when the
/// branches asked are the sketch's and every iterated default has one.
fn stored_assembly(plan: &Plan, asked: &[usize], defaults: &[f64]) -> Option<Vec<f64>> {
    let sketch_branches = (plan.branches.iter().zip(asked)).all(|(b, &a)| b.default == a);
    if !sketch_branches || asked.len() != plan.branches.len() {
        return None;
    }
    let mut out = defaults.to_vec();
    for it in &plan.iterations {
        for d in &it.defaults {
            let d = d.0 as usize;
            *out.get_mut(d)? = plan.defaults.get(d)?.assembled?;
        }
    }
    Some(out)
}

/// Starts beside `last` (the defaults, by the plan's order): each iterated default moved by
/// 1e-6 to 1e-2 of its scale (a radian, or its own size) either way, nearest first.
fn nearby(plan: &Plan, last: &[f64]) -> Vec<Vec<f64>> {
    let mut out = Vec::new();
    for exponent in [6, 5, 4, 3, 2] {
        for it in &plan.iterations {
            for d in &it.defaults {
                let d = d.0 as usize;
                let scale = if plan.defaults[d].is_angle() {
                    1.0
                } else {
                    1.0 + last[d].abs()
                };
                for sign in [1.0, -1.0] {
                    let mut start = last.to_vec();
                    start[d] += sign * scale * 10f64.powi(-exponent);
                    out.push(start);
                }
            }
        }
    }
    out
}

/// The most a step of [`followed_from_sketch`] may move a default, in its scale, before it is
/// taken shorter: a tenth of a radian, a tenth of the model's size.
const LONGEST_MOVE: f64 = 0.1;

/// Among the real assemblies on `branches` at `params` in the sketch's assembly mode, the one
/// that moves the points least from the sketch (the smallest sum of squared displacements), so
/// that the answer does not depend on which default the analysis chose; with none, the solve
/// from the sketch's defaults.
fn nearest_in_mode(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
) -> Result<Solution, gcs_runtime::error::SolveError> {
    let from_sketch = crate::solve_plan_with(model, plan, scope, params, branches, defaults);
    let Some(sketch) = Solution::of_sketch(model, params, scope) else {
        return from_sketch;
    };
    let held: Vec<Option<usize>> = branches.iter().map(|&i| Some(i)).collect();
    let found = solve_all_of(model, plan, scope, params, defaults, &held);
    let sketch_modes: Vec<_> = plan.iterations.iter().map(|it| it.mode).collect();
    let in_mode = |s: &Solution| {
        let at: Vec<f64> = s.defaults.iter().map(|(_, v)| *v).collect();
        let modes = interp::modes_at(model, plan, params, &at, branches);
        (sketch_modes.iter().zip(&modes)).all(|(want, got)| match (want, got) {
            (Some(want), Some(got)) => want == got,
            _ => true,
        })
    };
    // The solve from the sketch keeps the sketch's mode by itself; it is a candidate too, so
    // that a search from a grid that misses it cannot make the answer jump.
    let mut candidates: Vec<Solution> = found.solutions.into_iter().filter(in_mode).collect();
    if let Ok(s) = &from_sketch {
        if !candidates.iter().any(|t| same_assembly(t, s)) {
            candidates.push(s.clone());
        }
    }
    let least = (candidates.into_iter())
        .map(|s| (motion(&sketch, &s), s))
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, s)| s);
    match least {
        Some(s) => Ok(s),
        None => from_sketch,
    }
}

/// How far `s` lies from `sketch` (both read over the same scope): the sum of the squared
/// displacements of its points, the measure of least motion.
pub fn motion(sketch: &Solution, s: &Solution) -> f64 {
    let at = sketch.by_name();
    (s.points.iter())
        .filter_map(|(n, p)| {
            let q = at.point(n)?;
            Some(p.iter().zip(q).map(|(a, b)| (a - b) * (a - b)).sum::<f64>())
        })
        .sum()
}

/// The branch combinations a search tries: each branch held at an index or varied over its
/// roots, the first varied varying fastest, counted from the index it starts at (combination
/// 0 is the one it starts from). At most [`MAX_COMBINATIONS`] are tried.
#[derive(Clone, Debug)]
pub struct Combinations {
    /// Where each branch starts, by the plan's branch order.
    start: Vec<usize>,
    /// The branches varied, in the order they vary (the first fastest), with their counts.
    varied: Vec<(usize, usize)>,
    /// How many combinations there are, if no more than [`MAX_COMBINATIONS`].
    count: Option<usize>,
}

impl Combinations {
    /// The combinations of `plan`'s branches that start at `start` and vary those of `varied`
    /// (by branch index, in the order given) that have several roots.
    pub fn new(plan: &Plan, start: &[usize], varied: &[usize]) -> Combinations {
        let varied: Vec<(usize, usize)> = (varied.iter())
            .map(|&b| (b, plan.branches[b].count))
            .filter(|&(_, c)| c > 1)
            .collect();
        let count = (varied.iter())
            .try_fold(1usize, |n, &(_, c)| n.checked_mul(c))
            .filter(|&n| n <= MAX_COMBINATIONS);
        Combinations {
            start: start.to_vec(),
            varied,
            count,
        }
    }

    /// Whether every combination is tried.
    pub fn complete(&self) -> bool {
        self.count.is_some()
    }

    /// How many are tried: every one, or the first [`MAX_COMBINATIONS`].
    pub fn len(&self) -> usize {
        self.count.unwrap_or(MAX_COMBINATIONS)
    }

    /// Whether there is none to try: never, the one it starts from is always there.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Combination `k`, in mixed radix: each varied branch at `(start + digit) % count`.
    pub fn nth(&self, k: usize) -> Vec<usize> {
        let mut rest = k;
        let mut out = self.start.clone();
        for &(b, c) in &self.varied {
            out[b] = (out[b] + rest % c) % c;
            rest /= c;
        }
        out
    }
}

/// [`solve_all`], each branch held at its index where `held` gives one, and varied over its
/// roots (from 0) where it does not.
fn solve_all_of(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    defaults: &[f64],
    held: &[Option<usize>],
) -> AllSolutions {
    let start: Vec<usize> = held.iter().map(|h| h.unwrap_or(0)).collect();
    let free: Vec<usize> = (0..held.len()).filter(|&b| held[b].is_none()).collect();
    let combinations = Combinations::new(plan, &start, &free);
    let sketch: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let mut out = AllSolutions {
        solutions: Vec::new(),
        complete: combinations.complete(),
    };
    let (varied, one_angle) = varied_defaults(plan);
    if !exhaustive(plan) {
        out.complete = false;
    }
    // One scan serves every value of the branches its iteration does not see.
    let scanned = scanned_branches(plan);
    let mut scans: std::collections::HashMap<Vec<usize>, (Vec<Vec<f64>>, bool)> =
        std::collections::HashMap::new();
    for k in 0..combinations.len() {
        let branches = combinations.nth(k);
        let key: Vec<usize> = (branches.iter().zip(&scanned))
            .map(|(&b, &seen)| if seen || !one_angle { b } else { usize::MAX })
            .collect();
        let (starts, truncated) = scans
            .entry(key)
            .or_insert_with(|| starts(model, plan, params, defaults, &branches, &varied, one_angle))
            .clone();
        if truncated {
            out.complete = false;
        }
        for start in starts {
            let solved =
                crate::solve::solve_plan_searching(model, plan, scope, params, &branches, &start);
            if let Ok(mut s) = solved {
                if !out.solutions.iter().any(|t| same_assembly(t, &s)) {
                    s.branches_changed = BranchChange::of(plan, &sketch, &branches);
                    out.solutions.push(s);
                }
            }
        }
    }
    out
}

/// For each of `plan`'s branch variables, whether a scan of its first iteration sees it: a
/// step before the iteration's region ends takes its root. One that no such step takes
/// changes nothing the scan measures, so one scan serves all its values (here and in the
/// generated `solve_all`).
pub(crate) fn scanned_branches(plan: &Plan) -> Vec<bool> {
    let end = plan.iterations.first().map_or(0, |it| it.end);
    let mut seen = vec![false; plan.branches.len()];
    for s in plan.steps.iter().take(end) {
        if let Some(slot) = s.op.branch().and_then(|b| seen.get_mut(b.0 as usize)) {
            *slot = true;
        }
    }
    seen
}

/// The defaults `plan`'s iterations vary (by index), and whether they are one angle of one
/// iteration: a search scans its turn (otherwise it starts from a grid).
pub(crate) fn varied_defaults(plan: &Plan) -> (Vec<usize>, bool) {
    let varied: Vec<usize> = (plan.iterations.iter())
        .flat_map(|it| it.defaults.iter().map(|d| d.0 as usize))
        .collect();
    let one_angle =
        plan.iterations.len() == 1 && varied.len() == 1 && plan.defaults[varied[0]].is_angle();
    (varied, one_angle)
}

/// Whether a search over `plan`'s branches and iterations finds every real assembly: with no
/// iteration (every combination of branches is tried), or with one iteration over one angle
/// whose error changes sign across its roots ([`closes_signed`]), which a scan of the turn
/// brackets, on branches that follow their roots continuously along it ([`branches_follow`]).
/// The generated `solve_all` says the same of its list.
pub(crate) fn exhaustive(plan: &Plan) -> bool {
    let (varied, one_angle) = varied_defaults(plan);
    varied.is_empty() || (one_angle && closes_signed(plan) && branches_follow(plan))
}

/// Whether every branch taken inside an iteration names the same root as the iterated angle
/// turns: not a quartic's roots in the order of their first angle
/// (`SpatialOp::ThreeCircles`, `SpatialOp::PlanarChainEnds`), which two roots swap where
/// their first angles cross (or one wraps past a half turn). The scan of one branch then
/// jumps from one root's error to the other's, and a root near the jump can be missed.
fn branches_follow(plan: &Plan) -> bool {
    use crate::plan::{Op, SpatialOp};
    (plan.iterations.iter()).all(|it| {
        (plan.steps[it.start..it.end].iter()).all(|s| {
            !matches!(
                s.op,
                Op::Spatial(SpatialOp::ThreeCircles { .. } | SpatialOp::PlanarChainEnds { .. })
            )
        })
    })
}

/// Whether every error an iteration closes changes sign across its roots, so that a scan
/// brackets each: not a point's distance from a line or circle of space, nor a residual's
/// magnitude, which only touch zero there (their roots are found as minima, with no promise
/// that none is missed between two samples).
fn closes_signed(plan: &Plan) -> bool {
    use crate::plan::{Op, Ty, MAGNITUDE};
    let def =
        |r: crate::plan::Reg| (plan.steps.iter()).find(|s| s.out.is_some_and(|(o, _)| o == r));
    let ty = |r| def(r).and_then(|s| s.out).map(|(_, t)| t);
    (plan.steps.iter()).all(|s| {
        let Op::Close { residual, .. } = s.op else {
            return true;
        };
        match def(residual).map(|d| &d.op) {
            Some(Op::Implicit { locus, .. }) => {
                plan.space != gcs_lang::model::Space::D3
                    || !matches!(ty(*locus), Some(Ty::Line | Ty::Circle))
            }
            Some(Op::Error { component, .. }) => *component != MAGNITUDE,
            _ => true,
        }
    })
}

/// Where to start the solves of one branch combination: the defaults given when nothing
/// iterates; each root of the error function when one angle does; a grid otherwise. And
/// whether the scan found more roots than it keeps.
fn starts(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    branches: &[usize],
    varied: &[usize],
    one_angle: bool,
) -> (Vec<Vec<f64>>, bool) {
    if varied.is_empty() {
        return (vec![defaults.to_vec()], false);
    }
    let choice = Choice::Given(branches.to_vec());
    if one_angle {
        let d = varied[0];
        let scan = interp::scan(model, plan, params, defaults, &choice);
        let starts = (scan.roots().iter())
            .map(|&x| {
                let mut start = defaults.to_vec();
                start[d] = x;
                start
            })
            .collect();
        return (starts, scan.truncated());
    }
    // A grid over each varied default: a turn for an angle, the sketch's value give or take
    // the model's size for a length.
    let size = 1.0
        + model
            .default_params()
            .iter()
            .chain(plan.defaults.iter().map(|d| &d.sketch))
            .fold(0.0f64, |m, x| m.max(x.abs()));
    let each = grid(varied.len());
    let mut cells = vec![defaults.to_vec()];
    for &d in varied {
        let var = &plan.defaults[d];
        let values: Vec<f64> = (0..each)
            .map(|i| {
                let t = i as f64 / each as f64;
                if var.is_angle() {
                    -std::f64::consts::PI + 2.0 * std::f64::consts::PI * t
                } else {
                    defaults[d] + size * (2.0 * t - 1.0)
                }
            })
            .collect();
        cells = (cells.iter())
            .flat_map(|g| {
                values.iter().map(move |&v| {
                    let mut next = g.clone();
                    next[d] = v;
                    next
                })
            })
            .take(MAX_COMBINATIONS)
            .collect();
    }
    (cells, false)
}

/// Whether two solutions are one assembly: every point and vector within a relative
/// [`gcs_runtime::tol::SAME_ASSEMBLY_REL`].
fn same_assembly(a: &Solution, b: &Solution) -> bool {
    let scale = 1.0
        + (a.points.iter())
            .flat_map(|(_, v)| v.iter())
            .fold(0.0f64, |m, x| m.max(x.abs()));
    let close = |u: &[(String, Vec<f64>)], v: &[(String, Vec<f64>)], tol: f64| {
        u.len() == v.len()
            && u.iter().zip(v).all(|((n, x), (m, y))| {
                n == m && x.iter().zip(y).all(|(p, q)| (p - q).abs() <= tol)
            })
    };
    let tol = gcs_runtime::tol::SAME_ASSEMBLY_REL;
    close(&a.points, &b.points, tol * scale) && close(&a.vectors, &b.vectors, tol)
}
