//! What every part of codegen reads and none changes: the model, the pruned plan, the names of
//! the generated structs' fields, and facts about the plan indexed once, so that asking them of
//! every geom or register costs no scan of the plan.

use super::names::{Clash, Namer};
use super::writer::lit;
use crate::plan::{Op, Plan, PlanarOp, Reg, SpatialOp};
use gcs_lang::expr::ParamId;
use gcs_lang::model::{ConstraintId, GeomId, Owner, Part};
use gcs_lang::Model;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::collections::BTreeSet;

/// The read-only input of codegen.
pub(super) struct Context<'a> {
    /// How many `SolveError`s' code has been made: a step whose code grew one names its
    /// constraint (see `facts::Made`).
    pub(super) errors_made: std::cell::Cell<usize>,
    /// Whether the code written so far in the function being written reads the run-time
    /// tolerance (a check, a point that must lie on its locus, an iteration's close, a closing
    /// length), so that it declares `tol`: a point onto the locus it was intersected with is
    /// not tested, so a plan's steps alone do not tell.
    pub(super) reads_tol: std::cell::Cell<bool>,
    /// Each top-level geom's members whose local coordinates params set, once asked for
    /// ([`Context::param_members`]).
    pub(super) param_members_of: std::cell::RefCell<HashMap<GeomId, Vec<GeomId>>>,
    pub(super) model: &'a Model,
    pub(super) plan: &'a Plan,
    /// The top-level geoms the solution reports.
    pub(super) scope: &'a BTreeSet<GeomId>,
    /// Param field names.
    pub(super) params: HashMap<ParamId, String>,
    /// Branch field names by branch index.
    pub(super) branches: Vec<String>,
    /// Default field names by default index.
    pub(super) defaults: Vec<String>,
    /// The model's file name, for comments.
    pub(super) file: String,
    /// Registers some generated step reads (an intersection's `near` is for the sketch's
    /// branch only, so it is not among them).
    pub(super) used: HashSet<Reg>,
    /// What the plan does to each geom.
    pub(super) index: PlanIndex,
    /// Points some rotation turns a rigid point onto (`RotatePoint`'s `to`).
    pub(super) rotated_onto: HashSet<Reg>,
    /// Names of params, branch variables and defaults that became one field.
    pub(super) clashes: Vec<(Public, Clash)>,
    /// What the model's space writes differently (see `space`).
    pub(super) space: &'static dyn super::space::Space,
    /// In space, the sketch read once, for the values of constant sketches.
    pub(super) sketch3: Option<crate::config::Config<crate::config::D3>>,
    /// The step that defines each register.
    pub(super) defined_at: HashMap<Reg, usize>,
    /// Nearest points of circles that only turns toward them read ([`turned_toward`]).
    pub(super) turned_toward: HashSet<Reg>,
}

/// The public names of the generated module that come from the model's names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Public {
    /// A field of `Params`.
    Param,
    /// A field of `Branches`.
    Branch,
    /// A field of `Defaults`.
    Default,
    /// An accessor of `Solution`.
    Accessor,
}

