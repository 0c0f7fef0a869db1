//! The interpreter: runs a [`Plan`] on a model's sketch with given params, branches and
//! defaults.
//!
//! It is the reference the generated solvers are compared with, and what `gcs solve` uses.
//! Every failure is a [`SolveError`] naming the user's constraint: a locus intersection that
//! does not exist (with the gap), a check that does not hold (with the residual), a degenerate
//! configuration, or a non-finite param. The plan must be valid ([`Plan::validate`]; the
//! pipeline validates every plan it makes): a register read as another type than it holds is
//! a bug in gcs, and panics saying so, rather than going on with a made-up value.
//!
//! One machine, generic over the space ([`Space`]): registers, branch choices, defaults, outer
//! iterations, checks and closes are shared; each space runs its own steps (the plane's in
//! `planar.rs`, space's in `spatial.rs`, over `Frame3`s and the runtime's `locus3d`/`intersect3d`).
//! [`run`]/[`run_with`] are the plane's, [`run_in`] any space's; what returns no configuration
//! ([`sketch_choices`], [`audit`], [`errors_at`], [`scan`], [`runs`]) dispatches on the model's
//! space. An iterated region is run by the runtime's `iterate::solve` (through `outer::Outer`,
//! as generated code does) from the defaults given, re-assembling the region from its saved
//! state for each trial.
//!
//! - [`sketch_choices`] runs the plan on the sketch, taking at each intersection the root
//!   nearest the moving feature and each default's least-motion value: the pipeline makes
//!   those the branches' and defaults' sketch values.
//! - [`scan`] lists every root of the first iteration's error with `outer::Scan`;
//!   [`errors_at`] measures the closes' errors once at given defaults.
//! - [`audit`] runs past the checks that fail (a check places nothing) and returns every one
//!   with its step, and what stopped the run: the report of inconsistent redundant sets.

use crate::config::{Config, Frames, RigidFrame, D2, D3, P2, P3, V2, V3};
use crate::plan::{Iteration, Op, Plan, Reg, Step};
use gcs_lang::model::ConstraintId;
use gcs_lang::Model;
use gcs_runtime::error::{ErrorKind, SolveError};
use gcs_runtime::locus2d::{Circle, Conic, Line};
use gcs_runtime::locus3d::{Circle3, Cylinder, Line3, Plane, Sphere, Torus};
use gcs_runtime::outer::Outer;

mod planar;
mod spatial;

/// How to choose the root of each intersection.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Choice {
    /// The index given for each branch variable (by [`crate::plan::BranchId`] order).
    Given(Vec<usize>),
    /// The root nearest to the moving feature's position before the move (used once, on the
    /// sketch, to find each branch's default).
    Nearest,
}

/// A finished run, in the plane unless said (`Run<D3>`).
#[derive(Clone, Debug)]
pub struct Run<S: Frames = D2> {
    /// The configuration reached.
    pub config: Config<S>,
    /// The index taken at each branch variable, if its intersection ran.
    pub chosen: Vec<Option<usize>>,
    /// The value of each default: as given, as an iteration converged to, or (on the sketch,
    /// with [`Choice::Nearest`]) the one that moves nothing.
    pub defaults: Vec<f64>,
    /// The steps the outer iterations took, all regions together.
    pub iterations: u32,
}

/// The value of a register.
#[derive(Clone, Copy, Debug)]
enum Val {
    S(f64),
    P(P2),
    V(V2),
    L(Line),
    C(Circle),
    Q(Conic),
    P3(P3),
    V3(V3),
    L3(Line3),
    C3(Circle3),
    Plane(Plane),
    Sphere(Sphere),
    Cylinder(Cylinder),
    Torus(Torus),
    /// The answers of the linear system step `.0` solved (in [`Machine::linear`]).
    Xs(u32),
}

/// Runs `plan` with `params` (indexed like the model's params) and each default at its
/// sketch value.
pub fn run(model: &Model, plan: &Plan, params: &[f64], choice: &Choice) -> Result<Run, SolveError> {
    run_with(model, plan, params, &plan.sketch_defaults(), choice)
}

/// Whether `plan` runs to its end with `params` and each default at its sketch value, in the
/// model's space: the error that stops it, if one does.
pub fn runs(model: &Model, plan: &Plan, params: &[f64], choice: &Choice) -> Result<(), SolveError> {
    in_space(model, |space| {
        space.run(
            model,
            plan,
            params,
            plan.sketch_defaults(),
            choice,
            None,
            None::<&mut gcs_runtime::outer::Newton>,
        )
    })
    .map(|_| ())
}

/// [`run_with`] in the space `S`, which must be the model's: `run_in::<D3>` for a 3d model.
pub fn run_in<S: Space>(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    choice: &Choice,
) -> Result<Run<S>, SolveError> {
    run_machine::<S>(model, plan, params, defaults.to_vec(), choice, None)
}

