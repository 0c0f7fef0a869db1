//! The shared driver of the analysis: POSITION-ANALYSIS over clusters (000, Appendix A),
//! whatever the space.
//!
//! Every top-level geom starts as a *cluster*: a set of geoms that move together, with an
//! invariants record. The driver tries the pending relations in canonical order, first by
//! action analysis, then by locus analysis (both given by the [`Geometry`]), retrying a
//! relation only when a cluster it involves has changed; when both stop, it assembles the
//! smallest rigid chain or loop on a temporary ground and rewrites it as a macro-geom
//! (SOLVE-RIGID-CHAINS, SOLVE-LOOP), then goes on. Attempts that fail are rolled back, so the
//! plan holds only what was used. It also owns the plan being written: registers, their
//! words for explanations, and the caches of what has been measured.
//!
//! Checks: a relation already implied becomes a run-time check ([`Builder::check`]), and
//! every implied relation is measured, not only a constraint's last, so that no relation the
//! plan relies on goes unmeasured.
//!
//! Defaults (000, section 5.2.1): when nothing else applies and clusters still move, the
//! geometry fixes one freedom of the cluster a pending relation involves with the fewest DOF
//! (`Geometry::default`), and analysis goes on. `close_iterations` then finds, by tracing which
//! defaults each register and frame depends on (`Op::measures`, `Op::moves`), the checks (and
//! `Onto`s) a default displaced: each becomes an `Op::Error` and an `Op::Close` of an
//! `Iteration` region that varies the default. A coincidence, midpoint or mirror image with
//! more coordinates than open defaults closes one default by the distance it is off by
//! (`plan::MAGNITUDE`); a point on a line of space that two open defaults displaced closes
//! both by its offset across the line, two signed coordinates (a cylindrical robot's column
//! turn and carriage place). A default that displaces nothing parameterizes a free motion
//! (`Analysis::free_defaults`, the mobility); `Analysis::undefaulted` keeps the clusters as the
//! constraints alone left them.
//!
//! The work is linear in the model: a relation is retried only when a cluster it involves
//! changes, caches roll back by an insertion log, and registers and steps are looked up by
//! index, never by a scan.

use super::geometry::{Geometry, Invariants, Rel};
use super::{Analysis, Cluster, Unsupported};
use crate::plan::{BranchId, BranchVar, Op, Plan, Reg, Step, Ty};
use gcs_lang::model::{ConstraintId, GeomId};
use gcs_lang::Model;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::collections::{BTreeMap, BTreeSet};

/// Analyses a model with the geometry of its space.
pub(super) fn analyse<G: Geometry>(
    model: &Model,
    moves: super::Moves,
    values: super::Values,
) -> Result<Analysis, super::Unreadable> {
    let (mut rels, unsupported) = G::decompose(model)?;
    // Canonical order: by constraint name, then relation order within the constraint, so that
    // the plan does not depend on the order of statements.
    rels.sort_by(|a, b| {
        model.constraints[a.constraint]
            .name
            .cmp(&model.constraints[b.constraint].name)
    });
    mark_duplicates::<G>(&mut rels);
    let mut b = Builder::<G>::new(model);
    b.moves = Some(moves);
    b.values = Some(values);
    b.run(rels);
    let mut unsolved = unsupported;
    let mut listed: BTreeSet<ConstraintId> = unsolved.iter().map(|u| u.constraint).collect();
    for r in b.pending.drain(..) {
        if listed.insert(r.constraint) {
            unsolved.push(Unsupported {
                constraint: r.constraint,
                reason: "no plan fragment applies: its geoms keep too much freedom".into(),
            });
        }
    }
    let recorded = b
        .clusters
        .iter()
        .flat_map(|c| c.record.recorded())
        .filter(|c| !listed.contains(c))
        .collect();
    let redundant = b.redundant;
    let clusters = summary(model, &b.clusters);
    let undefaulted = match &b.undefaulted {
        Some(states) => summary(model, states),
        None => clusters.clone(),
    };
    Ok(Analysis {
        plan: b.plan,
        clusters,
        undefaulted,
        unsolved,
        recorded,
        redundant,
    })
}

/// Appends an error function (`Op::Error` or `Op::Implicit`) in a new register, and the
/// `Op::Close` of `constraint` that an outer iteration drives it to zero with.
fn error_and_close(
    steps: &mut Vec<Step>,
    regs: &mut u32,
    error: Op,
    constraint: ConstraintId,
    satisfies: Vec<ConstraintId>,
    explain: String,
) {
    let residual = Reg(*regs);
    *regs += 1;
    steps.push(Step {
        op: error,
        out: Some((residual, Ty::Scalar)),
        satisfies: Vec::new(),
        works_for: Some(constraint),
        explain: String::new(),
    });
    steps.push(Step {
        op: Op::Close {
            constraint,
            residual,
        },
        out: None,
        satisfies,
        works_for: Some(constraint),
        explain,
    });
}

/// The clusters as the analysis reports them.
fn summary<R: Invariants>(model: &Model, states: &[ClusterState<R>]) -> Vec<Cluster> {
    (states.iter())
        .map(|c| Cluster {
            geoms: c.geoms.clone(),
            dof: c.record.dof(),
            table2: c.record.table2(),
            freedom: (c.geoms.first()).map_or_else(String::new, |&g| c.record.freedom(model, g)),
        })
        .collect()
}

/// What makes two relations duplicates: the same kind over the same features.
type RelKey<R> = (std::mem::Discriminant<R>, Vec<GeomId>);

/// The key of a relation.
fn key<G: Geometry>(r: &G::Relation) -> RelKey<G::Relation> {
    let mut features = G::features(r);
    features.sort_unstable();
    features.dedup();
    (std::mem::discriminant(r), features)
}

/// Marks every relation whose key an earlier one (in canonical order) has.
fn mark_duplicates<G: Geometry>(rels: &mut [Rel<G::Relation>]) {
    let mut seen = HashSet::default();
    for r in rels {
        r.duplicate = !seen.insert(key::<G>(&r.relation));
    }
}

/// A cluster while the analysis runs: its top-level geoms and its record.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ClusterState<R> {
    /// The top-level geoms (empty once merged into a macro-geom).
    pub(crate) geoms: Vec<GeomId>,
    /// The invariants record.
    pub(crate) record: R,
}

/// A key of one of the builder's register caches.
#[derive(Clone, Copy, Debug)]
enum Key {
    Known(GeomId),
    Measured((GeomId, bool)),
    Expr(gcs_lang::expr::ExprId),
}

/// Where a rollback returns to: the plan's steps, registers and branches.
pub(crate) type Checkpoint = (usize, u32, usize);

/// The most clusters tied for a default that [`Builder::look_ahead`] tries besides the first.
const LOOK_AHEAD_TIES: usize = 3;

/// The most defaults [`Builder::look_ahead`] tries on a copy over one analysis.
const LOOK_AHEAD_BUDGET: usize = 32;