impl<'a> Context<'a> {
    pub(super) fn new(model: &'a Model, plan: &'a Plan, scope: &'a BTreeSet<GeomId>) -> Self {
        let mut field_names = Namer::default();
        let params = model
            .params
            .iter()
            .map(|(id, p)| (id, field_names.fresh(&p.name)))
            .collect();
        let mut branch_names = Namer::default();
        let branches = plan
            .branches
            .iter()
            .map(|b| branch_names.fresh(&b.name))
            .collect();
        let mut default_names = Namer::default();
        let defaults = plan
            .defaults
            .iter()
            .map(|d| default_names.fresh(&d.name))
            .collect();
        let clashes = [
            (Public::Param, &field_names),
            (Public::Branch, &branch_names),
            (Public::Default, &default_names),
        ]
        .into_iter()
        .flat_map(|(public, namer)| namer.clashes().iter().map(move |c| (public, c.clone())))
        .collect();
        let file = std::path::Path::new(model.source.name())
            .file_name()
            .map_or_else(
                || model.source.name().to_string(),
                |f| f.to_string_lossy().into_owned(),
            );
        let used = used_registers(plan);
        let index = PlanIndex::new(model, plan, &used);
        let rotated_onto = plan
            .steps
            .iter()
            .filter_map(|s| match &s.op {
                Op::RotatePoint { to, .. } => Some(*to),
                _ => None,
            })
            .collect();
        let space = super::space::of(model);
        let sketch3 = space.sketch_config(model);
        let defined_at = (plan.steps.iter().enumerate())
            .filter_map(|(i, s)| Some((s.out?.0, i)))
            .collect();
        let turned_toward = turned_toward(plan, &defined_at);
        Context {
            errors_made: Default::default(),
            reads_tol: Default::default(),
            param_members_of: Default::default(),
            turned_toward,
            space,
            sketch3,
            defined_at,
            model,
            plan,
            scope,
            params,
            branches,
            defaults,
            file,
            clashes,
            used,
            index,
            rotated_onto,
        }
    }

    /// The top-level geoms the solver computes, in model order.
    pub(super) fn solved(&self) -> Vec<GeomId> {
        self.model
            .top_level()
            .map(|(id, _)| id)
            .filter(|id| self.scope.contains(id))
            .collect()
    }

    /// Whether any step reads or moves geom `g`.
    pub(super) fn touched(&self, g: GeomId) -> bool {
        self.index.touched.contains(&g)
    }

    /// Whether any step moves geom `g`.
    pub(super) fn moved(&self, g: GeomId) -> bool {
        self.index.moved.contains(&g)
    }

    /// Whether the plan sets geom `g`'s dimension before any step reads it.
    pub(super) fn dim_set_before_read(&self, g: GeomId) -> bool {
        self.index.dim_first.get(&g).copied().unwrap_or(false)
    }

    /// Whether some step sets geom `g`'s dimension.
    pub(super) fn dim_set(&self, g: GeomId) -> bool {
        self.index.dim_set.contains(&g)
    }

    /// Whether a step reads feature `f` (a member point, vector, marker or marker axis).
    pub(super) fn reads_feature(&self, f: GeomId) -> bool {
        self.index.read.contains(&f)
    }

    /// `SolveError::new(label, text, kind, magnitude)` for the constraint step `i` works for.
    pub(super) fn error(&self, i: usize, kind: &str, magnitude: &str) -> String {
        match self.plan.constraint_of(i) {
            Some(c) => self.error_of(c, kind, magnitude),
            None => self.error_with("plan", "", kind, magnitude),
        }
    }

    /// The code of a `SolveError` of `kind` naming constraint `c`.
    pub(super) fn error_of(&self, c: ConstraintId, kind: &str, magnitude: &str) -> String {
        let con = &self.model.constraints[c];
        self.error_with(&con.name, &con.text, kind, magnitude)
    }

    /// The code of a `SolveError` of `kind` with the given label and text.
    pub(super) fn error_with(
        &self,
        label: &str,
        text: &str,
        kind: &str,
        magnitude: &str,
    ) -> String {
        self.errors_made.set(self.errors_made.get() + 1);
        format!(
            "SolveError::new({}, {}, ErrorKind::{kind}, {magnitude})",
            lit(label),
            lit(text)
        )
    }
}

/// The registers some generated step reads: what the plan's steps read, but an intersection's
/// `near` (the sketch's branch is chosen at analysis) and the point a circle or sphere goes
/// through when its radius is a constant.
fn used_registers(plan: &Plan) -> HashSet<Reg> {
    let mut used = HashSet::default();
    for step in &plan.steps {
        match &step.op {
            Op::Intersect { a, b, .. } => {
                used.insert(*a);
                used.insert(*b);
            }
            Op::Planar(PlanarOp::CircleThrough {
                center,
                through,
                radius,
            })
            | Op::Spatial(SpatialOp::SphereThrough {
                center,
                through,
                radius,
            }) => {
                used.insert(*center);
                if radius.is_none() {
                    used.insert(*through);
                }
            }
            op => used.extend(op.reads()),
        }
    }
    used
}

