//! Degrees-of-freedom analysis of a 2d model into a [`Plan`] (paper 000, sections 3-5 and
//! Appendix A).
//!
//! Every top-level geom starts as a *cluster*: a set of geoms that move together, with an
//! invariants record. Action analysis takes a relation one of whose sides is known ("fixed
//! enough") and moves the other side's cluster with the freedom its record leaves, then updates
//! the record. Locus analysis takes a coincidence between two partially fixed clusters, asks
//! the locus table where each feature can lie, and intersects the two loci (a branch variable).
//! Relations whose both sides are already known become run-time checks.
//!
//! The record of a cluster is kept in the canonical form of a rigid frame in the plane:
//! its rotation ([`Rot`]) and its position ([`Pos`]); [`Record::table2`] gives the slots of
//! Kramer's Table 2 for reports.

pub mod circle;
pub mod loops;
pub mod relation;
pub mod segment;

use crate::config::{Config, V2};
use crate::plan::{BranchId, BranchVar, Meet, Op, Plan, Reg, Step, Ty};
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Space};
use gcs_lang::Model;
use relation::{AngleValue, Dir, Rel, Relation, Unsupported};
use std::collections::{BTreeMap, BTreeSet, HashMap};

/// What a cluster's rotation is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Rot {
    /// Still free (one DOF).
    Free,
    /// Invariant: an invariant vector fixes it.
    Known,
    /// The cluster has no orientation (a point, a circle).
    None,
}

/// A world locus held in a register.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Locus {
    /// A line.
    Line(Reg),
    /// A circle.
    Circle(Reg),
    /// A conic (parabola, ellipse or hyperbola branch) from locus analysis of a circle.
    Conic(Reg),
}

/// What a cluster's position is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pos {
    /// Free to translate (two DOF; one for a line, whose slide along itself is no motion).
    Free,
    /// A feature is on a 1-dimensional locus (one DOF).
    On {
        /// The feature.
        feature: GeomId,
        /// Its locus.
        locus: Locus,
    },
    /// The cluster may only rotate about a known point (an invariant point).
    Pivot {
        /// The pivot's position.
        at: Reg,
        /// The feature at the pivot.
        feature: GeomId,
    },
    /// Position invariant.
    Fixed,
    /// The cluster has no position (a vector).
    None,
}

/// A cluster's invariants record.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// Rotation.
    pub rot: Rot,
    /// Position.
    pub pos: Pos,
    /// The geom with a free dimension (segment length, circle radius), if still free.
    pub free_dim: Option<GeomId>,
    /// Fixed-distance lines and points of a circle whose radius is still free (Table 2's last
    /// slots): each ties its centre to its radius.
    pub fd: Vec<circle::Fd>,
    /// Whether the position is the centre locus those fixed distances make (RR-1 and kin):
    /// then they fix the radius once the centre is placed, and count once, not twice.
    pub fd_locus: bool,
    /// Invariant dimensions.
    pub fixed_dims: Vec<GeomId>,
    /// Whether the cluster is a lone line (its slide along itself is a symmetry).
    pub line: bool,
}

impl Record {
    /// The degrees of freedom the record leaves.
    pub fn dof(&self) -> usize {
        let rot = usize::from(self.rot == Rot::Free);
        let pos = match self.pos {
            Pos::Free if self.line => 1,
            Pos::Free => 2,
            Pos::On { .. } => 1,
            Pos::Pivot { .. } | Pos::Fixed | Pos::None => 0,
        };
        // Each fixed distance ties the free radius to the centre: one DOF less, except those
        // already folded into the centre's locus.
        let tied = if self.fd_locus {
            self.fd.len().saturating_sub(1)
        } else {
            self.fd.len()
        };
        (rot + pos + usize::from(self.free_dim.is_some())).saturating_sub(tied)
    }

    /// Whether nothing about the cluster can move any more.
    pub fn grounded(&self) -> bool {
        self.dof() == 0
    }

    /// The cardinalities of Kramer's Table 2 slots: invariant points, 1D-constrained points,
    /// 2D-constrained points, invariant vectors, 1D-constrained vectors, invariant dimensions,
    /// fixed-distance points, lines and planes.
    pub fn table2(&self) -> [usize; 9] {
        let (inv_pts, pts_1d) = match self.pos {
            Pos::Pivot { .. } => (1, 0),
            Pos::Fixed => (if self.rot == Rot::Known { 2 } else { 1 }, 0),
            Pos::On { .. } => (0, 1),
            _ => (0, 0),
        };
        let inv_vec = usize::from(self.rot == Rot::Known);
        let fd_pts = self.fd.iter().filter(|f| !f.is_line()).count();
        let fd_lines = self.fd.len() - fd_pts;
        [
            inv_pts,
            pts_1d,
            0,
            inv_vec,
            0,
            self.fixed_dims.len(),
            fd_pts,
            fd_lines,
            0,
        ]
    }

    /// The signature as Kramer writes it: `IR[100_10_1_000]`.
    pub fn signature(&self) -> String {
        let t = self.table2();
        format!(
            "IR[{}{}{}_{}{}_{}_{}{}{}]",
            t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8]
        )
    }
}

/// A cluster: geoms moving together, and their record.
#[derive(Clone, Debug, PartialEq)]
pub struct Cluster {
    /// The top-level geoms.
    pub geoms: Vec<GeomId>,
    /// The record.
    pub record: Record,
}

/// The outcome of the analysis.
#[derive(Clone, Debug)]
pub struct Analysis {
    /// The plan.
    pub plan: Plan,
    /// Every cluster at the end, with its record.
    pub clusters: Vec<Cluster>,
    /// Relations no fragment could satisfy, by constraint, with the reason.
    pub unsolved: Vec<Unsupported>,
    /// Constraints that are implied by others (kept as run-time checks).
    pub redundant: Vec<ConstraintId>,
}

impl Analysis {
    /// The DOF left on each top-level geom's cluster, for geoms not grounded.
    pub fn free_geoms(&self) -> Vec<(GeomId, usize)> {
        let mut out = Vec::new();
        for c in &self.clusters {
            let dof = c.record.dof();
            if dof > 0 {
                for &g in &c.geoms {
                    out.push((g, dof));
                }
            }
        }
        out
    }
}

