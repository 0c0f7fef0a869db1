//! Solving a model by running its plan in the interpreter: the whole plan ([`solve`]) or one
//! pruned to some geoms ([`solve_plan`]), read back as a [`solution::Solution`] and measured
//! by the verifier. These solve on the branches given, or fail.
//!
//! [`solve_near_sketch`] is `gcs solve`'s: on the sketch's branches (and those the user
//! chose), or, when the constraints cannot be met on them, on the combination nearest the
//! sketch, saying which branches it changed ([`Kept`]).

use crate::solution::Solution;
use crate::{analysis, config, interp, plan, solution, verify};
use gcs_lang::model::GeomId;
use gcs_runtime::error::SolveError;
use std::collections::BTreeSet;

/// Solves a model with its whole plan: every geom. `branches` are indices by branch order.
pub fn solve(
    model: &gcs_lang::Model,
    analysis: &analysis::Analysis,
    params: &[f64],
    branches: &[usize],
) -> Result<solution::Solution, SolveError> {
    // An incomplete plan never produces an answer: a constraint it cannot satisfy, or a geom
    // it leaves free, is an error naming it.
    if let Some(u) = analysis.unsolved.first() {
        let c = &model.constraints[u.constraint];
        let dof: usize = analysis.free_geoms().iter().map(|(_, d)| d).sum();
        return Err(SolveError::new(
            c.name.clone(),
            c.text.clone(),
            gcs_runtime::error::ErrorKind::Degenerate,
            dof as f64,
        ));
    }
    if let Some((g, dof)) = analysis.free_geoms().first() {
        return Err(SolveError::new(
            model.geoms[*g].name.clone(),
            "under-constrained".to_string(),
            gcs_runtime::error::ErrorKind::Degenerate,
            *dof as f64,
        ));
    }
    let all: BTreeSet<GeomId> = model.top_level().map(|(id, _)| id).collect();
    solve_plan(model, &analysis.plan, &all, params, branches)
}

/// Runs `plan` (whole or pruned to `scope`, the top-level geoms it computes) and reads the
/// solution of those geoms; its `max_residual` covers every constraint among them, measured
/// independently of the plan.
pub fn solve_plan(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
) -> Result<solution::Solution, SolveError> {
    solve_plan_with(
        model,
        plan,
        scope,
        params,
        branches,
        &plan.sketch_defaults(),
    )
}

/// [`solve_plan`] with `defaults` (indexed like the plan's): the values of the defaults that
/// parameterize free motions, and where the outer iterations start.
pub fn solve_plan_with(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
) -> Result<solution::Solution, SolveError> {
    solve_plan_run(model, plan, scope, params, branches, defaults, false)
}

/// [`solve_plan_with`] as one start of many, as `solve_all` runs them
/// ([`interp::run_searching_in`]): a failure not told apart, no mode held.
pub fn solve_plan_searching(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
) -> Result<solution::Solution, SolveError> {
    solve_plan_run(model, plan, scope, params, branches, defaults, true)
}

/// [`solve_plan_with`], `searching` as [`solve_plan_searching`].
fn solve_plan_run(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
    searching: bool,
) -> Result<solution::Solution, SolveError> {
    let choice = interp::Choice::Given(branches.to_vec());
    let (mut s, run_defaults, iterations) = match model.space {
        gcs_lang::model::Space::D2 => {
            let run = if searching {
                interp::run_searching_in::<config::D2>(model, plan, params, defaults, &choice)?
            } else {
                interp::run_in::<config::D2>(model, plan, params, defaults, &choice)?
            };
            let s = solution::Solution::read(model, &run.config, scope);
            (s, run.defaults, run.iterations)
        }
        gcs_lang::model::Space::D3 => {
            let run = if searching {
                interp::run_searching_in::<config::D3>(model, plan, params, defaults, &choice)?
            } else {
                interp::run_in::<config::D3>(model, plan, params, defaults, &choice)?
            };
            let s = solution::Solution::read_space(model, &run.config, scope);
            (s, run.defaults, run.iterations)
        }
    };
    s.branches = plan
        .branches
        .iter()
        .zip(branches)
        .map(|(b, i)| (b.name.clone(), *i))
        .collect();
    s.defaults = (plan.defaults.iter())
        .zip(&run_defaults)
        .map(|(d, v)| (d.name.clone(), *v))
        .collect();
    s.iterations = iterations;
    s.grounded = plan.grounded.map(|g| model.geoms[g].name.clone());
    let residuals = verify::residuals_in(model, &s, params, scope);
    s.max_residual = verify::max_residual(&residuals);
    off_by(model, &s, &residuals)?;
    Ok(s)
}