/// [`run_in`] as one start of many ([`gcs_runtime::outer::Search`]): an iteration that fails is
/// not told apart, and none holds a mode, as a generated `solve_all` runs its starts.
pub fn run_searching_in<S: Space>(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    choice: &Choice,
) -> Result<Run<S>, SolveError> {
    run_machine_with::<S>(
        model,
        plan,
        params,
        defaults.to_vec(),
        choice,
        None,
        Some(&mut gcs_runtime::outer::Search),
    )
}

/// Runs `plan` with `params` and `defaults` (indexed like the plan's defaults): each outer
/// iteration starts from the defaults given and ends where its closes hold.
pub fn run_with(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    choice: &Choice,
) -> Result<Run, SolveError> {
    run_machine(model, plan, params, defaults.to_vec(), choice, None)
}

/// The errors the closes of `plan`'s first outer iteration measure with `defaults` as given
/// (no iteration): what an iteration drives to zero. An error where the plan cannot assemble
/// up to there, or the iteration's region at these defaults.
pub fn errors_at(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    choice: &Choice,
) -> Result<Vec<f64>, SolveError> {
    let mut measure = Measure::default();
    let run = in_space(model, |space| {
        space.run(
            model,
            plan,
            params,
            defaults.to_vec(),
            choice,
            None,
            Some(&mut measure),
        )
    });
    match (measure.errors, run) {
        (Some(errors), _) => Ok(errors),
        (None, Err(e)) => Err(e),
        // A plan without outer iterations: nothing to close.
        (None, Ok(_)) => Ok(Vec::new()),
    }
}

/// An outer iteration measured once, at its start: the errors kept, the run ended there.
#[derive(Default)]
struct Measure {
    errors: Option<Vec<f64>>,
}

impl Outer for Measure {
    fn iterate<const N: usize, E>(
        &mut self,
        trial: &mut [f64; N],
        _scale: &[f64; N],
        _settings: &gcs_runtime::iterate::Settings,
        mut f: impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
    ) -> Result<gcs_runtime::iterate::Converged, gcs_runtime::iterate::Failure<E>> {
        use gcs_runtime::iterate::Failure;
        let mut errors = [0.0; N];
        f(trial, &mut errors).map_err(Failure::Start)?;
        self.errors = Some(errors.to_vec());
        Err(Failure::NoConvergence {
            residual: f64::NAN,
            iterations: 0,
        })
    }
}

/// Runs `plan` with `defaults` as given up to its first outer iteration, and lists every
/// root of that iteration's error over a turn of its default with the runtime's
/// [`Scan`](gcs_runtime::outer::Scan), as a generated `solve_all` does: what every real
/// assembly is searched on ([`crate::all`]). The scan says whether it reached such an
/// iteration (an iteration over one default, on an assembly that exists up to there).
pub fn scan(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    choice: &Choice,
) -> gcs_runtime::outer::Scan {
    let mut scan = gcs_runtime::outer::Scan::default();
    // The run ends at the iteration scanned, with the scan's stop as its error.
    let _ = in_space(model, |space| {
        space.run(
            model,
            plan,
            params,
            defaults.to_vec(),
            choice,
            None,
            Some(&mut scan),
        )
    });
    scan
}

/// Runs `plan`; with `reached`, on the sketch: each default takes the value its measure
/// register holds (least motion), recorded there, and closes are not enforced.
fn run_machine<S: Space>(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: Vec<f64>,
    choice: &Choice,
    reached: Option<&mut Vec<Option<f64>>>,
) -> Result<Run<S>, SolveError> {
    run_machine_with::<S>(
        model,
        plan,
        params,
        defaults,
        choice,
        reached,
        None::<&mut gcs_runtime::outer::Newton>,
    )
}

/// [`run_machine`]; with `first`, the outer iterations are driven by it instead of solved
/// (a [`Scan`](gcs_runtime::outer::Scan), or a [`Measure`]: each ends the run at the first).
fn run_machine_with<S: Space>(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: Vec<f64>,
    choice: &Choice,
    reached: Option<&mut Vec<Option<f64>>>,
    first: Option<&mut impl Outer>,
) -> Result<Run<S>, SolveError> {
    let mut machine = Machine::<S>::start(model, plan, params, defaults, choice, reached)?;
    machine.execute(first).map_err(|f| f.error)?;
    Ok(machine.finish())
}

/// The model's space, for the runs whose result holds no configuration.
#[derive(Clone, Copy)]
enum InSpace {
    D2,
    D3,
}

impl InSpace {
    /// [`run_machine_with`] in this space, keeping what holds no configuration.
    #[allow(clippy::too_many_arguments)]
    fn run(
        self,
        model: &Model,
        plan: &Plan,
        params: &[f64],
        defaults: Vec<f64>,
        choice: &Choice,
        reached: Option<&mut Vec<Option<f64>>>,
        first: Option<&mut impl Outer>,
    ) -> Result<(Vec<Option<usize>>, Vec<f64>), SolveError> {
        match self {
            InSpace::D2 => {
                run_machine_with::<D2>(model, plan, params, defaults, choice, reached, first)
                    .map(|r| (r.chosen, r.defaults))
            }
            InSpace::D3 => {
                run_machine_with::<D3>(model, plan, params, defaults, choice, reached, first)
                    .map(|r| (r.chosen, r.defaults))
            }
        }
    }
}