/// The analysis in progress: clusters and their records, the relations still pending, and
/// the plan written so far.
#[derive(Clone)]
pub(crate) struct Builder<'m, G: Geometry> {
    pub(crate) model: &'m Model,
    /// Which checks move with the defaults, asked once the plan is written (see
    /// [`super::analyse`]); none while a loop is solved on a temporary ground.
    pub(crate) moves: Option<super::Moves>,
    /// What registers hold when the plan so far runs on the sketch (see [`super::analyse`]).
    pub(crate) values: Option<super::Values>,
    /// Whether relations a linear stage can take whole are left to it where action or locus
    /// analysis would build them as a double root (a touching contact as the meeting of two
    /// loci that touch): true until a linear stage finds nothing to take.
    pub(crate) linear_first: bool,
    /// Pairs of geoms a space's geometry marks once per model (the plane: each circle and
    /// segment in a touching contact, the segment's end on the circle it touches).
    pub(crate) pairs: std::rc::Rc<std::cell::OnceCell<HashSet<(GeomId, GeomId)>>>,
    pub(crate) plan: Plan,
    pub(crate) clusters: Vec<ClusterState<G::Record>>,
    /// The cluster of each top-level geom, by its index in the model's arena (0 for the
    /// others, which no lookup reaches): read at every step, so a vector, not a map.
    cluster_of: Vec<usize>,
    /// Registers holding invariant positions, reused once measured.
    known_points: HashMap<GeomId, Reg>,
    /// Registers holding current positions and directions, valid until their cluster moves.
    measured: HashMap<(GeomId, bool), Reg>,
    /// The keys of `measured` by top-level geom (a superset: keys may have gone since), so
    /// that an action forgets what it invalidates without scanning every measurement.
    measured_by_top: HashMap<GeomId, Vec<(GeomId, bool)>>,
    /// The centre of each locus register that has one, in words, for branch meanings.
    pub(crate) centers: BTreeMap<Reg, String>,
    exprs: HashMap<gcs_lang::expr::ExprId, Reg>,
    /// The constraint whose value each size expression is ([`Model::value_is_size`]): its
    /// register checks that it is not negative.
    size_of: HashMap<gcs_lang::expr::ExprId, gcs_lang::model::ConstraintId>,
    /// Words for registers (indexed by register), to write explanations and branch meanings.
    words: Vec<Option<String>>,
    /// The keys inserted into `known_points`, `measured` and `exprs` since the last
    /// checkpoint, so that a rollback forgets them without scanning the maps.
    inserted: Vec<Key>,
    /// The step defining each register, by register number.
    def_step: Vec<usize>,
    pub(crate) pending: Vec<Rel<G::Relation>>,
    /// Every relation the analysis started with, for the guards of iterated regions.
    relations: Vec<Rel<G::Relation>>,
    redundant: Vec<ConstraintId>,
    /// For each constraint, a step that moves geoms for it ([`Builder::moved_for`]).
    moved: HashMap<ConstraintId, usize>,
    /// Constraints a step solved together with others constructed in part (a linear stage's
    /// rows), whichever constraint that step works for.
    constructed: HashSet<ConstraintId>,
    /// The keys of the relations done so far: a duplicate waits for its key here.
    done: HashSet<RelKey<G::Relation>>,
    /// The clusters before the first default, once one is added.
    undefaulted: Option<Vec<ClusterState<G::Record>>>,
    /// The constraint of the relation being tried, which each step written records.
    working: Option<ConstraintId>,
    /// Each geom's place in name order (by arena index): the last key of the defaults' order.
    name_rank: std::rc::Rc<Vec<u32>>,
    /// Once no relation is pending, the clusters that may take a default in their order: a
    /// default then changes its own cluster only, so the order is kept, not sorted again.
    idle_order: Option<std::collections::BinaryHeap<std::cmp::Reverse<(usize, u32, usize)>>>,
    /// How many more defaults [`Builder::look_ahead`] may try on a copy: a bound on its work,
    /// each trial a copy and one stage, so that analysis stays linear in a model's size
    /// however many ties it meets (an arm meets one or two).
    look_aheads_left: usize,
}

/// A geom's index in the model's arena.
fn geom_index(g: GeomId) -> usize {
    g.into_raw().into_u32() as usize
}

/// Each geom's place in the order of names, by its index in the model's arena.
fn name_ranks(model: &Model) -> Vec<u32> {
    let mut by_name: Vec<(&str, usize)> = (model.geoms.iter())
        .map(|(id, g)| (g.name.as_str(), geom_index(id)))
        .collect();
    by_name.sort();
    let mut rank = vec![0; model.geoms.len()];
    for (place, (_, index)) in by_name.into_iter().enumerate() {
        rank[index] = place as u32;
    }
    rank
}

impl<'m, G: Geometry> Builder<'m, G> {
    fn new(model: &'m Model) -> Self {
        let mut clusters = Vec::new();
        let mut cluster_of = vec![0; model.geoms.len()];
        for (id, _) in model.top_level() {
            cluster_of[geom_index(id)] = clusters.len();
            clusters.push(ClusterState {
                geoms: vec![id],
                record: G::record(model, id),
            });
        }
        Builder {
            model,
            moves: None,
            values: None,
            linear_first: true,
            pairs: Default::default(),
            plan: Plan::new(model.space),
            clusters,
            cluster_of,
            known_points: HashMap::default(),
            measured: HashMap::default(),
            measured_by_top: HashMap::default(),
            centers: BTreeMap::new(),
            exprs: HashMap::default(),
            size_of: model
                .constraints
                .iter()
                .filter(|&(id, _)| model.value_is_size(id))
                .filter_map(|(id, c)| Some((c.value?, id)))
                .collect(),
            words: Vec::new(),
            inserted: Vec::new(),
            def_step: Vec::new(),
            pending: Vec::new(),
            relations: Vec::new(),
            redundant: Vec::new(),
            moved: HashMap::default(),
            constructed: HashSet::default(),
            done: HashSet::default(),
            undefaulted: None,
            working: None,
            name_rank: std::rc::Rc::new(name_ranks(model)),
            idle_order: None,
            look_aheads_left: LOOK_AHEAD_BUDGET,
        }
    }

    // ------------------------------------------------------------ emitting

    /// Appends a step; returns the register it defines (meaningless when `ty` is `None`).
    pub(crate) fn emit(
        &mut self,
        op: impl Into<Op>,
        ty: Option<Ty>,
        satisfies: Vec<ConstraintId>,
        explain: String,
    ) -> Reg {
        let op = op.into();
        // An action invalidates what was measured on the geoms it moves.
        for g in op.moves().to_vec() {
            self.forget_measured(g);
        }
        if let (Some(c), false) = (self.working, op.moves().is_empty()) {
            if !self.moved_for(c) {
                self.moved.insert(c, self.plan.steps.len());
            }
        }
        let reg = Reg(self.plan.regs);
        let out = ty.map(|t| {
            self.plan.regs += 1;
            (reg, t)
        });
        if out.is_some() {
            self.def_step.push(self.plan.steps.len());
        }
        self.plan.steps.push(Step {
            op,
            out,
            satisfies,
            works_for: self.working,
            explain,
        });
        reg
    }

    /// Whether any of registers `regs` depends on a default taken so far: read from one, or
    /// measured on a geom a step that read one moved (as `close_iterations` traces it).
    pub(crate) fn depends_on_default(&self, regs: &[Reg]) -> bool {
        // Most plans take no default: nothing to trace.
        if self.plan.defaults.is_empty() {
            return false;
        }
        let mut reg_deps = vec![BTreeSet::new(); self.plan.regs as usize];
        let mut geom_deps = HashMap::default();
        for step in &self.plan.steps {
            trace_defaults(self.model, step, &mut reg_deps, &mut geom_deps);
        }
        regs.iter()
            .any(|r| reg_deps.get(r.0 as usize).is_some_and(|d| !d.is_empty()))
    }