/// Nothing off is `Ok`: the error of the constraint the verifier finds furthest from met, when
/// that is past a run-time check's tolerance ([`gcs_runtime::tol::CHECK_REL`] times one plus
/// the solution's size). A plan meets every constraint by construction or checks it, so this
/// fires only where a plan is wrong (an iteration that closed on an error that does not
/// measure what it displaced); the verifier shares nothing with the plan, so it sees that.
fn off_by(
    model: &gcs_lang::Model,
    s: &solution::Solution,
    residuals: &[verify::Residual],
) -> Result<(), SolveError> {
    let size = (s.points.iter().flat_map(|(_, p)| p.iter()))
        .chain(s.scalars.iter().map(|(_, x)| x))
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let tol = gcs_runtime::tol::CHECK_REL * (1.0 + size);
    if s.max_residual.is_finite() && s.max_residual <= tol {
        return Ok(());
    }
    let worst = (residuals.iter())
        .map(|r| {
            (
                if r.value.is_nan() {
                    f64::INFINITY
                } else {
                    r.value
                },
                r,
            )
        })
        .max_by(|a, b| a.0.total_cmp(&b.0));
    match worst {
        Some((off, r)) if off > tol => {
            let c = &model.constraints[r.constraint];
            Err(SolveError::new(
                c.name.clone(),
                c.text.clone(),
                gcs_runtime::error::ErrorKind::Inconsistent,
                off,
            ))
        }
        _ => Ok(()),
    }
}

/// A solve that kept the branches asked, or says which it had to change
/// ([`solve_near_sketch`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Kept {
    /// The solution; its `branches_changed` lists the branches changed, empty when none.
    pub solution: solution::Solution,
    /// For each branch changed (in the order of `solution.branches_changed`): its constraint,
    /// and the points it places, each with its distance from its sketch, farthest first.
    pub moved: Vec<Moved>,
    /// Why the branches asked were not kept, when a search found others: the error of the
    /// solve on them.
    pub not_kept: Option<SolveError>,
    /// Where the sketch's assembly, followed from the model's params to those solved, passed
    /// through a tangency inside an iterated region onto another root: why the branches it
    /// lists changed, when it did ([`crate::all::sketch_assembly`]).
    pub passed: Vec<crate::all::Tangency>,
}

/// What a changed branch places ([`Kept::moved`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Moved {
    /// The constraint whose intersection the branch chooses.
    pub constraint: gcs_lang::model::ConstraintId,
    /// Every point whose solved position depends on the branch, with its distance from where
    /// the sketch has it (at the params solved), farthest first.
    pub points: Vec<(String, f64)>,
}

impl Kept {
    /// Whether a branch was changed.
    pub fn changed(&self) -> bool {
        !self.solution.branches_changed.is_empty()
    }

    /// Whether the solution is not the sketch's assembly: a branch changed, or the assembly
    /// followed from the sketch ended on the way (`sketch_assembly_ended`).
    pub fn broken(&self) -> bool {
        self.changed() || self.solution.sketch_assembly_ended.is_some()
    }

    /// The point placed by a changed branch that lies farthest from its sketch, and how far.
    pub fn farthest(&self) -> Option<(&str, f64)> {
        (self.moved.iter())
            .filter_map(|m| m.points.first())
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(n, d)| (n.as_str(), *d))
    }
}

/// The most plan steps the search of [`solve_near_sketch`] runs, over every combination it
/// tries: [`crate::plan::MAX_COMBINATIONS`] solves of a plan of 256 steps, fewer of a larger
/// one, or of an iterated one solved for least motion (which scans every root: counted as
/// [`crate::all::ANGLE_SAMPLES`] runs). A failed combination whose failure is asked for the
/// branches it depends on counts twice.
pub const SEARCH_STEPS: usize = 1 << 20;