fn in_space<T>(model: &Model, f: impl FnOnce(InSpace) -> T) -> T {
    match model.space {
        gcs_lang::model::Space::D2 => f(InSpace::D2),
        gcs_lang::model::Space::D3 => f(InSpace::D3),
    }
}

/// A check that did not hold, or the error that stopped a run: the step it happened at (an
/// outer iteration that does not converge: its last close; none when the run stopped before
/// its first step, or inside an iteration's trial) and the error.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    /// The step, an index into the plan's steps.
    pub step: Option<usize>,
    /// The error, naming the constraint with its magnitude.
    pub error: SolveError,
}

/// A run that went on past the checks that failed ([`audit`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Audit {
    /// Every check that did not hold, in step order.
    pub failed: Vec<Failure>,
    /// What stopped the run, if something did: a step that cannot be done (loci that miss, a
    /// degenerate configuration, an invalid value, an iteration that does not converge).
    pub stopped: Option<Failure>,
}

/// Runs `plan` as [`run_with`] does, except that a check that fails does not stop it: a check
/// places nothing, so every later step runs as it would have, and every failed check is
/// reported, each an inconsistent redundant constraint. What cannot be done still stops the
/// run (a check inside an outer iteration's trials is that iteration's business, and fails
/// it as in [`run_with`]). [`run_with`] itself pays nothing for this: the difference is only
/// on a check's failing path.
pub fn audit(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    choice: &Choice,
) -> Audit {
    match model.space {
        gcs_lang::model::Space::D2 => audit_in::<D2>(model, plan, params, defaults, choice),
        gcs_lang::model::Space::D3 => audit_in::<D3>(model, plan, params, defaults, choice),
    }
}

fn audit_in<S: Space>(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    choice: &Choice,
) -> Audit {
    let mut machine =
        match Machine::<S>::start(model, plan, params, defaults.to_vec(), choice, None) {
            Ok(m) => m,
            Err(error) => {
                return Audit {
                    failed: Vec::new(),
                    stopped: Some(Failure { step: None, error }),
                }
            }
        };
    machine.failed = Some(Vec::new());
    let stopped = machine
        .execute(None::<&mut gcs_runtime::outer::Newton>)
        .err();
    Audit {
        failed: machine.failed.take().unwrap_or_default(),
        stopped,
    }
}

/// Each run-time check's residual and each `Onto`'s gap of `plan` (one with no outer
/// iterations) run with `defaults`, by step index, and the configuration's size: the run goes
/// on past those that fail, so that the analysis can see which of them move with the
/// defaults. An error where the plan cannot assemble.
pub fn residuals_at(
    model: &Model,
    plan: &Plan,
    defaults: &[f64],
    choice: &Choice,
) -> Result<(Vec<(usize, f64)>, f64), SolveError> {
    fn run<S: Space>(
        model: &Model,
        plan: &Plan,
        defaults: &[f64],
        choice: &Choice,
    ) -> Result<(Vec<(usize, f64)>, f64), SolveError> {
        let params = model.default_params();
        let mut machine =
            Machine::<S>::start(model, plan, &params, defaults.to_vec(), choice, None)?;
        machine.probed = Some(Vec::new());
        (machine.execute(None::<&mut gcs_runtime::outer::Newton>)).map_err(|f| f.error)?;
        Ok((machine.probed.take().unwrap_or_default(), machine.scale))
    }
    match model.space {
        gcs_lang::model::Space::D2 => run::<D2>(model, plan, defaults, choice),
        gcs_lang::model::Space::D3 => run::<D3>(model, plan, defaults, choice),
    }
}

/// The values of registers `regs` of a `plan` being written (no outer iterations yet) run on
/// the sketch, each default at its least-motion value and each branch at its sketch root, a
/// check that fails not stopping the run: a scalar as `[x, 0, 0]`, a point or a direction as
/// its coordinates (in the plane, `z` 0), a line of space as its direction, anything else NaN. `None` where the plan does not
/// run. What the analysis asks of a system it is about to write (which of its coefficients
/// vanish), or of a default it is about to take (whether what follows is regular there).
pub fn sketch_values(model: &Model, plan: &Plan, regs: &[Reg]) -> Option<Vec<[f64; 3]>> {
    fn read<S: Space>(model: &Model, plan: &Plan, regs: &[Reg]) -> Option<Vec<[f64; 3]>> {
        let params = model.default_params();
        let mut reached = vec![None; plan.defaults.len()];
        let mut machine = Machine::<S>::start(
            model,
            plan,
            &params,
            plan.sketch_defaults(),
            &Choice::Nearest,
            Some(&mut reached),
        )
        .ok()?;
        machine.failed = Some(Vec::new());
        machine
            .execute(None::<&mut gcs_runtime::outer::Newton>)
            .ok()?;
        Some(
            (regs.iter())
                .map(|&r| match machine.get(r) {
                    Some(&Val::S(x)) => [x, 0.0, 0.0],
                    Some(&Val::P(p)) => [p.x, p.y, 0.0],
                    Some(&Val::V(v)) => [v.x, v.y, 0.0],
                    Some(&Val::P3(p)) => [p.x, p.y, p.z],
                    Some(&Val::V3(v)) => [v.x, v.y, v.z],
                    Some(Val::L3(l)) => [l.dir.x, l.dir.y, l.dir.z],
                    _ => [f64::NAN; 3],
                })
                .collect(),
        )
    }
    match model.space {
        gcs_lang::model::Space::D2 => read::<D2>(model, plan, regs),
        gcs_lang::model::Space::D3 => read::<D3>(model, plan, regs),
    }
}