    /// Whether a step of the plan so far moves geoms for constraint `c` (one of its relations
    /// was constructed, not only checked). The index kept may be stale after a rollback: the
    /// step at it is read to tell.
    fn moved_for(&self, c: ConstraintId) -> bool {
        self.constructed.contains(&c)
            || self.moved.get(&c).is_some_and(|&i| {
                self.plan
                    .steps
                    .get(i)
                    .is_some_and(|s| s.works_for == Some(c) && !s.op.moves().is_empty())
            })
    }

    /// Forgets the measurements of the features of top-level geom `top` (it moves).
    fn forget_measured(&mut self, top: GeomId) {
        if let Some(keys) = self.measured_by_top.remove(&top) {
            for k in keys {
                self.measured.remove(&k);
            }
        }
    }

    fn insert_measured(&mut self, key: (GeomId, bool), r: Reg) {
        self.measured.insert(key, r);
        self.measured_by_top
            .entry(self.model.top_level_of(key.0))
            .or_default()
            .push(key);
        self.inserted.push(Key::Measured(key));
    }

    /// Notes that register `r` holds the invariant position of point feature `f`.
    pub(crate) fn insert_known(&mut self, f: GeomId, r: Reg) {
        self.known_points.insert(f, r);
        self.inserted.push(Key::Known(f));
    }

    /// The step that defines register `r`.
    pub(crate) fn def(&self, r: Reg) -> Option<&Step> {
        self.def_step
            .get(r.0 as usize)
            .and_then(|&i| self.plan.steps.get(i))
    }

    /// The type of register `r`.
    pub(crate) fn ty(&self, r: Reg) -> Ty {
        self.def(r)
            .and_then(|s| s.out.filter(|o| o.0 == r).map(|o| o.1))
            .unwrap_or(Ty::Scalar)
    }

    /// A step computing a value, described by `words` where explanations name it.
    pub(crate) fn value(&mut self, op: impl Into<Op>, ty: Ty, words: String) -> Reg {
        let r = self.emit(op, Some(ty), Vec::new(), String::new());
        let i = r.0 as usize;
        if self.words.len() <= i {
            self.words.resize(i + 1, None);
        }
        self.words[i] = Some(words);
        r
    }

    /// How explanations name register `r`.
    pub(crate) fn word(&self, r: Reg) -> String {
        match self.words.get(r.0 as usize) {
            Some(Some(w)) => w.clone(),
            _ => format!("r{}", r.0),
        }
    }