/// Whether another branch combination could avoid an error of this kind: an intersection
/// whose loci miss or that lacks the root asked, a check that fails, a configuration that is
/// degenerate or an iteration that does not close may all depend on the sides taken before.
/// So may an iteration with no assembly on those branches, near its start or at all, or none
/// in the sketch's mode: an assembly a sweep follows past the tangency of an intersection
/// inside its region goes on along that intersection's other root, which the search finds and
/// names (the branch changed). An invalid input, value, param or default does not.
fn another_branch_may_avoid(kind: gcs_runtime::error::ErrorKind) -> bool {
    use gcs_runtime::error::ErrorKind as K;
    matches!(
        kind,
        K::NoIntersection
            | K::NoSuchBranch
            | K::Inconsistent
            | K::Degenerate
            | K::NoConvergence
            | K::NoAssembly
            | K::NoAssemblyNear
            | K::OtherMode
    )
}

/// Solves `plan` over `scope` on `branches` (indexed like the plan's) as `gcs solve` does: from
/// `defaults` when `defaults_given`, else, for an iterated plan, the assembly that moves least
/// from the sketch ([`crate::all::least_motion`]).
///
/// When that fails with an error another branch combination could avoid, the branches not
/// `held` (those the caller did not choose: each at its default, the sketch's) are searched:
/// first those the failing step depends on, the one nearest the failure varying fastest, then
/// those the failures of that search depend on too. The search is bounded as
/// `--all-solutions` bounds its own, and by the plan's size: at most
/// [`crate::plan::MAX_COMBINATIONS`] solves, and at most about [`SEARCH_STEPS`] steps run in
/// all (a plan of 20,000 steps is solved on 52 combinations, those nearest the failure), so
/// that a large model that cannot be met on any branch still fails quickly. Of the combinations
/// that solve in the first round that finds one, the one nearest the sketch
/// ([`crate::all::motion`]; ties to the first tried) is returned, with the branches it changed
/// (in its `branches_changed`) and how far the points they place lie from their sketch. A
/// branch held is never changed, nor one whose roots are the same assembly turned
/// (`symmetric`). When no combination tried solves, the error on the branches asked is
/// returned unchanged.
#[allow(clippy::too_many_arguments)]
pub fn solve_near_sketch(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    held: &[bool],
    defaults: &[f64],
    defaults_given: bool,
) -> Result<Kept, SolveError> {
    let solve = |b: &[usize]| {
        if defaults_given {
            solve_plan_with(model, plan, scope, params, b, defaults)
        } else {
            crate::all::least_motion(model, plan, scope, params, b, defaults)
        }
    };
    // Cold: the sketch's assembly followed to these params, which may go on through a
    // tangency onto another root of a branch not held.
    let first = if defaults_given {
        solve(branches).map(|s| (s, Vec::new()))
    } else {
        crate::all::sketch_assembly(model, plan, scope, params, branches, defaults, held)
            .map(|f| (f.solution, f.passed))
    };
    let error = match first {
        Ok((solution, passed)) => {
            let changed: Vec<usize> = (0..plan.branches.len())
                .filter(|&b| (solution.branches.get(b)).is_some_and(|(_, i)| *i != branches[b]))
                .collect();
            let moved = if changed.is_empty() {
                Vec::new()
            } else {
                moved_points(model, plan, params, scope, &solution, &changed)
            };
            return Ok(Kept {
                solution,
                moved,
                not_kept: None,
                passed,
            });
        }
        Err(e) => e,
    };
    if !another_branch_may_avoid(error.kind) {
        return Err(error);
    }
    let free: Vec<bool> = (plan.branches.iter().zip(held))
        .map(|(b, &h)| !h && !b.symmetric && b.count > 1)
        .chain(std::iter::repeat(false))
        .take(plan.branches.len())
        .collect();
    let search = Search::new(model, plan, params, defaults, &free);
    // The assembly that moves least is found among every root of the iteration: a scan.
    let runs = if defaults_given || plan.iterations.is_empty() {
        1
    } else {
        crate::all::ANGLE_SAMPLES as usize
    };
    let cost = plan.steps.len().saturating_mul(runs);
    let sketch = Solution::of_sketch(model, params, scope);
    let Some((used, mut solution)) = search.run(branches, &solve, cost, sketch) else {
        return Err(error);
    };
    solution.branches_changed = solution::BranchChange::of(plan, branches, &used);
    let changed: Vec<usize> = (0..plan.branches.len())
        .filter(|&b| branches[b] != used[b])
        .collect();
    let moved = moved_points(model, plan, params, scope, &solution, &changed);
    Ok(Kept {
        solution,
        moved,
        not_kept: Some(error),
        passed: Vec::new(),
    })
}