/// The index of the root nearest to the sketch's position of the moving feature, at each
/// intersection of the plan run on the sketch with the default params: each branch
/// variable's default. `None` where the run did not reach an intersection.
pub fn sketch_branches(model: &Model, plan: &Plan) -> Vec<Option<usize>> {
    sketch_choices(model, plan).0
}

/// Each branch variable's default (as [`sketch_branches`]) and each default's sketch value:
/// what its measure register holds when the plan runs on the sketch, so that the default
/// moves nothing there (least motion). `None` where the run did not reach it. A check that
/// fails does not stop this run: it places nothing, and an inconsistent redundant constraint
/// early in the plan must not leave every later branch and default without its sketch value
/// (the model is reported inconsistent, and only that). A step that cannot be done on the
/// sketch (loci that miss) stops it: the branches before it are the sketch's all the same.
pub fn sketch_choices(model: &Model, plan: &Plan) -> (Vec<Option<usize>>, Vec<Option<f64>>) {
    fn on_sketch<S: Space>(
        model: &Model,
        plan: &Plan,
        reached: &mut Vec<Option<f64>>,
    ) -> Vec<Option<usize>> {
        let params = model.default_params();
        let defaults = plan.sketch_defaults();
        let choice = Choice::Nearest;
        match Machine::<S>::start(model, plan, &params, defaults, &choice, Some(reached)) {
            Ok(mut machine) => {
                let _ = machine.execute(None::<&mut gcs_runtime::outer::Newton>);
                std::mem::take(&mut machine.chosen)
            }
            Err(_) => vec![None; plan.branches.len()],
        }
    }
    let mut reached = vec![None; plan.defaults.len()];
    let chosen = match model.space {
        gcs_lang::model::Space::D2 => on_sketch::<D2>(model, plan, &mut reached),
        gcs_lang::model::Space::D3 => on_sketch::<D3>(model, plan, &mut reached),
    };
    (chosen, reached)
}

/// The orientation of each of `plan`'s iterations (in order) at the root each reaches when the
/// plan runs at `params` from `defaults` on `branches`: its assembly mode
/// ([`gcs_runtime::mode`]). `None` for one whose root has none, and for those after a step that
/// fails.
pub fn modes_at(
    model: &Model,
    plan: &Plan,
    params: &[f64],
    defaults: &[f64],
    branches: &[usize],
) -> Vec<Option<gcs_runtime::mode::Orientation>> {
    let mut orient = Orient::default();
    let choice = Choice::Given(branches.to_vec());
    let _ = in_space(model, |space| {
        space.run(
            model,
            plan,
            params,
            defaults.to_vec(),
            &choice,
            None,
            Some(&mut orient),
        )
    });
    let mut modes = orient.modes;
    modes.resize(plan.iterations.len(), None);
    modes
}

/// Solves each outer iteration with no mode held, and records the orientation of the root it
/// reaches.
#[derive(Default)]
struct Orient {
    modes: Vec<Option<gcs_runtime::mode::Orientation>>,
}

impl Outer for Orient {
    fn iterate<const N: usize, E: gcs_runtime::iterate::Gap>(
        &mut self,
        trial: &mut [f64; N],
        scale: &[f64; N],
        settings: &gcs_runtime::iterate::Settings,
        mut f: impl FnMut(&[f64; N], &mut [f64; N]) -> Result<(), E>,
    ) -> Result<gcs_runtime::iterate::Converged, gcs_runtime::iterate::Failure<E>> {
        let converged = gcs_runtime::iterate::solve(trial, scale, &settings.holding(None), &mut f)?;
        (self.modes).push(gcs_runtime::mode::orientation(trial, scale, &mut f));
        Ok(converged)
    }
}

/// What a space's interpreter adds to the machine: its steps.
pub trait Space: Frames {
    /// Runs one step of the space's plan, keeping the value it defines in its register.
    #[doc(hidden)]
    fn step(m: &mut Machine<'_, '_, Self>, i: usize, step: &Step) -> Result<(), SolveError>;
}