    /// A cluster's geoms as the subject of a sentence: `crank`, or `link10 (with link7, link8)`.
    pub(crate) fn group_name(&self, geoms: &[GeomId]) -> String {
        match geoms {
            [] => String::new(),
            [one] => self.name(*one),
            [first, rest @ ..] => format!(
                "{} (with {})",
                self.name(*first),
                rest.iter()
                    .map(|&g| self.name(g))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        }
    }

    pub(crate) fn name(&self, g: GeomId) -> String {
        self.model.geoms[g].name.clone()
    }

    /// A constraint as explanations quote it: `label: text`, or the text.
    pub(crate) fn cname(&self, c: ConstraintId) -> String {
        let c = &self.model.constraints[c];
        match &c.label {
            Some(l) => format!("{l}: {}", c.text),
            None => c.text.clone(),
        }
    }

    /// The register of a model expression, evaluated once.
    pub(crate) fn expr(&mut self, e: gcs_lang::expr::ExprId) -> Reg {
        if let Some(r) = self.exprs.get(&e) {
            return *r;
        }
        let text = crate::plan::expr_text(self.model, e);
        let op = match self.size_of.get(&e) {
            Some(&constraint) => Op::Size {
                expr: e,
                constraint,
            },
            None => Op::Expr(e),
        };
        let r = self.value(op, Ty::Scalar, text);
        self.exprs.insert(e, r);
        self.inserted.push(Key::Expr(e));
        r
    }

    /// The current position of a point feature (re-measured unless invariant).
    pub(crate) fn point(&mut self, f: GeomId) -> Reg {
        if let Some(r) = self
            .known_points
            .get(&f)
            .or_else(|| self.measured.get(&(f, true)))
        {
            return *r;
        }
        let r = self.value(Op::PointOf(f), Ty::Point, self.name(f));
        if self.point_known(f) {
            self.insert_known(f, r);
        } else {
            self.insert_measured((f, true), r);
        }
        r
    }

    /// The current direction of a vector feature (re-measured after its cluster moves).
    pub(crate) fn direction(&mut self, g: GeomId) -> Reg {
        if let Some(r) = self.measured.get(&(g, false)) {
            return *r;
        }
        let words = self.name(g);
        let r = self.value(Op::DirOf(g), Ty::Vector, words);
        self.insert_measured((g, false), r);
        r
    }

    /// Declares a branch variable for an intersection that satisfies `constraint`: named
    /// after it, with the meaning of each of its `meanings.len()` roots. A single root still
    /// declares its (trivial) branch, so that every intersection is named.
    ///
    /// Names are unique: a constraint with a second intersection names it `NAME_2` (and so
    /// on), except that a single root (a crossing, with nothing to choose) gives its name up
    /// to a later intersection with several.
    pub(crate) fn branch(&mut self, constraint: ConstraintId, meanings: Vec<String>) -> BranchId {
        let base = &self.model.constraints[constraint].name;
        let free = |branches: &[BranchVar]| {
            (2..)
                .map(|k| format!("{base}_{k}"))
                .find(|n| branches.iter().all(|b| &b.name != n))
                .expect("a free name")
        };
        let mut name = base.clone();
        if let Some(i) = self.plan.branches.iter().position(|b| &b.name == base) {
            let renamed = free(&self.plan.branches);
            if self.plan.branches[i].count == 1 && meanings.len() > 1 {
                self.plan.branches[i].name = renamed;
            } else {
                name = renamed;
            }
        }
        let id = BranchId(self.plan.branches.len() as u32);
        self.plan.branches.push(BranchVar {
            name,
            constraint,
            count: meanings.len(),
            meanings,
            default: 0,
            from_sketch: false,
            symmetric: false,
        });
        id
    }

    // ------------------------------------------------------------ knowledge

    /// The cluster that moves feature or geom `g`.
    pub(crate) fn cluster(&self, g: GeomId) -> usize {
        let top = self.model.top_level_of(g);
        self.cluster_of.get(geom_index(top)).copied().unwrap_or(0)
    }

    /// The record of the cluster that moves `g`.
    pub(crate) fn record(&self, g: GeomId) -> &G::Record {
        &self.clusters[self.cluster(g)].record
    }

    /// Whether point feature `f` is invariant.
    pub(crate) fn point_known(&self, f: GeomId) -> bool {
        self.record(f).point_known(self.model, f)
    }

    /// The relations constraint `c` decomposes into.
    pub(crate) fn relations_of(&self, c: ConstraintId) -> Vec<G::Relation> {
        (self.relations.iter())
            .filter(|r| r.constraint == c)
            .map(|r| r.relation.clone())
            .collect()
    }

    /// The constraints a step satisfying `r` satisfies: its constraint, on its last relation.
    pub(crate) fn satisfies(&self, r: &Rel<G::Relation>) -> Vec<ConstraintId> {
        if r.last {
            vec![r.constraint]
        } else {
            Vec::new()
        }
    }

    /// Whether a relation of this kind between these features has been satisfied (by action,
    /// locus analysis or a check).
    pub(crate) fn is_done(&self, r: &G::Relation) -> bool {
        self.done.contains(&key::<G>(r))
    }

    /// A relation already implied: a run-time check that measures it. The check of a
    /// constraint's last relation satisfies the constraint, which is then redundant; an earlier
    /// relation is checked too, so that no relation the plan relies on goes unmeasured.
    pub(crate) fn check(&mut self, r: &Rel<G::Relation>) {
        let residual = G::residual(self, &r.relation);
        let explain = if r.last {
            format!(
                "Check that {} holds: it is implied by the steps before.",
                self.cname(r.constraint)
            )
        } else {
            format!(
                "Check that part of {} holds: it is implied by the steps before.",
                self.cname(r.constraint)
            )
        };
        self.emit(
            Op::Check {
                constraint: r.constraint,
                residual,
                guard: false,
            },
            None,
            self.satisfies(r),
            explain,
        );
        // A constraint some of whose relations were constructed is not redundant, only its
        // implied part is (a revolute joint of a planar mechanism modelled in space: its
        // coincidence places the link, its parallel axes are implied): checked, not listed.
        if r.last && !self.moved_for(r.constraint) {
            self.redundant.push(r.constraint);
        }
    }

    // ------------------------------------------------------------ the driver

    fn run(&mut self, rels: Vec<Rel<G::Relation>>) {
        self.relations = rels.clone();
        // Unary constraints first (Appendix A.3): dimensions.
        let (dims, others): (Vec<_>, Vec<_>) =
            rels.into_iter().partition(|r| G::is_dimension(&r.relation));
        for r in &dims {
            self.working = Some(r.constraint);
            G::action(self, r);
        }
        self.working = None;
        self.pending = others;
        if !self.model.top_level().any(|(_, g)| g.fixed) && !self.clusters.is_empty() {
            let free = |b: &Self| b.clusters.iter().map(|c| c.record.dof()).sum::<usize>();
            let before = free(self);
            G::ground(self);
            // What the grounding holds: the placement's DOF, less any the constraints already
            // anchor to the world (horizontal and vertical ones anchor the rotation).
            self.plan.grounded_dof = before.saturating_sub(free(self));
        }
        // POSITION-ANALYSIS (000, Appendix A.3): action and locus analysis until stuck; then
        // the smallest rigid chain or loop is assembled on a temporary ground and rewritten as
        // a macro-geom; repeat.
        //
        // When neither applies and clusters still move (000, section 5.2.1), a default fixes
        // one freedom of the cluster with the fewest DOF, preferring those the pending
        // relations involve; the constraints it displaces become the error functions of an
        // outer iteration ([`Builder::close_iterations`]), and one that displaces none
        // parameterizes a free motion.
        loop {
            self.stage();
            if self.undefaulted.is_none() {
                self.undefaulted = Some(self.clusters.clone());
            }
            if !self.take_default() {
                break;
            }
            // A default changed the clusters: a linear stage may now take what it could not.
            self.linear_first = true;
        }
        // A constraint a later step constructed in part is not redundant (`check`); read
        // before `close_iterations` renumbers the steps.
        let redundant = std::mem::take(&mut self.redundant);
        self.redundant = redundant
            .into_iter()
            .filter(|&c| !self.moved_for(c))
            .collect();
        self.close_iterations();
    }

    /// Action, locus, chain, loop, linear and sub-chain analysis until none applies: one stage
    /// of POSITION-ANALYSIS, between two defaults.
    fn stage(&mut self) {
        loop {
            self.fixpoint(None);
            if !self.pending.is_empty() && self.group() {
                continue;
            }
            if !self.pending.is_empty() && G::linear(self) {
                continue;
            }
            // Nothing for a linear stage: what was left to it goes back to action analysis.
            if self.linear_first && !self.pending.is_empty() {
                self.linear_first = false;
                continue;
            }
            if !self.pending.is_empty() && G::subchains(self) {
                continue;
            }
            break;
        }
    }

    /// How many relations stay pending after cluster `k` takes a default and the stage after
    /// it runs, on a copy; `None` when `k` takes none.
    fn left_after_default(&self, k: usize) -> Option<usize> {
        let mut trial = self.clone();
        if !G::default(&mut trial, &[k]) {
            return None;
        }
        trial.linear_first = true;
        trial.stage();
        Some(trial.pending.len())
    }

    /// Of the clusters tied with `first` for a default (involved in a pending relation, one
    /// freedom each, [`Geometry::LOOK_AHEAD`]), the one whose default lets the next stage
    /// settle the most pending relations, when it settles more than `first`'s: an arm whose
    /// base and tool ends both turn about known axes closes with one default at the right
    /// end and needs three at the other. At most [`LOOK_AHEAD_TIES`] are tried, each one stage
    /// on a copy, and [`LOOK_AHEAD_BUDGET`] over the analysis.
    fn look_ahead(&mut self, first: usize, involved: &BTreeSet<usize>) -> usize {
        if !G::LOOK_AHEAD || self.look_aheads_left == 0 {
            return first;
        }
        let Some(key) = self.default_key(involved, first) else {
            return first;
        };
        if key.1 != 1 {
            return first;
        }
        let mut tied: Vec<_> = (involved.iter())
            .filter(|&&k| k != first)
            .filter_map(|&k| self.default_key(involved, k))
            .filter(|other| (other.0, other.1) == (key.0, key.1))
            .collect();
        if tied.is_empty() {
            return first;
        }
        tied.sort();
        self.look_aheads_left -= 1;
        let Some(mut least) = self.left_after_default(first) else {
            return first;
        };
        let mut best = first;
        for other in tied.into_iter().take(LOOK_AHEAD_TIES) {
            if least == 0 || self.look_aheads_left == 0 {
                break;
            }
            self.look_aheads_left -= 1;
            if let Some(left) = self.left_after_default(other.3) {
                if left < least {
                    (least, best) = (left, other.3);
                }
            }
        }
        best
    }

    /// The order in which clusters may take a default: not grounded, in the order Kramer picks
    /// a loop to rigidify: those a pending relation involves first, then by fewest DOF, then
    /// by name. `None` for a cluster that may not.
    fn default_key(
        &self,
        involved: &BTreeSet<usize>,
        k: usize,
    ) -> Option<(bool, usize, u32, usize)> {
        let c = &self.clusters[k];
        let first = c.geoms.first()?;
        let dof = c.record.dof();
        (dof > 0).then(|| {
            (
                !involved.contains(&k),
                dof,
                self.name_rank[geom_index(*first)],
                k,
            )
        })
    }

    /// The clusters a pending relation involves.
    fn involved_clusters(&self) -> BTreeSet<usize> {
        (self.pending.iter())
            .flat_map(|r| self.clusters_of(r))
            .collect()
    }

    /// Gives a default to the first cluster that takes one, in the order of
    /// [`Builder::default_key`]; `false` when none does.
    ///
    /// A model with a default per stage asks once per stage, so the order is not sorted each
    /// time: while relations are pending, the first is one of the clusters they involve (a
    /// pass over those); once none is, the order is kept in a heap across defaults, each of
    /// which changes its own cluster only. The clusters are sorted only when the first
    /// refuses.
    fn take_default(&mut self) -> bool {
        if !self.pending.is_empty() {
            self.idle_order = None;
            let involved = self.involved_clusters();
            let first = (involved.iter())
                .filter_map(|&k| self.default_key(&involved, k))
                .min()
                .or_else(|| {
                    (0..self.clusters.len())
                        .filter_map(|k| self.default_key(&involved, k))
                        .min()
                });
            let Some(first) = first.map(|key| key.3) else {
                return false;
            };
            // One that would leave a pending relation degenerate on the sketch gives way to
            // the next the pending relations involve, when that one would not.
            let first = if G::default_leaves_degenerate(self, first) {
                let mut keys: Vec<_> = (involved.iter())
                    .filter(|&&k| k != first)
                    .filter_map(|&k| self.default_key(&involved, k))
                    .collect();
                keys.sort();
                (keys.into_iter().map(|key| key.3))
                    .find(|&k| !G::default_leaves_degenerate(self, k))
                    .unwrap_or(first)
            } else {
                first
            };
            let first = self.look_ahead(first, &involved);
            if G::default(self, &[first]) {
                return true;
            }
            // A refused default changes nothing: the order is the one `first` came from.
            let mut keys: Vec<_> = (0..self.clusters.len())
                .filter(|&k| k != first)
                .filter_map(|k| self.default_key(&involved, k))
                .collect();
            keys.sort();
            let others: Vec<usize> = keys.into_iter().map(|key| key.3).collect();
            return G::default(self, &others);
        }
        let none = BTreeSet::new();
        let mut heap = match self.idle_order.take() {
            Some(heap) => heap,
            None => (0..self.clusters.len())
                .filter_map(|k| self.default_key(&none, k))
                .map(|(_, dof, rank, k)| std::cmp::Reverse((dof, rank, k)))
                .collect(),
        };
        let mut refused = Vec::new();
        let mut taken = false;
        while let Some(std::cmp::Reverse(entry)) = heap.pop() {
            let k = entry.2;
            // An entry whose cluster changed since is put back at its place now.
            match self.default_key(&none, k) {
                Some((_, dof, rank, _)) if (dof, rank, k) == entry => {}
                Some((_, dof, rank, _)) => {
                    heap.push(std::cmp::Reverse((dof, rank, k)));
                    continue;
                }
                None => continue,
            }
            if G::default(self, &[k]) {
                if let Some((_, dof, rank, _)) = self.default_key(&none, k) {
                    heap.push(std::cmp::Reverse((dof, rank, k)));
                }
                taken = true;
                break;
            }
            refused.push(std::cmp::Reverse(entry));
        }
        heap.extend(refused);
        self.idle_order = Some(heap);
        taken
    }

    /// Case (b) of 000, section 5.2.1: a run-time check that depends on a default is a
    /// constraint that the default displaced. Taking the checks in plan order, each becomes the
    /// error function of the latest default it depends on that no earlier one closes (a
    /// coincidence closes two, and so does a point on a line of space): `Op::Error` measures
    /// it signed, `Op::Close` drives it to zero. The defaults so closed are varied by outer
    /// iterations, over the steps from the first such default to its last close (overlapping
    /// regions merge); the others parameterize a free motion (case (a)). A check no open
    /// default explains stays a check.
    ///
    /// A point met on its own locus (the meeting of that locus with another) is on it
    /// wherever the meeting exists: its distance from the locus is zero or undefined, no
    /// error to close. Such a step is passed over for a later check its default displaced (a
    /// turn's cone, two circles' common plane), unless none closes that default.
    fn close_iterations(&mut self) {
        if self.plan.defaults.is_empty() {
            return;
        }
        let mut trial = self.clone();
        if trial.close_iterations_with(true) {
            *self = trial;
        } else {
            self.close_iterations_with(false);
        }
    }

    /// [`Builder::close_iterations`]; with `past_own_locus`, a point met on its own locus is
    /// passed over. Returns whether every default so passed over is closed by a later step.
    fn close_iterations_with(&mut self, past_own_locus: bool) -> bool {
        use crate::plan::{DefaultId, Iteration, Residual};
        let model = self.model;
        // What each register holds, by the steps that define them.
        let defs: HashMap<Reg, Op> = (self.plan.steps.iter())
            .filter_map(|s| s.out.map(|(r, _)| (r, s.op.clone())))
            .collect();
        let same_locus =
            |a: Reg, b: Reg| a == b || defs.get(&a).is_some_and(|d| defs.get(&b) == Some(d));
        let met_on = |locus: Reg, point: Reg| match defs.get(&point) {
            Some(Op::Intersect { a, b, .. }) => same_locus(*a, locus) || same_locus(*b, locus),
            _ => false,
        };
        let mut passed_over: BTreeSet<u32> = BTreeSet::new();
        // The defaults each register and each top-level geom's placement depend on.
        let mut reg_deps: Vec<BTreeSet<u32>> = vec![BTreeSet::new(); self.plan.regs as usize];
        let mut geom_deps: HashMap<GeomId, BTreeSet<u32>> = HashMap::default();
        let mut closed: BTreeSet<u32> = BTreeSet::new();
        let mut steps = Vec::with_capacity(self.plan.steps.len());
        // For each closed default: the step that reads it and its last close, in new steps.
        let mut spans: BTreeMap<u32, (usize, usize)> = BTreeMap::new();
        let mut regs = self.plan.regs;
        // Which checks move with the defaults, run on the sketch: one that does not is no
        // error to close, whatever it depends on on paper.
        let moving = self.moves.map(|f| f(model, &self.plan)).unwrap_or_default();
        for (i, step) in std::mem::take(&mut self.plan.steps).into_iter().enumerate() {
            let deps = trace_defaults(model, &step, &mut reg_deps, &mut geom_deps);
            let displaced = match moving.get(i) {
                Some(Some(false)) => BTreeSet::new(),
                _ => deps,
            };
            // A point that a 1-DOF motion must reach on its locus, displaced by a default: it
            // goes to the locus' nearest point, and its distance closes the iteration.
            if let (
                Op::Onto {
                    locus,
                    point,
                    constraint,
                },
                Some(&d),
            ) = (&step.op, displaced.difference(&closed).last())
            {
                if past_own_locus && met_on(*locus, *point) {
                    passed_over.insert(d);
                    steps.push(step);
                    continue;
                }
                closed.insert(d);
                let (locus, point, constraint) = (*locus, *point, *constraint);
                steps.push(Step {
                    op: Op::Nearest { locus, point },
                    ..step.clone()
                });
                let (cname, name) = (self.cname(constraint), &self.plan.defaults[d as usize].name);
                let explain = format!(
                    "{cname} is what `{name}` displaced: how far its point is from its locus closes the iteration on `{name}`."
                );
                // An orbit whose plane the model keeps the point in: its sphere's signed
                // distance, with a guard on the plane (see `Geometry::kept_in_orbit_plane`).
                let in_plane = match (defs.get(&locus), defs.get(&point)) {
                    (
                        Some(Op::Spatial(crate::plan::SpatialOp::Orbit {
                            pivot,
                            axis,
                            through,
                        })),
                        Some(Op::PointOf(g)),
                    ) => match defs.get(axis) {
                        Some(Op::DirOf(f)) if G::kept_in_orbit_plane(self, *f, *g) => {
                            Some((*pivot, *axis, *through))
                        }
                        _ => None,
                    },
                    _ => None,
                };
                let error = match in_plane {
                    Some((pivot, axis, through)) => {
                        let mut define = |op: Op, ty: Ty| {
                            let r = Reg(regs);
                            regs += 1;
                            steps.push(Step {
                                op,
                                out: Some((r, ty)),
                                satisfies: Vec::new(),
                                works_for: Some(constraint),
                                explain: String::new(),
                            });
                            r
                        };
                        let line = define(
                            Op::Line {
                                point: pivot,
                                dir: axis,
                                offset: None,
                            },
                            Ty::Line,
                        );
                        let center = define(
                            Op::Nearest {
                                locus: line,
                                point: through,
                            },
                            Ty::Point,
                        );
                        let sphere = define(
                            Op::Spatial(crate::plan::SpatialOp::SphereThrough {
                                center,
                                through,
                                radius: None,
                            }),
                            Ty::Sphere,
                        );
                        Op::Implicit {
                            locus: sphere,
                            point,
                        }
                    }
                    None => Op::Implicit { locus, point },
                };
                error_and_close(
                    &mut steps,
                    &mut regs,
                    error,
                    constraint,
                    Vec::new(),
                    explain,
                );
                spans.entry(d).or_insert((usize::MAX, 0)).1 = steps.len();
                if let Some((_, axis, through)) = in_plane {
                    let explain = format!(
                        "Guard: check that {cname} has its point in its locus' plane once the iteration has closed."
                    );
                    steps.push(Step {
                        op: Op::Check {
                            constraint,
                            residual: Residual::PointPlane {
                                p: point,
                                base: through,
                                normal: axis,
                                d: None,
                            },
                            guard: true,
                        },
                        out: None,
                        satisfies: Vec::new(),
                        works_for: Some(constraint),
                        explain,
                    });
                }
                continue;
            }
            let Op::Check {
                constraint,
                residual,
                ..
            } = &step.op
            else {
                steps.push(step);
                continue;
            };
            // A coincidence of points is one equation per coordinate.
            let coordinates = match self.model.space {
                gcs_lang::model::Space::D2 => 2,
                gcs_lang::model::Space::D3 => 3,
            };
            let components: u8 = match residual {
                Residual::PointPoint { d: None, .. }
                | Residual::Midpoint { .. }
                | Residual::Mirror { .. }
                | Residual::MirrorPlane { .. } => coordinates,
                _ => 1,
            };
            let open: Vec<u32> = displaced.difference(&closed).copied().collect();
            // A point on a line of space is two equations: with two open defaults displacing
            // it (a cylindrical robot's column turn and carriage place), its offset across the
            // line, two signed coordinates (`Op::Error` components 1 and 2), closes both.
            let across_line = matches!(residual, Residual::PointLine { d: None, .. })
                && self.model.space == gcs_lang::model::Space::D3
                && open.len() >= 2;
            let (components, first) = if across_line { (2, 1) } else { (components, 0) };
            // A coincidence (or a midpoint, a mirror image) one default displaced, whose
            // coordinates are more equations than it has defaults: the distance it is off by
            // closes the iteration (zero there, and every coordinate with it; unsigned,
            // V-shaped at the root, which the iteration's polish knows).
            if let [d] = open.as_slice() {
                if components > 1 {
                    let (d, constraint) = (*d, *constraint);
                    closed.insert(d);
                    let (cname, name) =
                        (self.cname(constraint), &self.plan.defaults[d as usize].name);
                    let explain = format!(
                        "{cname} is what `{name}` displaced: the distance it is off by closes the iteration on `{name}`, and every coordinate with it."
                    );
                    let error = Op::Error {
                        residual: residual.clone(),
                        component: crate::plan::MAGNITUDE,
                    };
                    let satisfies = step.satisfies.clone();
                    error_and_close(&mut steps, &mut regs, error, constraint, satisfies, explain);
                    spans.entry(d).or_insert((usize::MAX, 0)).1 = steps.len();
                    self.redundant.retain(|c| *c != constraint);
                    continue;
                }
            }
            if open.len() < usize::from(components) {
                steps.push(step);
                continue;
            }
            let (constraint, residual) = (*constraint, residual.clone());
            let cname = self.cname(constraint);
            for (component, &d) in open.iter().rev().take(components.into()).enumerate() {
                closed.insert(d);
                let words = match (across_line, components) {
                    (true, _) => [" across its line", " across its line, the other way"][component],
                    (false, 1) => "",
                    (false, _) => [" along x", " along y", " along z"][component],
                };
                let last = component + 1 == usize::from(components);
                let name = &self.plan.defaults[d as usize].name;
                let explain = format!(
                    "{cname} is what `{name}` displaced: its error{words} closes the iteration on `{name}`."
                );
                let error = Op::Error {
                    residual: residual.clone(),
                    component: first + component as u8,
                };
                let satisfies = if last {
                    step.satisfies.clone()
                } else {
                    Vec::new()
                };
                error_and_close(&mut steps, &mut regs, error, constraint, satisfies, explain);
                spans.entry(d).or_insert((usize::MAX, 0)).1 = steps.len();
            }
            self.redundant.retain(|c| *c != constraint);
        }
        if !passed_over.is_subset(&closed) {
            return false;
        }
        self.plan.steps = steps;
        self.plan.regs = regs;
        for (i, s) in self.plan.steps.iter().enumerate() {
            if let Op::Default(d) = s.op {
                if let Some(span) = spans.get_mut(&d.0) {
                    span.0 = span.0.min(i);
                }
            }
        }
        // Regions in step order, overlapping ones merged.
        let mut regions: Vec<(usize, usize, Vec<DefaultId>)> = spans
            .iter()
            .map(|(&d, &(start, end))| (start, end, vec![DefaultId(d)]))
            .collect();
        regions.sort_by_key(|r| r.0);
        let mut merged: Vec<(usize, usize, Vec<DefaultId>)> = Vec::new();
        for (start, end, ds) in regions {
            match merged.last_mut() {
                Some(last) if start < last.1 => {
                    last.1 = last.1.max(end);
                    last.2.extend(ds);
                }
                _ => merged.push((start, end, ds)),
            }
        }
        self.plan.iterations = merged
            .into_iter()
            .map(|(start, end, mut defaults)| {
                defaults.sort_by_key(|d| d.0);
                Iteration {
                    defaults,
                    start,
                    end,
                    // The sketch's, once the plan is run on it (`pipeline::analyse`).
                    mode: None,
                }
            })
            .collect();
        self.guard_iterations();
        true
    }

    /// Guards the iterated regions: every relation of a constraint a region's steps satisfy
    /// is measured again once the plan has run. A region's closing errors hold to the
    /// iteration's tolerance and its other steps construct their relations exactly, so a
    /// guard fails only where a closing error does not measure all that its default
    /// displaced: a wrong plan, then never an answer (in the interpreter and in generated
    /// code alike, as every check).
    fn guard_iterations(&mut self) {
        let mut claimed: BTreeSet<ConstraintId> = BTreeSet::new();
        for it in &self.plan.iterations {
            for s in &self.plan.steps[it.start..it.end] {
                claimed.extend(s.satisfies.iter().copied());
            }
        }
        let guarded: Vec<Rel<G::Relation>> = (self.relations.iter())
            .filter(|r| claimed.contains(&r.constraint))
            .cloned()
            .collect();
        for r in guarded {
            let residual = G::residual(self, &r.relation);
            let explain = format!(
                "Guard: check that {} still holds once the iteration has closed.",
                self.cname(r.constraint)
            );
            self.emit(
                Op::Check {
                    constraint: r.constraint,
                    residual,
                    guard: true,
                },
                None,
                Vec::new(),
                explain,
            );
        }
    }

    /// Declares a default named `name`, meaning `meaning`, whose least-motion value register
    /// `measure` holds when the plan runs on the sketch; returns the register of its value.
    pub(crate) fn default_value(
        &mut self,
        geom: GeomId,
        name: String,
        meaning: String,
        measure: Reg,
    ) -> Reg {
        let id = crate::plan::DefaultId(self.plan.defaults.len() as u32);
        self.plan.defaults.push(crate::plan::DefaultVar {
            name: name.clone(),
            meaning,
            geom: Some(self.model.top_level_of(geom)),
            sketch: 0.0,
            measure: Some(measure),
            assembled: None,
        });
        self.value(Op::Default(id), Ty::Scalar, format!("default `{name}`"))
    }

    /// Action analysis, then locus analysis, until neither applies to any pending relation
    /// (restricted to relations among the clusters `within`, when given).
    fn fixpoint(&mut self, within: Option<&[usize]>) {
        // In effect: repeatedly take the first pending relation (in canonical order) that
        // action analysis satisfies, else the first that locus analysis satisfies. An attempt
        // depends only on the records of the clusters its relation involves, so one that
        // failed without side effects fails again until one of those records changes: it is
        // tried again only then. (A failed attempt that forgot measurements is tried every
        // round, as every attempt used to be, so that it forgets them again.)
        let n = self.pending.len();
        let mut involved: Vec<Vec<usize>> = Vec::with_capacity(n);
        let mut by_cluster: HashMap<usize, Vec<usize>> = HashMap::default();
        // Relations to try, by mode (action, locus).
        let mut dirty: [BTreeSet<usize>; 2] = Default::default();
        for i in 0..n {
            let ks = self.clusters_of(&self.pending[i]);
            let inside = within.is_none_or(|set| ks.iter().all(|k| set.contains(k)));
            if inside {
                for &k in &ks {
                    by_cluster.entry(k).or_default().push(i);
                }
                dirty[0].insert(i);
                dirty[1].insert(i);
            }
            involved.push(ks);
        }
        let mut alive = vec![true; n];
        loop {
            let mut done = None;
            for (mode, locus) in [false, true].into_iter().enumerate() {
                let mut next = 0;
                while let Some(&i) = dirty[mode].range(next..).next() {
                    next = i + 1;
                    let r = self.pending[i].clone();
                    if r.duplicate {
                        // A duplicate never constructs: it is checked once the relation it
                        // repeats is done and its sides are known, and waits until then.
                        if locus || !self.done.contains(&key::<G>(&r.relation)) {
                            continue;
                        }
                        if !G::implied(self, &r.relation) {
                            dirty[mode].remove(&i);
                            continue;
                        }
                    }
                    let before: Vec<G::Record> = involved[i]
                        .iter()
                        .map(|&k| self.clusters[k].record.clone())
                        .collect();
                    let measured = self.measured.len();
                    let cp = self.checkpoint();
                    self.working = Some(r.constraint);
                    let ok = if r.duplicate {
                        self.check(&r);
                        true
                    } else if locus {
                        G::locus(self, &r)
                    } else {
                        G::action(self, &r)
                    };
                    self.working = None;
                    if ok {
                        done = Some((i, before));
                        break;
                    }
                    self.rollback(cp);
                    if self.measured.len() == measured {
                        dirty[mode].remove(&i);
                    }
                }
                if done.is_some() {
                    break;
                }
            }
            let Some((i, before)) = done else { break };
            alive[i] = false;
            self.done.insert(key::<G>(&self.pending[i].relation));
            dirty[0].remove(&i);
            dirty[1].remove(&i);
            for (&k, old) in involved[i].iter().zip(&before) {
                if self.clusters[k].record != *old {
                    for &j in by_cluster.get(&k).into_iter().flatten() {
                        if alive[j] {
                            dirty[0].insert(j);
                            dirty[1].insert(j);
                        }
                    }
                }
            }
        }
        let mut keep = alive.into_iter();
        self.pending.retain(|_| keep.next().unwrap_or(false));
    }

    /// [`Builder::settle_pending`] of every pending relation `settled` says: those a step of
    /// a space's own (a chain closed at once) satisfied.
    pub(crate) fn settle_where(
        &mut self,
        settled: impl Fn(&Rel<G::Relation>) -> bool,
    ) -> Vec<Rel<G::Relation>> {
        let indices: BTreeSet<usize> = (self.pending.iter().enumerate())
            .filter(|(_, r)| settled(r))
            .map(|(i, _)| i)
            .collect();
        self.settle_pending(&indices)
    }

    /// Takes the pending relations at `indices` as satisfied together (by a linear stage):
    /// they leave the pending list, and their keys are done. Returns them.
    pub(crate) fn settle_pending(&mut self, indices: &BTreeSet<usize>) -> Vec<Rel<G::Relation>> {
        let mut taken = Vec::with_capacity(indices.len());
        let mut kept = Vec::with_capacity(self.pending.len());
        for (i, r) in std::mem::take(&mut self.pending).into_iter().enumerate() {
            if indices.contains(&i) {
                self.done.insert(key::<G>(&r.relation));
                taken.push(r);
            } else {
                kept.push(r);
            }
        }
        self.pending = kept;
        taken
    }

    /// Forgets the invariant positions measured of the geoms of cluster `k`: a step a space
    /// writes is about to move it off them (and back).
    pub(crate) fn forget_known(&mut self, k: usize) {
        let model = self.model;
        let geoms = &self.clusters[k].geoms;
        self.known_points
            .retain(|f, _| !geoms.contains(&model.top_level_of(*f)));
    }

    /// Makes cluster `from` part of cluster `into`, which keeps its record: a pair that a
    /// space's step made rigid (a joint whose angle it fixed) moves as one from now on.
    pub(crate) fn merge_clusters(&mut self, into: usize, from: usize) {
        let geoms = std::mem::take(&mut self.clusters[from].geoms);
        for &g in &geoms {
            self.cluster_of[geom_index(g)] = into;
        }
        self.clusters[into].geoms.extend(geoms);
    }

    /// Notes that constraint `c` was constructed (in part) by a step that works for another.
    pub(crate) fn constructed(&mut self, c: ConstraintId) {
        self.constructed.insert(c);
    }

    /// Sets the constraint the steps written next work for.
    pub(crate) fn work_for(&mut self, c: Option<ConstraintId>) {
        self.working = c;
    }

    /// The clusters a relation involves.
    pub(crate) fn clusters_of(&self, r: &Rel<G::Relation>) -> Vec<usize> {
        let mut ks: Vec<usize> = G::features(&r.relation)
            .into_iter()
            .map(|g| self.cluster(g))
            .collect();
        ks.sort_unstable();
        ks.dedup();
        ks
    }

    pub(crate) fn checkpoint(&mut self) -> Checkpoint {
        self.inserted.clear();
        (
            self.plan.steps.len(),
            self.plan.regs,
            self.plan.branches.len(),
        )
    }

    /// Undoes the steps of a failed attempt, and forgets the registers they defined.
    pub(crate) fn rollback(&mut self, (steps, regs, branches): Checkpoint) {
        if self.plan.steps.len() == steps {
            return;
        }
        self.plan.steps.truncate(steps);
        self.plan.regs = regs;
        self.plan.branches.truncate(branches);
        self.def_step.truncate(regs as usize);
        // Every cache entry naming a register defined since the checkpoint was inserted since
        // the checkpoint (checkpoints do not nest).
        let live = |r: Option<&Reg>| r.is_some_and(|r| r.0 < regs);
        for key in std::mem::take(&mut self.inserted) {
            match key {
                Key::Known(f) => {
                    if !live(self.known_points.get(&f)) {
                        self.known_points.remove(&f);
                    }
                }
                Key::Measured(k) => {
                    if !live(self.measured.get(&k)) {
                        self.measured.remove(&k);
                    }
                }
                Key::Expr(e) => {
                    if !live(self.exprs.get(&e)) {
                        self.exprs.remove(&e);
                    }
                }
            }
        }
        self.words.truncate(regs as usize);
        self.centers.split_off(&Reg(regs));
    }

    /// SOLVE-RIGID-CHAINS and SOLVE-LOOP (000, Appendix A.1-A.2): among clusters that are
    /// rigid and still move, find the smallest chain (2 clusters) or loop (up to
    /// [`Geometry::MAX_LOOP`]) whose relations make it rigid, assemble it on one of its
    /// clusters as a temporary ground, and rewrite it as one macro-geom that keeps the
    /// ground's freedom. Candidates are tried in name order, so the choice does not depend on
    /// statement order.
    fn group(&mut self) -> bool {
        // Rigid clusters that still move; a group holds at most one that is partially fixed,
        // and then that one is its temporary ground and gives the macro-geom its record.
        let free: Vec<usize> = (0..self.clusters.len())
            .filter(|&k| {
                let c = &self.clusters[k];
                !c.geoms.is_empty() && !c.record.grounded() && c.record.rigid()
            })
            .collect();
        let mut edges: BTreeSet<(usize, usize)> = Default::default();
        for r in &self.pending {
            if let [x, y] = self.clusters_of(r).as_slice() {
                if free.contains(x) && free.contains(y) {
                    edges.insert((*x, *y));
                }
            }
        }
        // A set's clusters by the place of their first geom's name: the order of their names.
        let key = |s: &Self, set: &[usize]| {
            let mut ranks: Vec<u32> = set
                .iter()
                .map(|&k| s.name_rank[geom_index(s.clusters[k].geoms[0])])
                .collect();
            ranks.sort_unstable();
            ranks
        };
        // Chains first (SOLVE-RIGID-CHAINS), then loops up to the space's limit
        // (IDENTIFY-LOOPS over the free clusters numbered in name order).
        let mut sets: Vec<Vec<usize>> = edges.iter().map(|&(x, y)| vec![x, y]).collect();
        let mut order: Vec<usize> = free.clone();
        order.sort_by_key(|&k| self.name_rank[geom_index(self.clusters[k].geoms[0])]);
        // Each free cluster's neighbours, by place in `order`, in order: from the edges, not
        // by asking every pair (a model with many free clusters asks here after every chain).
        let place: HashMap<usize, usize> = order.iter().enumerate().map(|(j, &k)| (k, j)).collect();
        let mut adj: Vec<Vec<usize>> = vec![Vec::new(); order.len()];
        for &(x, y) in &edges {
            if let (Some(&i), Some(&j)) = (place.get(&x), place.get(&y)) {
                adj[i].push(j);
                adj[j].push(i);
            }
        }
        for next in &mut adj {
            next.sort_unstable();
            next.dedup();
        }
        for l in super::loops::identify_loops(&adj, G::MAX_LOOP) {
            sets.push(l.into_iter().map(|i| order[i]).collect());
        }
        sets.sort_by_cached_key(|s| (s.len(), key(self, s)));
        for set in sets {
            let held: Vec<usize> = set
                .iter()
                .copied()
                .filter(|&k| !self.clusters[k].record.loose())
                .collect();
            let mut grounds = match held.as_slice() {
                [] => set.clone(),
                [one] => vec![*one],
                [first, rest @ ..] if rest.iter().all(|&k| G::share_pivot(self, *first, k)) => {
                    held.clone()
                }
                _ => continue,
            };
            grounds.sort_by_key(|&k| self.name_rank[geom_index(self.clusters[k].geoms[0])]);
            for ground in grounds {
                let mut trial = self.clone();
                if trial.solve_group(&set, ground) {
                    *self = trial;
                    return true;
                }
            }
        }
        false
    }

    fn solve_group(&mut self, set: &[usize], ground: usize) -> bool {
        let saved = self.clusters[ground].record.clone();
        let first_step = self.plan.steps.len();
        self.clusters[ground].record.hold();
        self.fixpoint(Some(set));
        if !set.iter().all(|&k| self.clusters[k].record.grounded()) {
            return false;
        }
        // Rewrite the group as one macro-geom with the ground's record.
        let mut geoms = self.clusters[ground].geoms.clone();
        for &k in set {
            if k != ground {
                geoms.extend(std::mem::take(&mut self.clusters[k].geoms));
            }
        }
        for &g in &geoms {
            self.cluster_of[geom_index(g)] = ground;
        }
        let names: Vec<String> = geoms.iter().map(|&g| self.name(g)).collect();
        if let Some(step) = self.plan.steps[first_step..]
            .iter_mut()
            .find(|s| !s.explain.is_empty())
        {
            step.explain = format!(
                "{} form a rigid {}: hold {} where it is, assemble the others on it, and move \
                 them from now on as one body (a macro-geom).\n   {}",
                names.join(", "),
                if set.len() == 2 { "chain" } else { "loop" },
                names[0],
                step.explain
            );
        }
        self.clusters[ground].geoms = geoms.clone();
        self.clusters[ground].record = saved;
        // Positions measured relative to the temporary ground are not invariant in the world.
        let model = self.model;
        self.known_points
            .retain(|f, _| !geoms.contains(&model.top_level_of(*f)));
        true
    }
}

/// The defaults `step` depends on, traced forward as the plan says what depends on what
/// (`plan/deps.rs`): those of the registers it reads, a default it takes, and those the
/// top-level geom it measures was moved by; recorded for the register it defines and the
/// geoms it moves. Shared by `close_iterations` and `depends_on_default`.
fn trace_defaults(
    model: &Model,
    step: &Step,
    reg_deps: &mut [BTreeSet<u32>],
    geom_deps: &mut HashMap<GeomId, BTreeSet<u32>>,
) -> BTreeSet<u32> {
    let mut deps: BTreeSet<u32> = BTreeSet::new();
    for r in step.op.reads() {
        deps.extend(reg_deps[r.0 as usize].iter().copied());
    }
    if let Op::Default(d) = step.op {
        deps.insert(d.0);
    }
    if let Some(g) = (step.op.measures()).and_then(|f| geom_deps.get(&model.top_level_of(f))) {
        deps.extend(g.iter().copied());
    }
    for g in step.op.moves() {
        geom_deps
            .entry(*g)
            .or_default()
            .extend(deps.iter().copied());
    }
    if let Some((r, _)) = step.out {
        reg_deps[r.0 as usize] = deps.clone();
    }
    deps
}