/// The search of [`solve_near_sketch`]: which branches each failure depends on.
struct Search<'a> {
    model: &'a gcs_lang::Model,
    plan: &'a plan::Plan,
    params: &'a [f64],
    defaults: &'a [f64],
    /// Whether each branch may be changed.
    free: &'a [bool],
    /// The step of each branch's intersection.
    step_of: Vec<Option<usize>>,
    deps: plan::Deps<'a>,
}

impl<'a> Search<'a> {
    fn new(
        model: &'a gcs_lang::Model,
        plan: &'a plan::Plan,
        params: &'a [f64],
        defaults: &'a [f64],
        free: &'a [bool],
    ) -> Search<'a> {
        let mut step_of = vec![None; plan.branches.len()];
        for (i, s) in plan.steps.iter().enumerate() {
            if let Some(slot) = s.op.branch().and_then(|b| step_of.get_mut(b.0 as usize)) {
                *slot = Some(i);
            }
        }
        Search {
            model,
            plan,
            params,
            defaults,
            free,
            step_of,
            deps: plan.deps(model),
        }
    }

    /// The free branches the failures of a run on `branches` depend on: those of the steps in
    /// the backward slice of each failed check and of the step that stopped it; every free
    /// branch when no failure names its step (the verifier's, or one before the first step).
    fn depended_on(&self, branches: &[usize]) -> BTreeSet<usize> {
        let choice = interp::Choice::Given(branches.to_vec());
        let audit = interp::audit(self.model, self.plan, self.params, self.defaults, &choice);
        let steps: Vec<Option<usize>> = (audit.failed.iter().chain(&audit.stopped))
            .map(|f| f.step)
            .collect();
        if steps.is_empty() || steps.iter().any(Option::is_none) {
            return (0..self.free.len()).filter(|&b| self.free[b]).collect();
        }
        let mut walk = self.deps.walk();
        for i in steps.into_iter().flatten() {
            walk.take(i);
        }
        walk.run(|_, _| {});
        let slice = walk.finish();
        (slice.steps.iter())
            .filter_map(|&i| self.plan.steps[i].op.branch())
            .map(|b| b.0 as usize)
            .filter(|&b| self.free.get(b).copied().unwrap_or(false))
            .collect()
    }

    /// Searches from `branches` (which fail) for a combination that `solve`s, in rounds: the
    /// branches the failures depend on, varied nearest the failure first; when none solves,
    /// those the failures of that round depend on too. The solution nearest `sketch` of the
    /// first round that finds any, with its branches. A solve runs about `cost` steps.
    fn run(
        &self,
        branches: &[usize],
        solve: &dyn Fn(&[usize]) -> Result<Solution, SolveError>,
        cost: usize,
        sketch: Option<Solution>,
    ) -> Option<(Vec<usize>, Solution)> {
        let mut budget = crate::plan::MAX_COMBINATIONS.min(SEARCH_STEPS / cost.max(1));
        if budget == 0 {
            return None;
        }
        let mut varied = self.depended_on(branches);
        loop {
            // The branch nearest the failure (latest in the plan) varies fastest.
            let mut order: Vec<usize> = varied.iter().copied().collect();
            order.sort_by_key(|&b| std::cmp::Reverse(self.step_of[b]));
            let combinations = crate::all::Combinations::new(self.plan, branches, &order);
            let mut best: Option<(f64, Vec<usize>, Solution)> = None;
            let mut more = BTreeSet::new();
            // Combination 0 is the one asked, which failed. A round the budget cuts short is
            // the last: what its failures depend on is not asked.
            let last = combinations.len() > budget;
            for k in 1..combinations.len() {
                if budget == 0 {
                    break;
                }
                budget -= 1;
                let tried = combinations.nth(k);
                match solve(&tried) {
                    Ok(s) => {
                        let d = sketch.as_ref().map_or(0.0, |at| crate::all::motion(at, &s));
                        if best.as_ref().is_none_or(|(b, _, _)| d < *b) {
                            best = Some((d, tried, s));
                        }
                    }
                    Err(_) if best.is_none() && !last => {
                        budget = budget.saturating_sub(1);
                        more.extend(self.depended_on(&tried));
                    }
                    Err(_) => {}
                }
            }
            if let Some((_, tried, s)) = best {
                return Some((tried, s));
            }
            let before = varied.len();
            varied.extend(more);
            if varied.len() == before || budget == 0 {
                return None;
            }
        }
    }
}