/// A run in progress (public only as the argument of [`Space::step`]).
#[doc(hidden)]
#[allow(missing_debug_implementations)]
pub struct Machine<'a, 'r, S: Space> {
    model: &'a Model,
    plan: &'a Plan,
    params: &'a [f64],
    defaults: Vec<f64>,
    choice: &'a Choice,
    config: Config<S>,
    /// The tolerance of checks, relative to the configuration's scale.
    tol: f64,
    /// The configuration's size: the natural step of a default that is a length.
    scale: f64,
    regs: Vec<Option<Val>>,
    chosen: Vec<Option<usize>>,
    /// On the sketch: each default's least-motion value, as reached.
    reached: Option<&'r mut Vec<Option<f64>>>,
    /// Inside an iterated region: the errors its closes measure, in step order.
    errors: Option<Vec<f64>>,
    /// Evaluations of iterated regions so far.
    evaluations: u32,
    /// Steps of outer iterations so far.
    iterations: u32,
    /// When auditing ([`audit`]): the checks that failed, the run going on past them.
    failed: Option<Vec<Failure>>,
    /// When probing ([`residuals_at`]): each check's residual and each `Onto`'s gap by step,
    /// the run going on past them.
    probed: Option<Vec<(usize, f64)>>,
    /// The answers of each linear system, by the step that solved it.
    linear: Vec<Vec<f64>>,
}

/// The panic of a malformed plan: a bug in gcs, never an input's fault.
#[cold]
fn malformed(r: Reg, want: &str, got: Option<&Val>) -> ! {
    panic!(
        "bug in gcs: the plan reads r{} as {want}, but it holds {got:?}; \
         the pipeline validates every plan, so please report this",
        r.0
    )
}

impl<'a, 'r, S: Space> Machine<'a, 'r, S> {
    /// A machine at the start of `plan`: params and defaults checked finite and within range,
    /// the configuration read from the sketch.
    fn start(
        model: &'a Model,
        plan: &'a Plan,
        params: &'a [f64],
        defaults: Vec<f64>,
        choice: &'a Choice,
        reached: Option<&'r mut Vec<Option<f64>>>,
    ) -> Result<Self, SolveError> {
        // As the generated solve checks them (`check_all_finite`): finite, and within range.
        for ((_, p), v) in model.params.iter().zip(params) {
            if !gcs_runtime::num::in_range(*v) {
                return Err(SolveError::new(
                    p.name.clone(),
                    String::new(),
                    ErrorKind::InvalidInput,
                    *v,
                ));
            }
        }
        for (d, v) in plan.defaults.iter().zip(&defaults) {
            if !gcs_runtime::num::in_range(*v) {
                // No text, as the generated solve's `check_all_finite` reports it.
                return Err(SolveError::new(
                    d.name.clone(),
                    String::new(),
                    ErrorKind::InvalidInput,
                    *v,
                ));
            }
        }
        let config = Config::from_sketch(model, params).map_err(|b| {
            SolveError::new(
                model.geoms[b.geom].name.clone(),
                b.what,
                ErrorKind::InvalidInput,
                f64::NAN,
            )
        })?;
        let scale = config_scale(&config, &plan.touched(model));
        Ok(Machine {
            model,
            plan,
            params,
            defaults,
            choice,
            config,
            tol: gcs_runtime::tol::CHECK_REL * (1.0 + scale),
            scale,
            regs: vec![None; plan.regs as usize],
            chosen: vec![None; plan.branches.len()],
            reached,
            errors: None,
            evaluations: 0,
            iterations: 0,
            failed: None,
            probed: None,
            linear: Vec::new(),
        })
    }

    /// Runs every step, each iterated region by its outer iteration unless the run is on the
    /// sketch; the iterations driven by `first` when given (which ends the run at the first),
    /// else solved.
    fn execute<O: Outer>(&mut self, mut first: Option<&mut O>) -> Result<(), Failure> {
        let plan = self.plan;
        let iterate = self.reached.is_none();
        let mut i = 0;
        while i < plan.steps.len() {
            match plan.iterations.iter().find(|it| it.start == i) {
                Some(it) if iterate => {
                    let outcome = match first.as_deref_mut() {
                        Some(outer) => self.iterate(it, outer),
                        None => self.iterate(it, &mut gcs_runtime::outer::Newton),
                    };
                    outcome.map_err(|error| Failure {
                        // An iteration that fails (not at its start) names its first close.
                        step: matches!(
                            error.kind,
                            ErrorKind::NoConvergence
                                | ErrorKind::NoAssembly
                                | ErrorKind::NoAssemblyNear
                                | ErrorKind::OtherMode
                        )
                        .then(|| self.first_close(it)),
                        error,
                    })?;
                    i = it.end;
                }
                _ => {
                    self.step(i, &plan.steps[i]).map_err(|error| Failure {
                        step: Some(i),
                        error,
                    })?;
                    i += 1;
                }
            }
        }
        Ok(())
    }