/// Analyses a 2d model. Fails only for models outside the analysis (3d for now): every 2d model
/// gets a plan, with whatever it cannot solve reported in [`Analysis::unsolved`].
pub fn analyse(model: &Model) -> Result<Analysis, String> {
    if model.space != Space::D2 {
        return Err(
            "the degrees-of-freedom analysis covers 2d models; 3d lands with the 3d issue".into(),
        );
    }
    let params = model.default_params();
    let sketch = Config::from_sketch(model, &params).map_err(|b| {
        format!(
            "the sketch of `{}` is invalid: {}",
            model.geoms[b.geom].name, b.what
        )
    })?;
    let view = SketchOf {
        model,
        config: &sketch,
    };
    let (mut rels, unsupported) = relation::decompose(model, &view);
    // Canonical order: by constraint name, then relation order within the constraint, so that
    // the plan does not depend on the order of statements.
    rels.sort_by(|a, b| {
        model.constraints[a.constraint]
            .name
            .cmp(&model.constraints[b.constraint].name)
    });
    let mut b = Builder::new(model);
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
    b.calibrate_branches();
    Ok(Analysis {
        plan: b.plan,
        clusters: b.clusters,
        unsolved,
        redundant: b.redundant,
    })
}

/// The sketch configuration, as the decomposition sees it.
struct SketchOf<'a> {
    model: &'a Model,
    config: &'a Config,
}

impl relation::SketchView for SketchOf<'_> {
    fn angle(&self, u: Dir, v: Dir) -> f64 {
        let d = |x: Dir| match x {
            Dir::Feature(g) => self.config.dir(self.model, g),
            Dir::World(x, y) => V2::new(x, y),
        };
        let (a, b) = (d(u), d(v));
        (a.x * b.y - a.y * b.x).atan2(a.dot(&b))
    }
    fn point(&self, p: GeomId) -> [f64; 2] {
        let q = self.config.point(self.model, p);
        [q.x, q.y]
    }
    fn dir(&self, v: GeomId) -> [f64; 2] {
        let d = self.config.dir(self.model, v);
        [d.x, d.y]
    }
    fn radius(&self, c: GeomId) -> f64 {
        self.config.dim(c)
    }
}

/// A target for a feature: a point or a locus.
#[derive(Clone, Copy, Debug)]
enum Target {
    Point(Reg),
    On(Locus),
}

/// A key of one of the builder's register caches.
#[derive(Clone, Copy, Debug)]
enum Key {
    Known(GeomId),
    Measured((GeomId, bool)),
    Expr(gcs_lang::expr::ExprId),
}

#[derive(Clone)]
struct Builder<'m> {
    model: &'m Model,
    plan: Plan,
    clusters: Vec<Cluster>,
    cluster_of: HashMap<GeomId, usize>,
    /// Registers holding invariant positions, reused once measured.
    known_points: HashMap<GeomId, Reg>,
    /// Registers holding current positions and directions, valid until their cluster moves.
    measured: HashMap<(GeomId, bool), Reg>,
    /// The keys of `measured` by top-level geom (a superset: keys may have gone since), so
    /// that an action forgets what it invalidates without scanning every measurement.
    measured_by_top: HashMap<GeomId, Vec<(GeomId, bool)>>,
    /// The centre of each circle register, in words, for branch meanings.
    centers: BTreeMap<Reg, String>,
    exprs: HashMap<gcs_lang::expr::ExprId, Reg>,
    /// Words for registers, to write explanations and branch meanings.
    words: BTreeMap<Reg, String>,
    /// The keys inserted into `known_points`, `measured` and `exprs` since the last
    /// checkpoint, so that a rollback forgets them without scanning the maps.
    inserted: Vec<Key>,
    /// The step defining each register, by register number.
    def_step: Vec<usize>,
    pending: Vec<Rel>,
    redundant: Vec<ConstraintId>,
}

impl<'m> Builder<'m> {
    fn new(model: &'m Model) -> Self {
        let mut clusters = Vec::new();
        let mut cluster_of = HashMap::new();
        for (id, g) in model.top_level() {
            let (rot, pos) = match g.kind {
                GeomKind::Point | GeomKind::Circle => (Rot::None, Pos::Free),
                GeomKind::Vector => (Rot::Free, Pos::None),
                _ => (Rot::Free, Pos::Free),
            };
            let free_dim = matches!(g.kind, GeomKind::Segment | GeomKind::Circle).then_some(id);
            let mut record = Record {
                rot,
                pos,
                free_dim,
                fd: Vec::new(),
                fd_locus: false,
                fixed_dims: Vec::new(),
                line: g.kind == GeomKind::Line,
            };
            if g.fixed {
                record.rot = if rot == Rot::Free { Rot::Known } else { rot };
                record.pos = if pos == Pos::None {
                    Pos::None
                } else {
                    Pos::Fixed
                };
                if let Some(d) = record.free_dim.take() {
                    record.fixed_dims.push(d);
                }
            }
            cluster_of.insert(id, clusters.len());
            clusters.push(Cluster {
                geoms: vec![id],
                record,
            });
        }
        Builder {
            model,
            plan: Plan::default(),
            clusters,
            cluster_of,
            known_points: HashMap::new(),
            measured: HashMap::new(),
            measured_by_top: HashMap::new(),
            centers: BTreeMap::new(),
            exprs: HashMap::new(),
            words: BTreeMap::new(),
            inserted: Vec::new(),
            def_step: Vec::new(),
            pending: Vec::new(),
            redundant: Vec::new(),
        }
    }

    // ------------------------------------------------------------ emitting

    fn emit(
        &mut self,
        op: Op,
        ty: Option<Ty>,
        satisfies: Vec<ConstraintId>,
        explain: String,
    ) -> Reg {
        // An action invalidates what was measured on the geoms it moves.
        if let Op::Translate { geoms, .. }
        | Op::RotatePoint { geoms, .. }
        | Op::RotateDir { geoms, .. } = &op
        {
            let moved: Vec<GeomId> = geoms.clone();
            for g in moved {
                self.forget_measured(g);
            }
        }
        if let Op::SetDim { geom, .. } = &op {
            let g = *geom;
            self.forget_measured(g);
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
            explain,
        });
        reg
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

    fn insert_known(&mut self, f: GeomId, r: Reg) {
        self.known_points.insert(f, r);
        self.inserted.push(Key::Known(f));
    }

    /// The step that defines register `r`.
    fn def(&self, r: Reg) -> Option<&Step> {
        self.def_step
            .get(r.0 as usize)
            .and_then(|&i| self.plan.steps.get(i))
    }