/// For each of `changed` (branch indices), the points of `solution` whose position depends on
/// it, with their distance from the sketch at `params`, farthest first. A step depends on the
/// branch when it is the branch's intersection, reads a register that does, or measures a
/// geom an earlier such step moved; an iterated region with such a step converges elsewhere,
/// so every step that reads the defaults it varies depends on the branch too.
fn moved_points(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    params: &[f64],
    scope: &BTreeSet<GeomId>,
    solution: &Solution,
    changed: &[usize],
) -> Vec<Moved> {
    let sketch = Solution::of_sketch(model, params, scope);
    let at = sketch.as_ref().map(Solution::by_name);
    let top: std::collections::HashMap<&str, GeomId> = (model.geoms.iter())
        .map(|(id, g)| (g.name.as_str(), model.top_level_of(id)))
        .collect();
    // `S.start`, `C.center`, `L.point` are their geom's; a member's name is its own.
    let geom_of = |name: &str| {
        top.get(name)
            .or_else(|| name.rsplit_once('.').and_then(|(g, _)| top.get(g)))
            .copied()
    };
    changed
        .iter()
        .map(|&b| {
            let placed = placed_by(model, plan, plan::BranchId(b as u32));
            let mut points: Vec<(String, f64)> = (solution.points.iter())
                .filter(|(n, _)| geom_of(n).is_some_and(|g| placed.contains(&g)))
                .map(|(n, p)| {
                    let d = (at.as_ref().and_then(|at| at.point(n))).map_or(f64::NAN, |q| {
                        p.iter()
                            .zip(q)
                            .map(|(a, b)| (a - b) * (a - b))
                            .sum::<f64>()
                            .sqrt()
                    });
                    (n.clone(), d)
                })
                .collect();
            points.sort_by(|a, b| b.1.total_cmp(&a.1));
            Moved {
                constraint: plan.branches[b].constraint,
                points,
            }
        })
        .collect()
}

/// The top-level geoms whose solved state depends on `branch` (see [`moved_points`]).
fn placed_by(
    model: &gcs_lang::Model,
    plan: &plan::Plan,
    branch: plan::BranchId,
) -> BTreeSet<GeomId> {
    let mut defaults: BTreeSet<plan::DefaultId> = BTreeSet::new();
    loop {
        let mut regs = vec![false; plan.regs as usize];
        let mut geoms: BTreeSet<GeomId> = BTreeSet::new();
        let mut steps = vec![false; plan.steps.len()];
        for (i, s) in plan.steps.iter().enumerate() {
            let depends = s.op.branch() == Some(branch)
                || matches!(s.op, plan::Op::Default(d) if defaults.contains(&d))
                || s.op
                    .reads()
                    .iter()
                    .any(|r| regs.get(r.0 as usize) == Some(&true))
                || (s.op.measures()).is_some_and(|f| geoms.contains(&model.top_level_of(f)));
            if depends {
                steps[i] = true;
                if let Some(slot) = s.out.and_then(|(r, _)| regs.get_mut(r.0 as usize)) {
                    *slot = true;
                }
                geoms.extend(s.op.moves().iter().copied());
            }
        }
        let before = defaults.len();
        for it in &plan.iterations {
            if steps
                .get(it.start..it.end)
                .is_some_and(|r| r.contains(&true))
            {
                defaults.extend(it.defaults.iter().copied());
            }
        }
        if defaults.len() == before {
            return geoms;
        }
    }
}