    /// The step of iterated region `it`'s first close (its last step if it has none): the
    /// constraint an iteration that does not converge is named after.
    fn first_close(&self, it: &Iteration) -> usize {
        (it.start..it.end)
            .find(|&i| matches!(self.plan.steps[i].op, Op::Close { .. }))
            .unwrap_or(it.end.saturating_sub(1))
    }

    /// The run's result.
    fn finish(self) -> Run<S> {
        Run {
            config: self.config,
            chosen: self.chosen,
            defaults: self.defaults,
            iterations: self.iterations,
        }
    }

    /// Runs iterated region `it`: varies its defaults, from their values given, until every
    /// close in it measures zero (000, section 5.2.1), then keeps that assembly. `outer`
    /// drives the iteration, as in a generated solver: it solves it, or scans it.
    fn iterate<O: Outer>(&mut self, it: &Iteration, outer: &mut O) -> Result<(), SolveError> {
        match it.defaults.len() {
            1 => self.iterate_n::<1, O>(it, outer),
            2 => self.iterate_n::<2, O>(it, outer),
            3 => self.iterate_n::<3, O>(it, outer),
            4 => self.iterate_n::<4, O>(it, outer),
            5 => self.iterate_n::<5, O>(it, outer),
            6 => self.iterate_n::<6, O>(it, outer),
            n => Err(self.error(it.start, ErrorKind::NoConvergence, n as f64)),
        }
    }

    /// [`Machine::iterate`] over `N` defaults.
    fn iterate_n<const N: usize, O: Outer>(
        &mut self,
        it: &Iteration,
        outer: &mut O,
    ) -> Result<(), SolveError> {
        use gcs_runtime::iterate::{self, Settings, Span};
        let mut x = [0.0; N];
        let mut scale = [0.0; N];
        for (k, d) in it.defaults.iter().enumerate() {
            x[k] = self.defaults[d.0 as usize];
            // An angle's natural step is a radian; a length's, the configuration's size.
            scale[k] = if self.plan.defaults[d.0 as usize].is_angle() {
                1.0
            } else {
                1.0 + self.scale
            };
        }
        let saved = (self.config.clone(), self.regs.clone(), self.chosen.clone());
        // One angle's turn, searched for a root when its iteration fails.
        let span = match it.defaults.as_slice() {
            [d] if self.plan.defaults[d.0 as usize].is_angle() => Span::Turn,
            _ => Span::Unknown,
        };
        // From the sketch's own defaults on its branches (a cold solve), the sketch's assembly
        // mode is kept, as generated code keeps it: an orientation is the sketch's on the
        // sketch's branches only (another branch closes another function).
        let sketch_branches = match self.choice {
            Choice::Given(given) => {
                (given.iter().zip(&self.plan.branches)).all(|(i, b)| *i == b.default)
            }
            Choice::Nearest => false,
        };
        let from_sketch = sketch_branches
            && (it.defaults.iter().zip(&x))
                .all(|(d, v)| *v == self.plan.defaults[d.0 as usize].sketch);
        let settings = Settings::for_size(self.scale)
            .spanning(span)
            .holding(it.mode.filter(|_| from_sketch));
        let outcome = outer.iterate(&mut x, &scale, &settings, |x: &[f64; N], r| {
            self.assemble(it, &saved, x, r)
        });
        match outcome {
            Ok(converged) => {
                self.iterations += converged.iterations;
                // An angle reported in (-pi, pi], as generated code reports it.
                for (k, d) in it.defaults.iter().enumerate() {
                    if self.plan.defaults[d.0 as usize].is_angle() {
                        x[k] = gcs_runtime::num::wrap_angle(x[k]);
                    }
                }
                // Leave the machine in the assembly converged to.
                let mut r = [0.0; N];
                self.assemble(it, &saved, &x, &mut r)
            }
            Err(iterate::Failure::Start(e)) => Err(e),
            // Named after the iteration's first close, as generated code names it.
            Err(failure) => {
                let (kind, magnitude) = (failure.kind())
                    .unwrap_or_else(|| panic!("bug in gcs: a failure at the start has no kind"));
                Err(self.error(self.first_close(it), kind, magnitude))
            }
        }
    }

    /// Assembles iterated region `it` from the state `saved` at its start with its defaults
    /// at `x`, and writes the errors its closes measure into `r`.
    fn assemble(
        &mut self,
        it: &Iteration,
        saved: &(Config<S>, Vec<Option<Val>>, Vec<Option<usize>>),
        x: &[f64],
        r: &mut [f64],
    ) -> Result<(), SolveError> {
        (self.config, self.regs, self.chosen) = saved.clone();
        for (d, &v) in it.defaults.iter().zip(x) {
            self.defaults[d.0 as usize] = v;
        }
        self.errors = Some(Vec::with_capacity(r.len()));
        self.evaluations += 1;
        let plan = self.plan;
        let mut outcome = Ok(());
        for i in it.start..it.end {
            outcome = self.step(i, &plan.steps[i]);
            if outcome.is_err() {
                break;
            }
        }
        let errors = self.errors.take().unwrap_or_default();
        outcome?;
        for (slot, e) in r.iter_mut().zip(errors) {
            *slot = e;
        }
        Ok(())
    }