/// Per-geom facts about a plan, each from one pass over its steps, so that asking them of every
/// geom costs no scan of the plan.
#[derive(Default)]
pub(super) struct PlanIndex {
    /// [`Plan::touched`].
    touched: BTreeSet<GeomId>,
    /// Geoms some action moves.
    moved: HashSet<GeomId>,
    /// Geoms whose dimension some step sets.
    dim_set: HashSet<GeomId>,
    /// Features a `PointOf` or `DirOf` reads.
    read: HashSet<GeomId>,
    /// For a geom, whether the first step that decides it sets its dimension (see
    /// [`Context::dim_set_before_read`]).
    dim_first: HashMap<GeomId, bool>,
}

impl PlanIndex {
    fn new(model: &Model, plan: &Plan, used: &HashSet<Reg>) -> PlanIndex {
        let mut ix = PlanIndex {
            touched: plan.touched(model),
            ..PlanIndex::default()
        };
        for step in &plan.steps {
            match &step.op {
                Op::Translate { geoms, .. }
                | Op::RotatePoint { geoms, .. }
                | Op::RotateDir { geoms, .. }
                | Op::Spatial(SpatialOp::RotateBy { geoms, .. }) => {
                    ix.moved.extend(geoms.iter().copied())
                }
                Op::SetDim { geom, .. } => {
                    ix.dim_set.insert(*geom);
                    ix.dim_first.entry(*geom).or_insert(true);
                }
                // A measure no generated step reads (a default's sketch value, taken at
                // analysis) reads nothing at run time.
                Op::DimOf(x) if step.out.is_some_and(|o| used.contains(&o.0)) => {
                    ix.dim_first.entry(*x).or_insert(false);
                }
                Op::PointOf(f) => {
                    ix.read.insert(*f);
                    if matches!(model.geoms[*f].owner, Owner::Part(_, Part::End))
                        && step.out.is_some_and(|o| used.contains(&o.0))
                    {
                        ix.dim_first.entry(model.top_level_of(*f)).or_insert(false);
                    }
                }
                Op::DirOf(f) => {
                    ix.read.insert(*f);
                }
                _ => {}
            }
        }
        ix
    }
}

/// The registers that are the nearest point of a circle (`Op::Nearest`) that only turns about
/// the circle's centre read, each turning a point onto it (`RotatePoint`): a turn about the
/// centre onto a point of a ray from the centre is the same turn wherever on the ray the point
/// lies, so the turns can aim at the point itself, and the projection is not written. One pass
/// over the plan.
pub(super) fn turned_toward(
    plan: &crate::plan::Plan,
    defined_at: &HashMap<Reg, usize>,
) -> HashSet<Reg> {
    let defined = |reg: Reg| defined_at.get(&reg).map(|&i| &plan.steps[i].op);
    // The centre of each nearest point of a circle, and whether every reader so far turns
    // about it onto the point (none while nothing has read it).
    let mut nearest: HashMap<Reg, (Reg, Option<bool>)> = HashMap::default();
    for s in &plan.steps {
        if let (Op::Nearest { locus, .. }, Some((r, _))) = (&s.op, s.out) {
            if let Some(Op::Planar(
                PlanarOp::Circle { center, .. } | PlanarOp::CircleThrough { center, .. },
            )) = defined(*locus)
            {
                nearest.insert(r, (*center, None));
            }
        }
    }
    for s in &plan.steps {
        for r in s.op.reads() {
            if let Some((center, all)) = nearest.get_mut(&r) {
                let turns_toward = matches!(&s.op, Op::RotatePoint { pivot, from, to, .. }
                    if *to == r && *from != r && pivot == center);
                *all = Some(all.unwrap_or(true) && turns_toward);
            }
        }
    }
    (nearest.into_iter())
        .filter(|(_, (_, all))| *all == Some(true))
        .map(|(r, _)| r)
        .collect()
}