    fn value(&mut self, op: Op, ty: Ty, words: String) -> Reg {
        let r = self.emit(op, Some(ty), Vec::new(), String::new());
        self.words.insert(r, words);
        r
    }

    fn word(&self, r: Reg) -> String {
        self.words
            .get(&r)
            .cloned()
            .unwrap_or_else(|| format!("r{}", r.0))
    }

    /// A cluster's geoms as the subject of a sentence: `crank`, or `link10 (with link7, link8)`.
    fn group_name(&self, geoms: &[GeomId]) -> String {
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

    fn name(&self, g: GeomId) -> String {
        self.model.geoms[g].name.clone()
    }

    fn cname(&self, c: ConstraintId) -> String {
        let c = &self.model.constraints[c];
        match &c.label {
            Some(l) => format!("{l}: {}", c.text),
            None => c.text.clone(),
        }
    }

    fn expr(&mut self, e: gcs_lang::expr::ExprId) -> Reg {
        if let Some(r) = self.exprs.get(&e) {
            return *r;
        }
        let text = crate::plan::expr_text(self.model, e);
        let r = self.value(Op::Expr(e), Ty::Scalar, text);
        self.exprs.insert(e, r);
        self.inserted.push(Key::Expr(e));
        r
    }

    /// The current position of a point feature (re-measured unless invariant).
    fn point(&mut self, f: GeomId) -> Reg {
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

    fn dir(&mut self, d: Dir) -> Reg {
        match d {
            Dir::Feature(g) => {
                if let Some(r) = self.measured.get(&(g, false)) {
                    return *r;
                }
                let words = self.name(g);
                let r = self.value(Op::DirOf(g), Ty::Vector, words);
                self.insert_measured((g, false), r);
                r
            }
            Dir::World(x, y) => {
                let words = if x != 0.0 { "the X axis" } else { "the Y axis" }.to_string();
                self.value(Op::Axis(x, y), Ty::Vector, words)
            }
        }
    }

    // ------------------------------------------------------------ knowledge

    fn cluster(&self, g: GeomId) -> usize {
        let top = self.model.top_level_of(g);
        self.cluster_of.get(&top).copied().unwrap_or(0)
    }

    fn record(&self, g: GeomId) -> &Record {
        &self.clusters[self.cluster(g)].record
    }

    fn point_known(&self, f: GeomId) -> bool {
        let r = self.record(f);
        r.grounded()
            || matches!(r.pos, Pos::Pivot { feature, .. } if feature == f)
            || (r.pos == Pos::Fixed && r.rot != Rot::Free && !depends_on_dim(self.model, f))
    }

    /// A known point on the line of (`base`, its direction): `base` itself, or the other end
    /// of the same segment.
    pub(super) fn line_point(&self, base: GeomId) -> Option<GeomId> {
        if self.point_known(base) {
            return Some(base);
        }
        match self.model.geoms[base].owner {
            gcs_lang::model::Owner::Part(s, gcs_lang::model::Part::Start) => {
                relation::part(self.model, s, gcs_lang::model::Part::End)
                    .filter(|&e| self.point_known(e))
            }
            _ => None,
        }
    }

    fn dir_known(&self, d: Dir) -> bool {
        match d {
            Dir::World(..) => true,
            Dir::Feature(g) => matches!(self.record(g).rot, Rot::Known | Rot::None),
        }
    }

    // ------------------------------------------------------------ the driver

    fn run(&mut self, rels: Vec<Rel>) {
        // Unary constraints first (Appendix A.3): dimensions.
        let (dims, others): (Vec<Rel>, Vec<Rel>) = rels
            .into_iter()
            .partition(|r| matches!(r.relation, Relation::Dim { .. }));
        for r in dims {
            self.dimension(&r);
        }
        self.pending = others;
        self.ground_if_nothing_fixed();
        // POSITION-ANALYSIS (000, Appendix A.3): action and locus analysis until stuck; then
        // the smallest rigid chain or loop is assembled on a temporary ground and rewritten as
        // a macro-geom; repeat.
        loop {
            self.fixpoint(None);
            if self.pending.is_empty() || !self.group() {
                break;
            }
        }
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
        let mut by_cluster: HashMap<usize, Vec<usize>> = HashMap::new();
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
                    let before: Vec<Record> = involved[i]
                        .iter()
                        .map(|&k| self.clusters[k].record.clone())
                        .collect();
                    let measured = self.measured.len();
                    let cp = self.checkpoint();
                    let ok = if locus {
                        self.locus(&r)
                    } else {
                        self.action(&r)
                    };
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

    /// The clusters a relation involves.
    fn clusters_of(&self, r: &Rel) -> Vec<usize> {
        let mut gs: Vec<GeomId> = Vec::new();
        match &r.relation {
            Relation::PointPoint { a, b, .. } => gs.extend([*a, *b]),
            Relation::PointLine { p, base, dir, .. } => gs.extend([*p, *base, *dir]),
            Relation::Angle { u, v, .. } => {
                for d in [u, v] {
                    if let Dir::Feature(g) = d {
                        gs.push(*g);
                    }
                }
            }
            Relation::Dim { geom, .. } => gs.push(*geom),
            Relation::CircleLine {
                circle, base, dir, ..
            } => gs.extend([*circle, *base, *dir]),
            Relation::PointCircle { p, circle, .. } => gs.extend([*p, *circle]),
            Relation::CircleCircle { a, b, .. } => gs.extend([*a, *b]),
        }
        let mut ks: Vec<usize> = gs.into_iter().map(|g| self.cluster(g)).collect();
        ks.sort_unstable();
        ks.dedup();
        ks
    }

    fn checkpoint(&mut self) -> (usize, u32, usize) {
        self.inserted.clear();
        (
            self.plan.steps.len(),
            self.plan.regs,
            self.plan.branches.len(),
        )
    }

    /// Undoes the steps of a failed attempt, and forgets the registers they defined.
    fn rollback(&mut self, (steps, regs, branches): (usize, u32, usize)) {
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
        self.words.split_off(&Reg(regs));
        self.centers.split_off(&Reg(regs));
    }

    /// SOLVE-RIGID-CHAINS and SOLVE-LOOP (000, Appendix A.1-A.2): among clusters that are
    /// entirely free, find the smallest chain (2 clusters) or loop (3, the limit in the plane)
    /// whose relations make it rigid, assemble it on one of its clusters as a temporary
    /// ground, and rewrite it as one macro-geom that keeps the ground's freedom. Candidates are
    /// tried in name order, so the choice does not depend on statement order.
    fn group(&mut self) -> bool {
        // Rigid clusters that still move; a group holds at most one that is partially fixed,
        // and then that one is its temporary ground and gives the macro-geom its record.
        let free: Vec<usize> = (0..self.clusters.len())
            .filter(|&k| {
                let c = &self.clusters[k];
                !c.geoms.is_empty()
                    && !c.record.grounded()
                    && c.record.free_dim.is_none()
                    && c.record.fd.is_empty()
            })
            .collect();
        let loose = |s: &Self, k: usize| {
            let r = &s.clusters[k].record;
            matches!(r.rot, Rot::Free | Rot::None) && r.pos == Pos::Free
        };
        let mut edges: std::collections::BTreeSet<(usize, usize)> = Default::default();
        for r in &self.pending {
            if let [x, y] = self.clusters_of(r).as_slice() {
                if free.contains(x) && free.contains(y) {
                    edges.insert((*x, *y));
                }
            }
        }
        let linked = |x: usize, y: usize| edges.contains(&(x.min(y), x.max(y)));
        let key = |s: &Self, set: &[usize]| {
            let mut names: Vec<String> = set
                .iter()
                .map(|&k| s.name(s.clusters[k].geoms[0]))
                .collect();
            names.sort();
            names
        };
        // Chains first (SOLVE-RIGID-CHAINS), then loops of up to three clusters, the limit in
        // the plane (IDENTIFY-LOOPS over the free clusters numbered in name order).
        let mut sets: Vec<Vec<usize>> = edges.iter().map(|&(x, y)| vec![x, y]).collect();
        let mut order: Vec<usize> = free.clone();
        order.sort_by_key(|&k| self.name(self.clusters[k].geoms[0]));
        let adj: Vec<Vec<usize>> = order
            .iter()
            .map(|&x| (0..order.len()).filter(|&j| linked(x, order[j])).collect())
            .collect();
        for l in loops::identify_loops(&adj, 3) {
            sets.push(l.into_iter().map(|i| order[i]).collect());
        }
        sets.sort_by_key(|s| (s.len(), key(self, s)));
        for set in sets {
            let held: Vec<usize> = set.iter().copied().filter(|&k| !loose(self, k)).collect();
            let mut grounds = match held.as_slice() {
                [] => set.clone(),
                [one] => vec![*one],
                _ => continue,
            };
            grounds.sort_by_key(|&k| self.name(self.clusters[k].geoms[0]));
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
        {
            let rec = &mut self.clusters[ground].record;
            if rec.rot == Rot::Free {
                rec.rot = Rot::Known;
            }
            if rec.pos != Pos::None {
                rec.pos = Pos::Fixed;
            }
        }
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
            self.cluster_of.insert(g, ground);
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

    fn ground_if_nothing_fixed(&mut self) {
        if self.model.top_level().any(|(_, g)| g.fixed) || self.clusters.is_empty() {
            return;
        }
        // Deterministically: the geom with the most DOF, then the first name.
        let mut best: Option<(usize, String, usize)> = None;
        for (i, c) in self.clusters.iter().enumerate() {
            let key = (c.record.dof(), self.model.geoms[c.geoms[0]].name.clone());
            if best
                .as_ref()
                .is_none_or(|b| key.0 > b.0 || (key.0 == b.0 && key.1 < b.1))
            {
                best = Some((key.0, key.1, i));
            }
        }
        // Horizontal and vertical constraints refer to the world's axes: they anchor the
        // rotation, so only the position of the chosen geom is held.
        let anchored = self.pending.iter().any(|r| {
            matches!(
                r.relation,
                Relation::Angle {
                    u: Dir::World(..),
                    ..
                } | Relation::Angle {
                    v: Dir::World(..),
                    ..
                }
            )
        });
        if let Some((_, _, i)) = best {
            if anchored && self.clusters[i].record.rot == Rot::Free {
                if let Some(f) = self.first_point_feature(i) {
                    let at = self.point(f);
                    self.clusters[i].record.pos = Pos::Pivot { at, feature: f };
                    self.insert_known(f, at);
                    self.plan.grounded = Some(self.clusters[i].geoms[0]);
                    return;
                }
            }
            let had_rotation = self.clusters[i].record.rot == Rot::Free;
            let r = &mut self.clusters[i].record;
            if r.rot == Rot::Free {
                r.rot = Rot::Known;
            }
            if r.pos != Pos::None {
                r.pos = Pos::Fixed;
            }
            self.plan.grounded = Some(self.clusters[i].geoms[0]);
            if !had_rotation {
                self.ground_direction(i);
            }
        }
    }

    /// The first point feature of a cluster: a line's base, a segment's start, a body's first
    /// point or marker.
    fn first_point_feature(&self, k: usize) -> Option<GeomId> {
        let g = *self.clusters[k].geoms.first()?;
        match self.model.geoms[g].kind {
            GeomKind::Line | GeomKind::Point => Some(g),
            GeomKind::Segment => relation::part(self.model, g, gcs_lang::model::Part::Start),
            GeomKind::Circle => relation::part(self.model, g, gcs_lang::model::Part::Center),
            GeomKind::Body => self.model.geoms[g]
                .parts
                .iter()
                .copied()
                .find(|&m| self.model.geoms[m].kind.is_pointlike()),
            _ => None,
        }
    }

    /// A geom without orientation (a point, a circle) held at its sketch leaves the model free
    /// to turn about it: hold the direction to the first point related to it (in name order)
    /// as the sketch has it too, so that the model is solved up to a rigid motion only.
    fn ground_direction(&mut self, i: usize) {
        let held = |s: &Self, f: GeomId| s.cluster(f) == i;
        let mut pair = None;
        for r in &self.pending {
            if let Relation::PointPoint { a, b, .. } = r.relation {
                let (ka, kb) = (self.cluster(a), self.cluster(b));
                if held(self, a) && kb != i && self.clusters[kb].record.pos == Pos::Free {
                    pair = Some((a, b));
                } else if held(self, b) && ka != i && self.clusters[ka].record.pos == Pos::Free {
                    pair = Some((b, a));
                }
                if pair.is_some() {
                    break;
                }
            }
        }
        let Some((at, other)) = pair else { return };
        let a = self.point(at);
        let o = self.point(other);
        let words = format!(
            "the direction from {} to {} in the sketch",
            self.name(at),
            self.name(other)
        );
        let d = self.value(Op::DirectionTo { from: a, to: o }, Ty::Vector, words);
        let words = format!(
            "the line from {} through {} as sketched",
            self.name(at),
            self.name(other)
        );
        let line = self.value(
            Op::Line {
                point: a,
                dir: d,
                offset: None,
            },
            Ty::Line,
            words,
        );
        let k = self.cluster(other);
        self.clusters[k].record.pos = Pos::On {
            feature: other,
            locus: Locus::Line(line),
        };
        self.plan.grounded_direction = Some((at, other));
    }

    fn satisfies(&self, r: &Rel) -> Vec<ConstraintId> {
        if r.last {
            vec![r.constraint]
        } else {
            Vec::new()
        }
    }

    /// A relation already implied: a run-time check of its constraint (once, on its last
    /// relation).
    fn check(&mut self, r: &Rel) {
        if r.last {
            let explain = format!(
                "Check that {} holds: it is implied by the steps before.",
                self.cname(r.constraint)
            );
            self.emit(
                Op::Check {
                    constraint: r.constraint,
                },
                None,
                vec![r.constraint],
                explain,
            );
            self.redundant.push(r.constraint);
        }
    }

    fn dimension(&mut self, r: &Rel) {
        let Relation::Dim { geom, value } = r.relation else {
            return;
        };
        let k = self.cluster(geom);
        if self.clusters[k].record.free_dim == Some(geom) {
            let v = self.expr(value);
            let what = if self.model.geoms[geom].kind == GeomKind::Circle {
                "radius"
            } else {
                "length"
            };
            let explain = format!(
                "Scale {} so that its {what} is {} ({}). This fixes its dimension.",
                self.name(geom),
                self.word(v),
                self.cname(r.constraint)
            );
            self.emit(
                Op::SetDim { geom, value: v },
                None,
                self.satisfies(r),
                explain,
            );
            let rec = &mut self.clusters[k].record;
            rec.free_dim = None;
            rec.fixed_dims.push(geom);
        } else {
            self.check(r);
        }
    }

    // ------------------------------------------------------------ action analysis

    /// Action analysis: one side known enough, the other side moved. Returns whether the
    /// relation was satisfied (or became a check).
    fn action(&mut self, r: &Rel) -> bool {
        match r.relation.clone() {
            Relation::PointPoint { a, b, d } => {
                let (ka, kb) = (self.point_known(a), self.point_known(b));
                if ka && kb
                    || (self.cluster(a) == self.cluster(b)
                        && self.clusters[self.cluster(a)].record.free_dim.is_none())
                {
                    self.check(r);
                    return true;
                }
                let (known, free) = match (ka, kb) {
                    (true, false) => (a, b),
                    (false, true) => (b, a),
                    _ => return false,
                };
                let at = self.point(known);
                let target = match d {
                    None => Target::Point(at),
                    Some(d) => {
                        let radius = self.expr(d);
                        let words = format!(
                            "the circle of radius {} about {}",
                            self.word(radius),
                            self.word(at)
                        );
                        let c = self.value(Op::Circle { center: at, radius }, Ty::Circle, words);
                        self.centers.insert(c, self.word(at));
                        Target::On(Locus::Circle(c))
                    }
                };
                self.move_feature(free, target, r)
            }
            Relation::PointLine { p, base, dir, d } => {
                let on_line = self.line_point(base);
                let line_known = on_line.is_some() && self.dir_known(Dir::Feature(dir));
                let base = on_line.unwrap_or(base);
                let p_known = self.point_known(p);
                if line_known && p_known {
                    self.check(r);
                    return true;
                }
                if self.cluster(p) == self.cluster(base) {
                    // Within one rigid cluster the relation is fixed: implied (a check).
                    if self.clusters[self.cluster(p)].record.free_dim.is_none() {
                        self.check(r);
                        return true;
                    }
                    return false;
                }
                if line_known {
                    let bp = self.point(base);
                    let dv = self.dir(Dir::Feature(dir));
                    let offset = d.map(|d| self.expr(d));
                    let words = match offset {
                        Some(o) => format!(
                            "the line along {} at distance {} from {}",
                            self.name(dir),
                            self.word(o),
                            self.name(base)
                        ),
                        None => format!(
                            "the line through {} along {}",
                            self.name(base),
                            self.name(dir)
                        ),
                    };
                    let line = self.value(
                        Op::Line {
                            point: bp,
                            dir: dv,
                            offset,
                        },
                        Ty::Line,
                        words,
                    );
                    return self.move_feature(p, Target::On(Locus::Line(line)), r);
                }
                if p_known {
                    let d = d.map(|d| self.expr(d));
                    return self.move_line_to_point(p, base, dir, d, r);
                }
                false
            }
            Relation::Angle { u, v, angle } => {
                let (ku, kv) = (self.dir_known(u), self.dir_known(v));
                if ku && kv
                    || matches!((u, v), (Dir::Feature(x), Dir::Feature(y)) if self.cluster(x) == self.cluster(y))
                {
                    self.check(r);
                    return true;
                }
                let a = match angle {
                    AngleValue::Expr(e) => self.expr(e),
                    AngleValue::Const(c) => self.value(Op::Const(c), Ty::Scalar, angle_words(c)),
                };
                match (ku, kv, u, v) {
                    (true, false, _, Dir::Feature(fv)) if angle == AngleValue::Const(0.0) => {
                        let base = self.dir(u);
                        self.turn(fv, base, r)
                    }
                    (false, true, Dir::Feature(fu), _) if angle == AngleValue::Const(0.0) => {
                        let base = self.dir(v);
                        self.turn(fu, base, r)
                    }
                    (true, false, _, Dir::Feature(fv)) => {
                        let base = self.dir(u);
                        let words = format!("{} turned by {}", self.word(base), self.word(a));
                        let target = self.value(
                            Op::Rotated {
                                dir: base,
                                angle: a,
                            },
                            Ty::Vector,
                            words,
                        );
                        self.turn(fv, target, r)
                    }
                    (false, true, Dir::Feature(fu), _) => {
                        let base = self.dir(v);
                        let words = format!("{} turned back by {}", self.word(base), self.word(a));
                        let minus = self.neg(a);
                        let target = self.value(
                            Op::Rotated {
                                dir: base,
                                angle: minus,
                            },
                            Ty::Vector,
                            words,
                        );
                        self.turn(fu, target, r)
                    }
                    _ => false,
                }
            }
            Relation::Dim { .. } => {
                self.dimension(r);
                true
            }
            Relation::PointCircle { .. }
            | Relation::CircleLine { .. }
            | Relation::CircleCircle { .. } => self.circle_relation(r),
        }
    }

    fn neg(&mut self, a: Reg) -> Reg {
        let words = format!("-{}", self.word(a));
        self.value(Op::Neg(a), Ty::Scalar, words)
    }

    /// Moves the cluster of feature `f` so that `f` meets `target`, with the freedom its record
    /// leaves (the plan fragment table for a rigid frame in the plane).
    pub(super) fn move_feature(&mut self, f: GeomId, target: Target, r: &Rel) -> bool {
        let k = self.cluster(f);
        if let Some(done) = self.segment_fragment(f, target, r) {
            return done;
        }
        if self.clusters[k].record.free_dim.is_some() && depends_on_dim(self.model, f) {
            // The feature moves with the free dimension: wait until it is fixed.
            return false;
        }
        let moved = self.move_feature_rigidly(f, target, r);
        if moved {
            self.settle(k);
        }
        moved
    }

    /// The fragments of a rigid frame in the plane (the free dimension, if any, does not move
    /// `f`).
    fn move_feature_rigidly(&mut self, f: GeomId, target: Target, r: &Rel) -> bool {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        let fname = self.name(f);
        match (rec.pos, target) {
            (Pos::Free, Target::Point(x)) => {
                let from = self.point(f);
                let explain = format!(
                    "{names} is free to translate: translate it so that {fname} lands on {} ({c}).",
                    self.word(x)
                );
                self.emit(
                    Op::Translate { geoms, from, to: x },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.pos = if rec.rot == Rot::Free {
                    Pos::Pivot { at: x, feature: f }
                } else {
                    Pos::Fixed
                };
                if rec.pos == Pos::Fixed {
                    rec.rot = if rec.rot == Rot::None {
                        Rot::None
                    } else {
                        Rot::Known
                    };
                }
                self.insert_known(f, x);
                true
            }
            (Pos::Free, Target::On(locus)) => {
                let from = self.point(f);
                let lreg = locus_reg(locus);
                let to = self.value(
                    Op::Nearest {
                        locus: lreg,
                        point: from,
                    },
                    Ty::Point,
                    format!("the point of {} nearest {fname}", self.word(lreg)),
                );
                let explain = format!(
                    "{names} is free to translate: translate it by the least motion that puts {fname} on {} ({c}).",
                    self.word(lreg)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                if rec.line {
                    // A line through a point of a locus: with its direction known it is fixed.
                    rec.pos = if rec.rot == Rot::Known {
                        Pos::Fixed
                    } else {
                        Pos::Pivot { at: to, feature: f }
                    };
                    if rec.pos == Pos::Fixed {
                        return true;
                    }
                    self.insert_known(f, to);
                } else {
                    rec.pos = Pos::On { feature: f, locus };
                }
                true
            }
            (
                Pos::On {
                    feature: g,
                    locus: lg,
                },
                target,
            ) if rec.rot != Rot::Free => {
                // Translation along the locus: f moves on the locus shifted by f - g.
                let from = self.point(f);
                let own = if g == f {
                    locus_reg(lg)
                } else {
                    self.shifted(lg, g, f)
                };
                let to = self.meet(own, target, from, r);
                let explain = format!(
                    "{names} can only slide so that {} stays on {}: move it so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(locus_reg(lg)),
                    self.word(to)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Fixed;
                true
            }
            (
                Pos::On {
                    feature: g,
                    locus: lg,
                },
                target,
            ) if g == f => {
                // Rotation free, f already on a locus: put it at the locus' meeting point.
                let from = self.point(f);
                let to = self.meet(locus_reg(lg), target, from, r);
                let explain = format!(
                    "{fname} must stay on {}: translate {names} so that it reaches {} ({c}); {names} may still rotate about it.",
                    self.word(locus_reg(lg)),
                    self.word(to)
                );
                self.emit(
                    Op::Translate { geoms, from, to },
                    None,
                    self.satisfies(r),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Pivot { at: to, feature: f };
                self.insert_known(f, to);
                true
            }
            (Pos::Pivot { at, feature: g }, target) if g != f => {
                let from = self.point(f);
                let own = self.circle_through(at, from, f, g);
                let to = self.meet(own, target, from, r);
                let explain = format!(
                    "{names} may only rotate about {} ({}): rotate it so that {fname} reaches {} ({c}).",
                    self.name(g),
                    self.word(at),
                    self.word(to)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        from,
                        to,
                    },
                    None,
                    self.satisfies(r),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.pos = Pos::Fixed;
                rec.rot = Rot::Known;
                true
            }
            _ => false,
        }
    }

    /// The circle about `at` through the current position `from` of feature `f`.
    fn circle_through(&mut self, at: Reg, from: Reg, f: GeomId, pivot: GeomId) -> Reg {
        // Both on one rigid geom: the radius is their distance in it.
        let rigid =
            (self.model.top_level_of(pivot) == self.model.top_level_of(f)).then_some((pivot, f));
        let words = format!(
            "the circle about {} through {}",
            self.word(at),
            self.name(f)
        );
        let c = self.value(
            Op::CircleThrough {
                center: at,
                through: from,
                rigid,
            },
            Ty::Circle,
            words,
        );
        self.centers.insert(c, self.word(at));
        c
    }

    /// The locus `lg` (of feature `g`) moved by `f - g`: where `f` goes when the cluster
    /// translates keeping `g` on `lg`.
    fn shifted(&mut self, lg: Locus, g: GeomId, f: GeomId) -> Reg {
        let pg = self.point(g);
        let pf = self.point(f);
        let fname = self.name(f);
        match lg {
            Locus::Line(l) => {
                let words = format!("the parallel to {} through {fname}", self.word(l));
                self.value(
                    Op::ParallelLine {
                        line: l,
                        through: pf,
                    },
                    Ty::Line,
                    words,
                )
            }
            // Only a circle's own centre rides on a conic: nothing else of it to shift.
            Locus::Conic(c) => c,
            Locus::Circle(c) => {
                let words = format!("{} moved with {fname}", self.word(c));
                self.value(
                    Op::ShiftedCircle {
                        circle: c,
                        from: pg,
                        to: pf,
                    },
                    Ty::Circle,
                    words,
                )
            }
        }
    }

    /// Where a feature moving on `own` meets `target`: an intersection (a branch variable), or
    /// the target point itself, which must lie on `own`.
    fn meet(&mut self, own: Reg, target: Target, near: Reg, r: &Rel) -> Reg {
        match target {
            Target::Point(x) => {
                let words = self.word(x);
                self.value(
                    Op::Onto {
                        locus: own,
                        point: x,
                        constraint: r.constraint,
                    },
                    Ty::Point,
                    words,
                )
            }
            Target::On(locus) => {
                let other = locus_reg(locus);
                let own_ty = self.ty(own);
                let (meet, a, b) = match (own_ty, locus) {
                    (Ty::Circle, Locus::Circle(c)) => (Meet::CircleCircle, own, c),
                    (Ty::Circle, Locus::Line(l)) => (Meet::LineCircle, l, own),
                    (Ty::Line, Locus::Circle(c)) => (Meet::LineCircle, own, c),
                    (Ty::Circle, Locus::Conic(q)) => (Meet::CircleConic, own, q),
                    (Ty::Line, Locus::Conic(q)) => (Meet::LineConic, own, q),
                    (Ty::Conic, Locus::Circle(c)) => (Meet::CircleConic, c, own),
                    (Ty::Conic, Locus::Line(l)) => (Meet::LineConic, l, own),
                    _ => (Meet::LineLine, own, other),
                };
                self.intersect(meet, a, b, near, r.constraint)
            }
        }
    }

    fn ty(&self, r: Reg) -> Ty {
        self.def(r)
            .and_then(|s| s.out.filter(|o| o.0 == r).map(|o| o.1))
            .unwrap_or(Ty::Scalar)
    }

    fn intersect(
        &mut self,
        meet: Meet,
        a: Reg,
        b: Reg,
        near: Reg,
        constraint: ConstraintId,
    ) -> Reg {
        let name = self.model.constraints[constraint].name.clone();
        let (wa, wb, wn) = (self.word(a), self.word(b), self.word(near));
        let centre = |s: &Self, r: Reg| {
            s.centers
                .get(&r)
                .cloned()
                .unwrap_or_else(|| format!("the centre of {}", s.word(r)))
        };
        let (ca, cb) = (centre(self, a), centre(self, b));
        let (count, meanings) = match meet {
            Meet::CircleCircle => (
                2,
                vec![
                    format!("{wn} to the left of the line from {ca} to {cb}"),
                    format!("{wn} to the right of the line from {ca} to {cb}"),
                ],
            ),
            Meet::LineCircle => (
                2,
                vec![
                    format!("the first crossing of {wa} with {wb}, along the line"),
                    "the second crossing, along the line".to_string(),
                ],
            ),
            Meet::LineLine => (1, vec![format!("the crossing of {wa} and {wb}")]),
            Meet::CircleConic => (
                4,
                (0..4)
                    .map(|i| format!("root {i} in increasing parameter along {wb}"))
                    .collect(),
            ),
            Meet::LineConic => (
                2,
                vec![
                    format!("the first crossing of {wa} with {wb}, along the line"),
                    "the second crossing, along the line".to_string(),
                ],
            ),
        };
        let branch = if count > 1 {
            let id = BranchId(self.plan.branches.len() as u32);
            self.plan.branches.push(BranchVar {
                name: name.clone(),
                constraint,
                count,
                meanings,
                default: 0,
            });
            id
        } else {
            // A single root still declares its (trivial) branch so every intersection is named.
            let id = BranchId(self.plan.branches.len() as u32);
            self.plan.branches.push(BranchVar {
                name: name.clone(),
                constraint,
                count,
                meanings,
                default: 0,
            });
            id
        };
        let words = format!("the meeting point of {wa} and {wb}");
        self.value(
            Op::Intersect {
                meet,
                a,
                b,
                branch,
                constraint,
                near,
            },
            Ty::Point,
            words,
        )
    }

    /// Turns the cluster of direction feature `v` so that it points along `target`.
    fn turn(&mut self, v: GeomId, target: Reg, r: &Rel) -> bool {
        let k = self.cluster(v);
        let rec = self.clusters[k].record.clone();
        if rec.rot != Rot::Free {
            return false;
        }
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let c = self.cname(r.constraint);
        let (pivot, about) = match rec.pos {
            Pos::Pivot { at, feature } => (at, self.name(feature)),
            Pos::On { feature, .. } => (self.point(feature), self.name(feature)),
            _ => {
                let origin = geoms[0];
                (
                    self.point(origin),
                    format!("the origin of {}", self.name(origin)),
                )
            }
        };
        let from = self.dir(Dir::Feature(v));
        let explain = format!(
            "Rotate {names} about {about} so that {} points along {} ({c}). This fixes its rotation.",
            self.name(v),
            self.word(target)
        );
        self.emit(
            Op::RotateDir {
                geoms,
                pivot,
                from,
                to: target,
            },
            None,
            self.satisfies(r),
            explain,
        );
        let rec = &mut self.clusters[k].record;
        rec.rot = Rot::Known;
        // Rotation known about a pivot: fixed, unless the pivot is a segment's end that its
        // free length still slides (the start then moves along the line).
        if matches!(rec.pos, Pos::Pivot { feature, .. } if !depends_on_dim(self.model, feature)) {
            rec.pos = Pos::Fixed;
        }
        true
    }

    /// A point feature `p` is known; the line (`base`, `dir`) of another cluster must pass at
    /// signed distance `d` from it.
    pub(super) fn move_line_to_point(
        &mut self,
        p: GeomId,
        base: GeomId,
        dir: GeomId,
        d: Option<Reg>,
        r: &Rel,
    ) -> bool {
        let k = self.cluster(base);
        let rec = self.clusters[k].record.clone();
        if rec.free_dim.is_some() {
            return false;
        }
        let at = self.point(p);
        if rec.rot == Rot::Known {
            // Its direction is known: the base must lie on the parallel at the right offset.
            let dv = self.dir(Dir::Feature(dir));
            let offset = d.map(|d| self.neg(d));
            let words = format!(
                "the line along {} placing {} at the right distance",
                self.name(dir),
                self.name(p)
            );
            let line = self.value(
                Op::Line {
                    point: at,
                    dir: dv,
                    offset,
                },
                Ty::Line,
                words,
            );
            return self.move_feature(base, Target::On(Locus::Line(line)), r);
        }
        if rec.line && d.is_none() && rec.pos == Pos::Free {
            // A lone line with free direction through a known point: slide its base there.
            return self.move_feature(base, Target::Point(at), r);
        }
        false
    }

    // ------------------------------------------------------------ locus analysis

    /// The locus table: where feature `f` of a partially fixed cluster can lie, if on a curve.
    fn locus_of(&mut self, f: GeomId) -> Option<Reg> {
        let rec = self.record(f).clone();
        if rec.free_dim.is_some() && depends_on_dim(self.model, f) {
            return None;
        }
        match rec.pos {
            Pos::On { feature, locus } if rec.rot != Rot::Free => Some(if feature == f {
                locus_reg(locus)
            } else {
                self.shifted(locus, feature, f)
            }),
            Pos::Pivot { at, feature } if feature != f => {
                let from = self.point(f);
                Some(self.circle_through(at, from, f, feature))
            }
            _ => None,
        }
    }

    /// Locus analysis: a coincidence between features of two partially fixed clusters, each on
    /// a curve: intersect the curves (a pseudo-point, 003 Example 2) and move both clusters.
    fn locus(&mut self, r: &Rel) -> bool {
        let Relation::PointPoint { a, b, d: None } = r.relation else {
            return false;
        };
        let (ka, kb) = (self.cluster(a), self.cluster(b));
        if ka == kb {
            return false;
        }
        let ready = |s: &Self, f: GeomId| {
            let rec = s.record(f);
            (rec.free_dim.is_none() || !depends_on_dim(s.model, f))
                && match rec.pos {
                    Pos::On { .. } => rec.rot != Rot::Free,
                    Pos::Pivot { feature, .. } => feature != f,
                    _ => false,
                }
        };
        if !ready(self, a) || !ready(self, b) {
            return false;
        }
        let (Some(la), Some(lb)) = (self.locus_of(a), self.locus_of(b)) else {
            return false;
        };
        let near = self.point(b);
        // The intersection table wants (line, circle), (circle, conic), (line, conic).
        let rank = |t: Ty| match t {
            Ty::Line => 0,
            Ty::Circle => 1,
            _ => 2,
        };
        let (x, y) = if rank(self.ty(la)) <= rank(self.ty(lb)) {
            (la, lb)
        } else {
            (lb, la)
        };
        let meet = match (self.ty(x), self.ty(y)) {
            (Ty::Circle, Ty::Circle) => Meet::CircleCircle,
            (Ty::Line, Ty::Line) => Meet::LineLine,
            (Ty::Line, Ty::Circle) => Meet::LineCircle,
            (Ty::Line, Ty::Conic) => Meet::LineConic,
            (Ty::Circle, Ty::Conic) => Meet::CircleConic,
            _ => return false,
        };
        let pseudo = self.intersect(meet, x, y, near, r.constraint);
        // The pseudo-point lies on both loci: move a's cluster there, then b's (which
        // satisfies the constraint), each with its one remaining motion.
        self.reach(a, pseudo, &[]);
        let sat = self.satisfies(r);
        self.reach(b, pseudo, &sat);
        true
    }

    /// Moves the cluster of `f`, whose one-DOF motion is known to reach `x`, so that `f` is at
    /// `x`: a rotation about its pivot, or a translation along its locus.
    fn reach(&mut self, f: GeomId, x: Reg, satisfies: &[ConstraintId]) {
        let k = self.cluster(f);
        let rec = self.clusters[k].record.clone();
        let geoms = self.clusters[k].geoms.clone();
        let names = self.group_name(&geoms);
        let from = self.point(f);
        let fname = self.name(f);
        let to = self.word(x);
        match rec.pos {
            Pos::Pivot { at, feature } => {
                let explain = format!(
                    "{names} may only rotate about {}: rotate it so that {fname} reaches {to}.",
                    self.name(feature)
                );
                self.emit(
                    Op::RotatePoint {
                        geoms,
                        pivot: at,
                        from,
                        to: x,
                    },
                    None,
                    satisfies.to_vec(),
                    explain,
                );
                let rec = &mut self.clusters[k].record;
                rec.rot = Rot::Known;
                rec.pos = Pos::Fixed;
            }
            _ => {
                let explain = format!("{names} may only slide along its locus: translate it so that {fname} reaches {to}.");
                self.emit(
                    Op::Translate { geoms, from, to: x },
                    None,
                    satisfies.to_vec(),
                    explain,
                );
                self.clusters[k].record.pos = Pos::Fixed;
            }
        }
        self.settle(k);
    }

    // ------------------------------------------------------------ branch defaults

    /// Runs the plan on the sketch, taking at each intersection the root nearest to where the
    /// moving feature is: that index is the sketch's branch, the default.
    fn calibrate_branches(&mut self) {
        let params = self.model.default_params();
        if let Ok(run) = crate::interp::run(
            self.model,
            &self.plan,
            &params,
            &crate::interp::Choice::Nearest,
        ) {
            for (b, idx) in self.plan.branches.iter_mut().zip(run.chosen) {
                if let Some(i) = idx {
                    b.default = i;
                }
            }
        }
    }
}

fn locus_reg(l: Locus) -> Reg {
    match l {
        Locus::Line(r) | Locus::Circle(r) | Locus::Conic(r) => r,
    }
}

/// Whether a feature's position depends on its geom's dimension (a segment's end).
fn depends_on_dim(model: &Model, f: GeomId) -> bool {
    matches!(
        model.geoms[f].owner,
        gcs_lang::model::Owner::Part(_, gcs_lang::model::Part::End)
    )
}

/// An angle constant in words: `0`, `pi`, `pi/2`, `-pi/2`.
fn angle_words(c: f64) -> String {
    use std::f64::consts::{FRAC_PI_2, PI};
    if c == 0.0 {
        "0".into()
    } else if c == PI {
        "pi".into()
    } else if c == FRAC_PI_2 {
        "pi/2".into()
    } else if c == -FRAC_PI_2 {
        "-pi/2".into()
    } else {
        crate::plan::fmt_f64(c)
    }
}