    fn get(&self, r: Reg) -> Option<&Val> {
        self.regs.get(r.0 as usize)?.as_ref()
    }
    fn s(&self, r: Reg) -> f64 {
        match self.get(r) {
            Some(&Val::S(x)) => x,
            v => malformed(r, "a scalar", v),
        }
    }
    /// An optional scalar, zero when absent.
    fn s_or_zero(&self, r: Option<Reg>) -> f64 {
        r.map_or(0.0, |r| self.s(r))
    }

    /// The error of step `i`'s constraint, or of the plan when the step works for none.
    fn error(&self, i: usize, kind: ErrorKind, magnitude: f64) -> SolveError {
        match self.plan.constraint_of(i) {
            Some(c) => err(self.model, c, kind, magnitude),
            None => SolveError::new("plan", String::new(), kind, magnitude),
        }
    }

    /// Step `i` cannot be done: its loci or directions are degenerate here.
    fn degenerate(&self, i: usize) -> SolveError {
        self.error(i, ErrorKind::Degenerate, 0.0)
    }

    /// `x` when it is finite; otherwise step `i`'s constraint cannot be met: a value the
    /// params give, finite one by one, can still overflow (`theta * 1e300`).
    /// Sets geom `g`'s dimension to register `value`, a size (finite, not negative), in
    /// either space.
    fn set_dim(
        &mut self,
        i: usize,
        g: gcs_lang::model::GeomId,
        value: Reg,
    ) -> Result<(), SolveError> {
        let mut x = self.s(value);
        // A closing length within rounding of zero is zero: the profile closes with that
        // segment collapsed, whichever side of zero the arithmetic lands on.
        if x < 0.0 && x >= -self.tol && self.plan.closing_length(i).is_some() {
            x = 0.0;
        }
        if !x.is_finite() || x < 0.0 {
            // A size given as a default is the default's fault, not the constraint's.
            if let Some(d) = self.plan.given_default(value) {
                let d = &self.plan.defaults[d.0 as usize];
                return Err(SolveError::new(
                    d.name.clone(),
                    d.meaning.clone(),
                    ErrorKind::InvalidDefault,
                    x,
                ));
            }
            // A length a linear stage solves for: the profile cannot close.
            if let (true, Some(c)) = (x.is_finite(), self.plan.closing_length(i)) {
                let c = &self.model.constraints[c];
                return Err(SolveError::new(
                    c.name.clone(),
                    c.text.clone(),
                    ErrorKind::CannotClose,
                    x,
                ));
            }
            return Err(self.error(i, ErrorKind::InvalidValue, x));
        }
        self.config.dims.insert(g, x);
        Ok(())
    }

    fn finite(&self, i: usize, x: f64) -> Result<f64, SolveError> {
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.error(i, ErrorKind::InvalidValue, x))
        }
    }

    /// Runs one step, keeping the value it defines in its register.
    fn step(&mut self, i: usize, step: &Step) -> Result<(), SolveError> {
        S::step(self, i, step)
    }

    /// The root index of `branch`: the one given, or on the sketch the root `nearest` finds
    /// (the one nearest the moving feature), recorded as the branch's default.
    fn choose(
        &mut self,
        branch: crate::plan::BranchId,
        nearest: impl FnOnce(&Self) -> Option<usize>,
    ) -> usize {
        let index = match self.choice {
            Choice::Given(b) => b.get(branch.0 as usize).copied().unwrap_or(0),
            Choice::Nearest => nearest(self).unwrap_or(0),
        };
        if let Some(slot) = self.chosen.get_mut(branch.0 as usize) {
            *slot = Some(index);
        }
        index
    }

    /// The value of a default: as given, or on the sketch the one that moves nothing (what
    /// its measure holds), recorded.
    fn default_value(&mut self, d: crate::plan::DefaultId) -> f64 {
        let k = d.0 as usize;
        let measured = (self.plan.defaults.get(k))
            .and_then(|v| v.measure)
            .filter(|_| self.reached.is_some())
            .and_then(|m| match self.get(m) {
                Some(&Val::S(x)) => Some(x),
                _ => None,
            });
        if let (Some(x), Some(reached)) = (measured, self.reached.as_deref_mut()) {
            reached[k] = Some(x);
            self.defaults[k] = x;
        }
        self.defaults
            .get(k)
            .copied()
            .unwrap_or_else(|| panic!("bug in gcs: no value for default {} of the plan", d.0))
    }
}

impl<'a, 'r, S: Space> Machine<'a, 'r, S> {
    /// The value of a scalar step, the same in every space; `None` for any other step.
    /// Step `i`'s several answers (`Ty::Values`), kept for `Op::Unknown` to read.
    fn answers(&mut self, i: usize, values: Vec<f64>) -> Val {
        if self.linear.len() <= i {
            self.linear.resize(i + 1, Vec::new());
        }
        self.linear[i] = values;
        Val::Xs(i as u32)
    }

    fn scalar(&mut self, i: usize, op: &Op) -> Result<Option<Val>, SolveError> {
        let model = self.model;
        Ok(Some(match op {
            Op::Expr(e) => Val::S(self.finite(i, model.exprs.eval(*e, self.params))?),
            Op::Size { expr, constraint } => {
                let x = model.exprs.eval(*expr, self.params);
                if !x.is_finite() || x < 0.0 {
                    // A size that is a param alone is the param's fault (params are finite).
                    if let gcs_lang::expr::ExprNode::Param(p) = model.exprs.node(*expr) {
                        return Err(SolveError::new(
                            model.params[*p].name.clone(),
                            model.constraints[*constraint].text.clone(),
                            ErrorKind::InvalidParam,
                            x,
                        ));
                    }
                    return Err(err(model, *constraint, ErrorKind::InvalidValue, x));
                }
                Val::S(x)
            }
            Op::Const(c) => Val::S(*c),
            // On the sketch, the value that moves nothing: what its measure holds.
            Op::Default(d) => Val::S(self.default_value(*d)),
            Op::Neg(x) => Val::S(-self.s(*x)),
            Op::DimOf(g) => Val::S(self.config.dim(*g)),
            Op::Sum(terms) => {
                let sum = terms.iter().map(|(k, r)| k * self.s(*r)).sum();
                Val::S(self.finite(i, sum)?)
            }
            Op::Unknown { of, index } => match self.get(*of) {
                Some(&Val::Xs(at)) => Val::S(self.linear[at as usize][*index as usize]),
                v => malformed(*of, "a step's answers", v),
            },
            _ => return Ok(None),
        }))
    }

    /// Keeps the value step `step` defines in its register.
    fn store(&mut self, step: &Step, value: Val) {
        if let Some((r, _)) = step.out {
            if let Some(slot) = self.regs.get_mut(r.0 as usize) {
                *slot = Some(value);
            }
        }
    }

    /// A check of `constraint` at step `i` that measured `r`: within tolerance, or an error
    /// (on the sketch, or auditing, the run goes on).
    fn checked(&mut self, i: usize, constraint: ConstraintId, r: f64) -> Result<(), SolveError> {
        if let Some(probed) = self.probed.as_mut() {
            probed.push((i, r));
            return Ok(());
        }
        if r.is_nan() || r > self.tol {
            // On the sketch, a check that fails decides nothing the run is for (the
            // branches and the defaults' sketch values): it places nothing.
            if self.reached.is_some() {
                return Ok(());
            }
            let error = err(self.model, constraint, ErrorKind::Inconsistent, r);
            // Auditing, outside an iteration's trials: the run goes on.
            if let (Some(failed), None) = (self.failed.as_mut(), &self.errors) {
                failed.push(Failure {
                    step: Some(i),
                    error,
                });
                return Ok(());
            }
            return Err(error);
        }
        Ok(())
    }

    /// A point that a motion must reach on its locus, `gap` from it: inconsistent past the
    /// tolerance (probing, recorded instead).
    fn onto(&mut self, i: usize, constraint: ConstraintId, gap: f64) -> Result<(), SolveError> {
        if let Some(probed) = self.probed.as_mut() {
            probed.push((i, gap));
            return Ok(());
        }
        if gap.is_nan() || gap > self.tol {
            return Err(err(self.model, constraint, ErrorKind::Inconsistent, gap));
        }
        Ok(())
    }

    /// A close of `constraint` reading error `residual`: inside an iteration, an error
    /// function it drives to zero; otherwise the defaults given must close it.
    fn closed(&mut self, constraint: ConstraintId, residual: Reg) -> Result<(), SolveError> {
        let error = self.s(residual);
        if let Some(errors) = self.errors.as_mut() {
            errors.push(error);
            return Ok(());
        }
        if self.reached.is_some() {
            // On the sketch: its defaults are where the iteration starts.
            return Ok(());
        }
        let r = error.abs();
        if r.is_nan() || r > self.tol {
            return Err(err(self.model, constraint, ErrorKind::NoConvergence, r));
        }
        Ok(())
    }
}

fn err(model: &Model, c: ConstraintId, kind: ErrorKind, magnitude: f64) -> SolveError {
    let con = &model.constraints[c];
    SolveError::new(con.name.clone(), con.text.clone(), kind, magnitude)
}

/// The largest coordinate or dimension of the given geoms in a configuration: what tolerances
/// scale with.
pub fn config_scale<S: Frames>(
    config: &Config<S>,
    geoms: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
) -> f64 {
    let mut s: f64 = 0.0;
    for (g, f) in &config.frames {
        if geoms.contains(g) {
            for x in <S::Frame as RigidFrame>::coords(&f.origin()) {
                s = s.max(x.abs());
            }
        }
    }
    for (g, d) in &config.dims {
        if geoms.contains(g) {
            s = s.max(d.abs());
        }
    }
    s
}
