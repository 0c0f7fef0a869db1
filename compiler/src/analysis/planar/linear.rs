//! The linear stage: clusters whose directions are all known, solved together.
//!
//! Action, locus, chain and loop analysis place one cluster at a time, or a rigid group.
//! A closed profile of horizontal and vertical segments with fillets gets stuck: once every
//! direction is known, each segment can still slide and stretch, each fillet slide, and the
//! profile closes only when all of them agree at once. No single relation places anything,
//! and a default would close the loop by iterating on a tangency whose error touches zero
//! without crossing it (its double root). But with the directions known, every relation left
//! between those clusters is *linear* in their motions:
//!
//! - a coincidence (each coordinate), a midpoint, a point's signed distance from a line, a
//!   circle of known radius tangent to a line: the directions are constants, the positions
//!   move by the unknowns;
//! - a segment end put on a circle the segment is tangent to: given the tangency, the end is
//!   on the circle exactly when it is the foot of the centre on the segment's line, so its
//!   error is the end's signed distance from that foot, along the segment.
//!
//! The unknowns are each cluster's translation (two for a free one, one for one sliding on a
//! line) and each free segment length. The stage collects the relations among such clusters,
//! builds one system in those unknowns ([`PlanarOp::Linear`]), and *tears* it: each row gives
//! one unknown from those before, but for a few torn unknowns that the rows left over (the
//! closures) fix as a small dense system. Pivots and closures are chosen on the sketch (the
//! plan so far run there, `Builder::values`), so that none is a coefficient that vanishes
//! there; rows left beyond the closures are implied, and checked. The solve is linear in the
//! size of the system: a closed profile of 256 segments is one pass over its rows.

use super::relation::Relation;
use super::{depends_on_dim, Locus, Planar, Pos, Rel, Rot};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{
    Coef, LinearRow, LinearSystem, LinearTerm, Meet, Op, PlanarOp, Reg, Residual, Ty,
};
use gcs_lang::constraints::ConstraintKind as K;
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Owner, Part};
use gcs_runtime::linear::MAX_TEARS;
use rustc_hash::FxHashSet as HashSet;
use std::collections::{BTreeMap, BTreeSet};

/// How a cluster of the stage may move.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Motion {
    /// Translate freely: two unknowns.
    Free,
    /// Slide `feature` along line `line`: one unknown.
    Slide { feature: GeomId, line: Reg },
    /// Stay (grounded, or only its length free).
    Still,
}

/// A cluster's part in the stage.
#[derive(Clone, Copy, Debug)]
struct Member {
    motion: Motion,
    /// The segment whose length is free (the cluster is that segment alone, held at its start).
    length: Option<GeomId>,
    /// Whether the cluster is grounded: a constant of the system.
    grounded: bool,
}

/// A direction a point moves along as an unknown grows.
#[derive(Clone, Copy, Debug)]
enum Along {
    X,
    Y,
    Dir(Reg),
}

/// One row to build, by the relation it comes from.
#[derive(Clone, Copy, Debug)]
enum Spec {
    /// Coordinate `axis` of `b - a`.
    Coincide { a: GeomId, b: GeomId, axis: u8 },
    /// Coordinate `axis` of `p` less the midpoint of `a` and `b`.
    Midpoint {
        p: GeomId,
        a: GeomId,
        b: GeomId,
        axis: u8,
    },
    /// Signed distance of `p` from the line (`base`, `dir`).
    OnLine {
        p: GeomId,
        base: GeomId,
        dir: GeomId,
    },
    /// `side` times the signed distance of the circle's centre from the line.
    Tangent {
        circle: GeomId,
        base: GeomId,
        dir: GeomId,
        side: f64,
    },
    /// The signed distance along the segment's direction `dir` from its end `p` to the foot
    /// of the circle's centre: zero exactly where `p` is on the circle the segment touches.
    Touch {
        p: GeomId,
        circle: GeomId,
        dir: GeomId,
    },
}

/// A relation the stage may take, with its rows.
#[derive(Clone, Debug)]
struct Candidate {
    /// Its index among the pending relations.
    index: usize,
    rel: Rel,
    specs: Vec<Spec>,
    /// The clusters of the stage it involves.
    clusters: Vec<usize>,
}

/// Estimated coefficients smaller than this, next to the largest of their row, are taken
/// to vanish on the sketch: never a pivot.
const PIVOT_ESTIMATE: f64 = 1e-6;

/// Closure rows whose estimated elimination leaves less than this (relative) do not fix
/// another tear.
const CLOSURE_ESTIMATE: f64 = 1e-9;

impl Builder<'_, Planar> {
    /// Each circle with each segment in a touching contact: the segment's end on the circle
    /// (`on`) and the segment tangent to it (`tangent`), whichever way each is written.
    fn touching_pairs(&self) -> &HashSet<(GeomId, GeomId)> {
        self.pairs.get_or_init(|| {
            let model = self.model;
            let mut on: HashSet<(GeomId, GeomId)> = HashSet::default();
            let mut tangent: HashSet<(GeomId, GeomId)> = HashSet::default();
            for (_, c) in model.constraints.iter() {
                let (Some(&a), Some(&b)) = (c.args.first(), c.args.get(1)) else {
                    continue;
                };
                let circle = |g: GeomId| model.geoms[g].kind == GeomKind::Circle;
                let segment = |g: GeomId| model.geoms[g].kind == GeomKind::Segment;
                match c.kind {
                    K::On if circle(b) => {
                        if let Owner::Part(seg, Part::Start | Part::End) = model.geoms[a].owner {
                            on.insert((b, seg));
                        }
                    }
                    K::Tangent if circle(a) && segment(b) => {
                        tangent.insert((a, b));
                    }
                    K::Tangent if circle(b) && segment(a) => {
                        tangent.insert((b, a));
                    }
                    _ => {}
                }
            }
            on.intersection(&tangent).copied().collect()
        })
    }

    /// Whether `relation` is half of a touching contact whose segment's direction is known:
    /// a linear stage can take it, exactly.
    fn touching(&self, relation: &Relation) -> bool {
        let model = self.model;
        let (circle, seg) = match *relation {
            Relation::PointCircle {
                p,
                circle,
                gap: None,
                ..
            } => match model.geoms[p].owner {
                Owner::Part(seg, Part::Start | Part::End) => (circle, seg),
                _ => return false,
            },
            Relation::CircleLine {
                circle,
                dir,
                gap: None,
                ..
            } => match model.geoms[dir].owner {
                Owner::Part(seg, Part::Dir) => (circle, seg),
                _ => return false,
            },
            _ => return false,
        };
        self.touching_pairs().contains(&(circle, seg)) && self.record(seg).rot == Rot::Known
    }

    /// Action or locus analysis (`attempt`) of `r`, refusing to build half of a touching
    /// contact as the meeting of a circle with another locus while a linear stage may take it
    /// (`linear_first`): the loci touch where the contact holds, and their meeting is a
    /// double root whose rounding grows to its square root, or a degenerate pair of circles
    /// where the profile's constraints are redundant.
    pub(super) fn no_double_root(
        &mut self,
        r: &Rel,
        attempt: impl FnOnce(&mut Self, &Rel) -> bool,
    ) -> bool {
        if !self.linear_first || !self.touching(&r.relation) {
            return attempt(self, r);
        }
        let ks = self.clusters_of(r);
        let records: Vec<_> = ks
            .iter()
            .map(|&k| self.clusters[k].record.clone())
            .collect();
        let start = self.plan.steps.len();
        if !attempt(self, r) {
            return false;
        }
        let double = self.plan.steps[start..].iter().any(|s| {
            matches!(
                s.op,
                Op::Intersect {
                    meet: Meet::CircleCircle
                        | Meet::LineCircle
                        | Meet::CircleConic
                        | Meet::LineConic
                        | Meet::ConicConic,
                    ..
                }
            )
        });
        if double {
            for (&k, rec) in ks.iter().zip(records) {
                self.clusters[k].record = rec;
            }
            // The caller rolls the steps back.
            return false;
        }
        true
    }

    /// The linear stage (see the module's documentation): solves the first group of
    /// clusters, connected by relations linear in their motions, whose system fixes every
    /// motion. Returns whether it solved one.
    pub(super) fn linear_stage(&mut self) -> bool {
        let mut members: BTreeMap<usize, Member> = BTreeMap::new();
        let mut candidates = Vec::new();
        // The (circle, direction) pairs a pending tangency makes touch, once for all.
        let touching: HashSet<(GeomId, GeomId)> = (self.pending.iter())
            .filter_map(|r| match r.relation {
                Relation::CircleLine {
                    circle,
                    dir,
                    gap: None,
                    ..
                } => Some((circle, dir)),
                _ => None,
            })
            .collect();
        for index in 0..self.pending.len() {
            let rel = self.pending[index].clone();
            if rel.duplicate {
                continue;
            }
            let Some(specs) = self.specs(&rel.relation, &touching) else {
                continue;
            };
            let ks = self.clusters_of(&rel);
            let mut clusters = Vec::new();
            let mut fits = true;
            for &k in &ks {
                let member = match members.get(&k) {
                    Some(m) => Some(*m),
                    None => self.member(k),
                };
                match member {
                    Some(m) => {
                        members.insert(k, m);
                        if !m.grounded {
                            clusters.push(k);
                        }
                    }
                    None => fits = false,
                }
            }
            if fits && !clusters.is_empty() {
                candidates.push(Candidate {
                    index,
                    rel,
                    specs,
                    clusters,
                });
            }
        }
        if candidates.is_empty() {
            return false;
        }
        // Groups: clusters joined by the candidates' rows.
        let mut parent: BTreeMap<usize, usize> = BTreeMap::new();
        fn find(parent: &mut BTreeMap<usize, usize>, k: usize) -> usize {
            let p = *parent.entry(k).or_insert(k);
            if p == k {
                return k;
            }
            let root = find(parent, p);
            parent.insert(k, root);
            root
        }
        for c in &candidates {
            let first = find(&mut parent, c.clusters[0]);
            for &k in &c.clusters[1..] {
                let r = find(&mut parent, k);
                if r != first {
                    parent.insert(r, first);
                }
            }
        }
        // In the order of their first relations.
        let mut groups: Vec<Vec<Candidate>> = Vec::new();
        let mut group_of: BTreeMap<usize, usize> = BTreeMap::new();
        for c in candidates {
            let root = find(&mut parent, c.clusters[0]);
            let g = *group_of.entry(root).or_insert_with(|| {
                groups.push(Vec::new());
                groups.len() - 1
            });
            groups[g].push(c);
        }
        for group in groups {
            let cp = self.checkpoint();
            if self.solve_linear(&members, &group) {
                return true;
            }
            self.rollback(cp);
        }
        false
    }

    /// The cluster's part in a linear stage, or `None` when it cannot take one (it may still
    /// turn, its locus is not a line, its circle's radius or its shape is free).
    fn member(&self, k: usize) -> Option<Member> {
        let c = &self.clusters[k];
        let first = *c.geoms.first()?;
        let rec = &c.record;
        if rec.dof() == 0 {
            return Some(Member {
                motion: Motion::Still,
                length: None,
                grounded: true,
            });
        }
        if rec.rot == Rot::Free || !rec.fd.is_empty() || !rec.passes.is_empty() || rec.line {
            return None;
        }
        let model = self.model;
        let length = match rec.free_dim {
            None => None,
            Some(g) if model.geoms[g].kind == GeomKind::Segment && c.geoms == [g] => Some(g),
            Some(_) => return None,
        };
        let motion = match rec.pos {
            Pos::Free => Motion::Free,
            Pos::On {
                feature,
                locus: Locus::Line(line),
            } if !depends_on_dim(model, feature) => Motion::Slide { feature, line },
            Pos::Fixed => Motion::Still,
            Pos::Pivot { feature, .. }
                if feature != first && !depends_on_dim(model, feature) && rec.rot == Rot::Known =>
            {
                Motion::Still
            }
            _ => return None,
        };
        Some(Member {
            motion,
            length,
            grounded: false,
        })
    }

    /// The rows of a relation linear in the motions, or `None` when it is not.
    fn specs(
        &self,
        relation: &Relation,
        touching: &HashSet<(GeomId, GeomId)>,
    ) -> Option<Vec<Spec>> {
        let model = self.model;
        Some(match *relation {
            Relation::PointPoint { a, b, d: None } => {
                (0..2).map(|axis| Spec::Coincide { a, b, axis }).collect()
            }
            Relation::Midpoint { p, a, b } => (0..2)
                .map(|axis| Spec::Midpoint { p, a, b, axis })
                .collect(),
            Relation::PointLine { p, base, dir, .. } => vec![Spec::OnLine { p, base, dir }],
            Relation::CircleLine {
                circle,
                base,
                dir,
                side,
                ..
            } if self.record(circle).free_dim != Some(circle) => vec![Spec::Tangent {
                circle,
                base,
                dir,
                side,
            }],
            Relation::PointCircle {
                p,
                circle,
                gap: None,
                ..
            } => {
                // A segment's end on a circle the segment touches (or is made to touch with
                // this stage): the foot of the centre on its line.
                let Owner::Part(seg, Part::Start | Part::End) = model.geoms[p].owner else {
                    return None;
                };
                let dir = model.dir_feature(seg)?;
                let touches =
                    self.record(circle).tangent.contains(&dir) || touching.contains(&(circle, dir));
                if !touches || self.record(circle).free_dim == Some(circle) {
                    return None;
                }
                vec![Spec::Touch { p, circle, dir }]
            }
            _ => return None,
        })
    }

    /// Builds, tears and writes the system of one group; `false` (the caller rolls back)
    /// when it does not fix every motion of the group.
    fn solve_linear(&mut self, members: &BTreeMap<usize, Member>, group: &[Candidate]) -> bool {
        let model = self.model;
        // The unknowns, cluster by cluster in order.
        let mut clusters: Vec<usize> = group.iter().flat_map(|c| c.clusters.clone()).collect();
        clusters.sort_unstable();
        clusters.dedup();
        // In the order of their first geoms' names, so that the plan does not depend on the
        // order of statements.
        clusters.sort_by_cached_key(|&k| self.name(self.clusters[k].geoms[0]));
        let mut first_unknown: BTreeMap<usize, u16> = BTreeMap::new();
        let mut length_unknown: BTreeMap<usize, u16> = BTreeMap::new();
        let mut slide_dir: BTreeMap<usize, Reg> = BTreeMap::new();
        let mut n: u16 = 0;
        let mut words: Vec<String> = Vec::new();
        let mut names: Vec<String> = Vec::new();
        for &k in &clusters {
            let m = members[&k];
            let name = self.group_name(&self.clusters[k].geoms.clone());
            let first_geom = self.clusters[k].geoms[0];
            first_unknown.insert(k, n);
            match m.motion {
                Motion::Free => {
                    words.push(format!("the shift of {name} along x"));
                    words.push(format!("the shift of {name} along y"));
                    names.push(format!("{}_dx", self.name(first_geom)));
                    names.push(format!("{}_dy", self.name(first_geom)));
                    n += 2;
                }
                Motion::Slide { line, .. } => {
                    let w = format!("the direction of {}", self.word(line));
                    let d = self.value(PlanarOp::LineDir(line), Ty::Vector, w);
                    slide_dir.insert(k, d);
                    words.push(format!("the slide of {name} along its line"));
                    names.push(format!("{}_slide", self.name(first_geom)));
                    n += 1;
                }
                Motion::Still => {}
            }
            if let Some(seg) = m.length {
                length_unknown.insert(k, n);
                words.push(format!("the change of {}'s length", self.name(seg)));
                names.push(format!("{}_stretch", self.name(seg)));
                n += 1;
            }
        }
        if n == 0 || n > 4096 {
            return false;
        }
        // The rows.
        let mut rows: Vec<LinearRow> = Vec::new();
        let mut row_of: Vec<usize> = Vec::new();
        for (ci, c) in group.iter().enumerate() {
            for spec in &c.specs {
                let row = self.row(
                    spec,
                    &c.rel,
                    members,
                    &first_unknown,
                    &length_unknown,
                    &slide_dir,
                );
                rows.push(row);
                row_of.push(ci);
            }
        }
        // Estimates on the sketch.
        let mut regs: Vec<Reg> = rows.iter().map(|r| r.error).collect();
        for row in &rows {
            for t in &row.terms {
                regs.extend(t.coef.regs());
            }
        }
        regs.sort_unstable_by_key(|r| r.0);
        regs.dedup();
        let Some(probe) = self.values else {
            return false;
        };
        let Some(values) = probe(model, &self.plan, &regs) else {
            return false;
        };
        let at: BTreeMap<Reg, [f64; 3]> = regs.iter().copied().zip(values).collect();
        let estimate = |c: &Coef| -> f64 {
            let v = |r: &Reg| at.get(r).copied().unwrap_or([f64::NAN; 3]);
            match c {
                Coef::One => 1.0,
                Coef::X(a) => v(a)[0],
                Coef::Y(a) => v(a)[1],
                Coef::Dot(a, b) => {
                    let (a, b) = (v(a), v(b));
                    a[0] * b[0] + a[1] * b[1]
                }
                Coef::Cross(a, b) => {
                    let (a, b) = (v(a), v(b));
                    a[0] * b[1] - a[1] * b[0]
                }
            }
        };
        let est: Vec<Vec<(u16, f64)>> = (rows.iter())
            .map(|row| {
                let mut by: BTreeMap<u16, f64> = BTreeMap::new();
                for t in &row.terms {
                    *by.entry(t.unknown).or_default() += t.scale * estimate(&t.coef);
                }
                by.into_iter().collect()
            })
            .collect();
        if est.iter().flatten().any(|(_, c)| !c.is_finite()) {
            return false;
        }
        let rhs: Vec<f64> = (rows.iter())
            .map(|r| -at.get(&r.error).map_or(f64::NAN, |v| v[0]))
            .collect();
        let Some(torn) = tear(n as usize, &est, &rhs) else {
            return false;
        };
        self.write_linear(
            names,
            group,
            members,
            &clusters,
            rows,
            &row_of,
            torn,
            words,
            &first_unknown,
            &length_unknown,
        )
    }

    /// One row: its error register and its terms.
    fn row(
        &mut self,
        spec: &Spec,
        rel: &Rel,
        members: &BTreeMap<usize, Member>,
        first: &BTreeMap<usize, u16>,
        length: &BTreeMap<usize, u16>,
        slide: &BTreeMap<usize, Reg>,
    ) -> LinearRow {
        let model = self.model;
        let mut terms = Vec::new();
        // How point feature `f` moves: (unknown, direction).
        let motion = |s: &mut Self, f: GeomId| -> Vec<(u16, Along)> {
            let k = s.cluster(f);
            let Some(m) = members.get(&k) else {
                return Vec::new();
            };
            if m.grounded {
                return Vec::new();
            }
            let mut out = Vec::new();
            let u = first[&k];
            match m.motion {
                Motion::Free => {
                    out.push((u, Along::X));
                    out.push((u + 1, Along::Y));
                }
                Motion::Slide { .. } => out.push((u, Along::Dir(slide[&k]))),
                Motion::Still => {}
            }
            if let Some(seg) = m.length {
                if depends_on_dim(model, f) && model.geoms[f].owner == Owner::Part(seg, Part::End) {
                    if let Some(d) = model.dir_feature(seg) {
                        let d = s.direction(d);
                        out.push((length[&k], Along::Dir(d)));
                    }
                }
            }
            out
        };
        let add = |terms: &mut Vec<LinearTerm>,
                   moves: Vec<(u16, Along)>,
                   sign: f64,
                   f: &dyn Fn(Along) -> Option<(f64, Coef)>| {
            for (unknown, along) in moves {
                if let Some((scale, coef)) = f(along) {
                    terms.push(LinearTerm {
                        unknown,
                        scale: sign * scale,
                        coef,
                    });
                }
            }
        };
        let component = |axis: u8| {
            move |along: Along| match (along, axis) {
                (Along::X, 0) | (Along::Y, 1) => Some((1.0, Coef::One)),
                (Along::X, _) | (Along::Y, _) => None,
                (Along::Dir(v), 0) => Some((1.0, Coef::X(v))),
                (Along::Dir(v), _) => Some((1.0, Coef::Y(v))),
            }
        };
        let cross = |d: Reg| {
            move |along: Along| {
                Some(match along {
                    Along::X => (-1.0, Coef::Y(d)),
                    Along::Y => (1.0, Coef::X(d)),
                    Along::Dir(v) => (1.0, Coef::Cross(d, v)),
                })
            }
        };
        let dot = |d: Reg| {
            move |along: Along| {
                Some(match along {
                    Along::X => (1.0, Coef::X(d)),
                    Along::Y => (1.0, Coef::Y(d)),
                    Along::Dir(v) => (1.0, Coef::Dot(d, v)),
                })
            }
        };
        let error = match *spec {
            Spec::Coincide { a, b, axis } => {
                let (pa, pb) = (self.point(a), self.point(b));
                let ma = motion(self, a);
                let mb = motion(self, b);
                add(&mut terms, mb, 1.0, &component(axis));
                add(&mut terms, ma, -1.0, &component(axis));
                self.value(
                    Op::Error {
                        residual: Residual::PointPoint {
                            a: pa,
                            b: pb,
                            d: None,
                        },
                        component: axis,
                    },
                    Ty::Scalar,
                    format!("how far {} is from {}", self.name(b), self.name(a)),
                )
            }
            Spec::Midpoint { p, a, b, axis } => {
                let (pp, pa, pb) = (self.point(p), self.point(a), self.point(b));
                let (mp, ma, mb) = (motion(self, p), motion(self, a), motion(self, b));
                add(&mut terms, mp, 1.0, &component(axis));
                add(&mut terms, ma, -0.5, &component(axis));
                add(&mut terms, mb, -0.5, &component(axis));
                self.value(
                    Op::Error {
                        residual: Residual::Midpoint {
                            p: pp,
                            a: pa,
                            b: pb,
                        },
                        component: axis,
                    },
                    Ty::Scalar,
                    format!("how far {} is from the midpoint", self.name(p)),
                )
            }
            Spec::OnLine { p, base, dir } => {
                let residual = self.residual(&rel.relation);
                let d = self.direction(dir);
                let (mp, mb) = (motion(self, p), motion(self, base));
                add(&mut terms, mp, 1.0, &cross(d));
                add(&mut terms, mb, -1.0, &cross(d));
                self.value(
                    Op::Error {
                        residual,
                        component: 0,
                    },
                    Ty::Scalar,
                    format!("how far {} is from its line", self.name(p)),
                )
            }
            Spec::Tangent {
                circle,
                base,
                dir,
                side,
            } => {
                let residual = self.residual(&rel.relation);
                let d = self.direction(dir);
                let centre = model.point_feature(circle);
                let (mc, mb) = (motion(self, centre), motion(self, base));
                add(&mut terms, mc, side, &cross(d));
                add(&mut terms, mb, -side, &cross(d));
                self.value(
                    Op::Error {
                        residual,
                        component: 0,
                    },
                    Ty::Scalar,
                    format!("how far {} is from touching its line", self.name(circle)),
                )
            }
            Spec::Touch { p, circle, dir } => {
                let centre = model.point_feature(circle);
                let (pp, pc) = (self.point(p), self.point(centre));
                let d = self.direction(dir);
                let (mp, mc) = (motion(self, p), motion(self, centre));
                add(&mut terms, mc, 1.0, &dot(d));
                add(&mut terms, mp, -1.0, &dot(d));
                self.value(
                    Op::Along {
                        from: pp,
                        dir: d,
                        to: pc,
                    },
                    Ty::Scalar,
                    format!(
                        "how far {} is from where {} touches its line",
                        self.name(p),
                        self.name(circle)
                    ),
                )
            }
        };
        LinearRow {
            constraint: rel.constraint,
            error,
            terms,
        }
    }

    /// Writes a torn system: the solve, each unknown, each cluster's move; the records become
    /// fixed, the relations done (checked where their rows were left over).
    #[allow(clippy::too_many_arguments)]
    fn write_linear(
        &mut self,
        names: Vec<String>,
        group: &[Candidate],
        members: &BTreeMap<usize, Member>,
        clusters: &[usize],
        rows: Vec<LinearRow>,
        row_of: &[usize],
        torn: Torn,
        words: Vec<String>,
        first: &BTreeMap<usize, u16>,
        length: &BTreeMap<usize, u16>,
    ) -> bool {
        let used: BTreeSet<usize> = (torn.pivots.iter().map(|&(r, _)| r as usize))
            .chain(torn.closures.iter().map(|&r| r as usize))
            .collect();
        // A relation is satisfied by the stage when every row of it is used; one with a row
        // left over is checked after it.
        let mut left_over: BTreeSet<usize> = BTreeSet::new();
        let mut constructed: BTreeSet<usize> = BTreeSet::new();
        for (r, &ci) in row_of.iter().enumerate() {
            if used.contains(&r) {
                constructed.insert(ci);
            } else {
                left_over.insert(ci);
            }
        }
        let cluster_names: Vec<String> = clusters
            .iter()
            .map(|&k| self.group_name(&self.clusters[k].geoms.clone()))
            .collect();
        let mut cnames: Vec<String> = Vec::new();
        for c in group {
            let n = self.cname(c.rel.constraint);
            if !cnames.contains(&n) {
                cnames.push(n);
            }
        }
        const LISTED: usize = 6;
        let listed = if cnames.len() > LISTED {
            format!(
                "{}, and {} more",
                cnames[..LISTED].join(", "),
                cnames.len() - LISTED
            )
        } else {
            cnames.join(", ")
        };
        let explain =
            format!(
            "{} keep their directions: their {} slides and free lengths make every relation left \
             between them linear ({}). Solve those {} equations as one linear system{}, and move \
             each there.",
            cluster_names.join(", "),
            words.len(),
            listed,
            rows.len(),
            if torn.tears.is_empty() {
                String::new()
            } else {
                format!(" (torn at {} unknowns, closed by as many rows)", torn.tears.len())
            }
        );
        let leading = group.first().map(|c| c.rel.constraint);
        self.work_for(leading);
        let system = LinearSystem {
            unknowns: words.len() as u16,
            names,
            rows,
            tears: torn.tears,
            pivots: torn.pivots,
            closures: torn.closures,
        };
        let solved = self.emit(
            PlanarOp::Linear(Box::new(system)),
            Some(Ty::Values),
            Vec::new(),
            explain,
        );
        let unknowns: Vec<Reg> = (words.iter().enumerate())
            .map(|(i, w)| {
                self.value(
                    Op::Unknown {
                        of: solved,
                        index: i as u16,
                    },
                    Ty::Scalar,
                    w.clone(),
                )
            })
            .collect();
        let mut origin = None;
        for &k in clusters {
            let m = members[&k];
            let geoms = self.clusters[k].geoms.clone();
            let u = first[&k] as usize;
            match m.motion {
                Motion::Free => {
                    let o = *origin.get_or_insert_with(|| {
                        let zero = self.value(Op::Const(0.0), Ty::Scalar, "0".into());
                        self.value(
                            PlanarOp::PointXY { x: zero, y: zero },
                            Ty::Point,
                            "the origin".into(),
                        )
                    });
                    let to = self.value(
                        PlanarOp::PointXY {
                            x: unknowns[u],
                            y: unknowns[u + 1],
                        },
                        Ty::Point,
                        format!("the shift of {}", self.group_name(&geoms)),
                    );
                    self.emit(
                        Op::Translate {
                            geoms: geoms.clone(),
                            from: o,
                            to,
                        },
                        None,
                        Vec::new(),
                        String::new(),
                    );
                }
                Motion::Slide { feature, line } => {
                    let from = self.point(feature);
                    let at = self.value(
                        Op::LocusParam {
                            locus: line,
                            point: from,
                        },
                        Ty::Scalar,
                        format!("where {} is along {}", self.name(feature), self.word(line)),
                    );
                    let moved = self.value(
                        Op::Sum(vec![(1.0, at), (1.0, unknowns[u])]),
                        Ty::Scalar,
                        format!(
                            "where {} goes along {}",
                            self.name(feature),
                            self.word(line)
                        ),
                    );
                    let to = self.value(
                        Op::LocusPoint {
                            locus: line,
                            at: moved,
                        },
                        Ty::Point,
                        format!("the new place of {}", self.name(feature)),
                    );
                    self.emit(
                        Op::Translate {
                            geoms: geoms.clone(),
                            from,
                            to,
                        },
                        None,
                        Vec::new(),
                        String::new(),
                    );
                }
                Motion::Still => {}
            }
            if let Some(seg) = m.length {
                let now = self.dim_of(seg);
                let value = self.value(
                    Op::Sum(vec![(1.0, now), (1.0, unknowns[length[&k] as usize])]),
                    Ty::Scalar,
                    format!("the new length of {}", self.name(seg)),
                );
                self.emit(
                    Op::SetDim { geom: seg, value },
                    None,
                    Vec::new(),
                    String::new(),
                );
            }
            let rec = &mut self.clusters[k].record;
            if rec.pos != Pos::None {
                rec.pos = Pos::Fixed;
            }
            if let Some(g) = rec.free_dim.take() {
                rec.fixed_dims.push(g);
            }
        }
        // What the stage satisfies, on its last step.
        let satisfied: Vec<ConstraintId> = (group.iter().enumerate())
            .filter(|(ci, c)| c.rel.last && !left_over.contains(ci))
            .map(|(_, c)| c.rel.constraint)
            .collect();
        if let Some(last) = self.plan.steps.last_mut() {
            last.satisfies.extend(satisfied);
        }
        for &ci in &constructed {
            self.constructed(group[ci].rel.constraint);
        }
        let indices: BTreeSet<usize> = group.iter().map(|c| c.index).collect();
        let taken = self.settle_pending(&indices);
        self.work_for(None);
        // Rows left over are implied: checked, as any implied relation is.
        for (ci, rel) in taken.iter().enumerate() {
            if left_over.contains(&ci) {
                self.work_for(Some(rel.constraint));
                self.check(rel);
                self.work_for(None);
            }
        }
        true
    }
}

/// A torn system's shape: see [`LinearSystem`].
#[derive(Debug, Default, PartialEq)]
struct Torn {
    tears: Vec<u16>,
    pivots: Vec<(u16, u16)>,
    closures: Vec<u16>,
}

/// Tears the system of `n` unknowns whose rows' coefficients, estimated on the sketch, are
/// `rows` (summed by unknown) and right-hand sides `rhs`: each row with one unknown left gives
/// it (if its coefficient does not vanish), else the row with the fewest unknowns left tears
/// all but its best; then the rows left over that fix the tears, in order, are the closures.
/// `None` when the rows do not fix every unknown, or need more than [`MAX_TEARS`] tears.
fn tear(n: usize, rows: &[Vec<(u16, f64)>], rhs: &[f64]) -> Option<Torn> {
    let size: Vec<f64> = (rows.iter())
        .map(|r| r.iter().fold(0.0_f64, |m, (_, c)| m.max(c.abs())))
        .collect();
    let usable = |r: usize, c: f64| c.abs() > PIVOT_ESTIMATE * size[r];
    let mut rows_of: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (r, row) in rows.iter().enumerate() {
        for &(u, c) in row {
            if usable(r, c) {
                rows_of[u as usize].push(r);
            }
        }
    }
    // Unknowns left per row (only those with a usable coefficient count: a vanishing one
    // neither blocks nor gives).
    let mut left: Vec<usize> = (rows.iter().enumerate())
        .map(|(r, row)| row.iter().filter(|&&(_, c)| usable(r, c)).count())
        .collect();
    let mut known = vec![false; n];
    let mut used = vec![false; rows.len()];
    let mut torn = Torn::default();
    let mut queue: std::collections::VecDeque<usize> =
        (0..rows.len()).filter(|&r| left[r] == 1).collect();
    let mut settled = 0;
    let know = |u: usize,
                known: &mut Vec<bool>,
                left: &mut Vec<usize>,
                queue: &mut std::collections::VecDeque<usize>| {
        known[u] = true;
        for &r in &rows_of[u] {
            left[r] -= 1;
            if left[r] == 1 {
                queue.push_back(r);
            }
        }
    };
    while settled < n {
        while let Some(r) = queue.pop_front() {
            if used[r] || left[r] != 1 {
                continue;
            }
            let Some(&(u, _)) = rows[r]
                .iter()
                .find(|&&(u, c)| !known[u as usize] && usable(r, c))
            else {
                continue;
            };
            used[r] = true;
            torn.pivots.push((r as u16, u));
            know(u as usize, &mut known, &mut left, &mut queue);
            settled += 1;
        }
        if settled == n {
            break;
        }
        // Tear: the unused row with the fewest unknowns left tears its weakest.
        let row = (0..rows.len())
            .filter(|&r| !used[r] && left[r] >= 2)
            .min_by_key(|&r| left[r]);
        let u = match row {
            Some(r) => rows[r]
                .iter()
                .filter(|&&(u, c)| !known[u as usize] && usable(r, c))
                .min_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
                .map(|&(u, _)| u as usize)?,
            // An unknown no row can give: the system leaves it free.
            None => return None,
        };
        torn.tears.push(u as u16);
        if torn.tears.len() > MAX_TEARS {
            return None;
        }
        know(u, &mut known, &mut left, &mut queue);
        settled += 1;
    }
    // The tears' closures, estimated: each unknown as an affine function of the tears.
    let k = torn.tears.len();
    let w = k + 1;
    let mut forms = vec![0.0; n * w];
    for (i, &t) in torn.tears.iter().enumerate() {
        forms[t as usize * w + 1 + i] = 1.0;
    }
    for &(r, u) in &torn.pivots {
        let (r, u) = (r as usize, u as usize);
        let mut acc = vec![0.0; w];
        acc[0] = rhs[r];
        let mut pivot = 0.0;
        for &(j, c) in &rows[r] {
            if j as usize == u {
                pivot += c;
            } else {
                for (a, f) in acc
                    .iter_mut()
                    .zip(&forms[j as usize * w..(j as usize + 1) * w])
                {
                    *a -= c * f;
                }
            }
        }
        for (f, a) in forms[u * w..(u + 1) * w].iter_mut().zip(&acc) {
            *f = a / pivot;
        }
    }
    // Greedy elimination over the rows left, in order: a row that still has a pivot after
    // the closures before it fixes one more tear.
    let mut basis: Vec<(usize, Vec<f64>)> = Vec::new();
    for r in (0..rows.len()).filter(|&r| !used[r]) {
        if basis.len() == k {
            break;
        }
        let mut a = vec![0.0; k];
        for &(j, c) in &rows[r] {
            for (x, f) in a
                .iter_mut()
                .zip(&forms[j as usize * w + 1..(j as usize + 1) * w])
            {
                *x += c * f;
            }
        }
        let scale = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        for (col, b) in &basis {
            let f = a[*col] / b[*col];
            for (x, y) in a.iter_mut().zip(b) {
                *x -= f * y;
            }
        }
        let Some(col) = (0..k).max_by(|&x, &y| a[x].abs().total_cmp(&a[y].abs())) else {
            continue;
        };
        if a[col].abs() > CLOSURE_ESTIMATE * scale.max(f64::MIN_POSITIVE) && a[col].is_finite() {
            basis.push((col, a));
            torn.closures.push(r as u16);
        }
    }
    (torn.closures.len() == k).then_some(torn)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_chain_needs_no_tear() {
        // x0 = 1; x1 - x0 = 2; x2 - x1 = 3.
        let rows = vec![
            vec![(0, 1.0)],
            vec![(0, -1.0), (1, 1.0)],
            vec![(1, -1.0), (2, 1.0)],
        ];
        let t = tear(3, &rows, &[1.0, 2.0, 3.0]).expect("torn");
        assert!(t.tears.is_empty());
        assert_eq!(t.pivots, [(0, 0), (1, 1), (2, 2)]);
    }

    #[test]
    fn a_loop_is_torn_once_and_closed_by_its_last_row() {
        // x1 - x0 = 1, x2 - x1 = 1, x0 + x2 = 4.
        let rows = vec![
            vec![(0, -1.0), (1, 1.0)],
            vec![(1, -1.0), (2, 1.0)],
            vec![(0, 1.0), (2, 1.0)],
        ];
        let t = tear(3, &rows, &[1.0, 1.0, 4.0]).expect("torn");
        assert_eq!(t.tears.len(), 1);
        assert_eq!(t.closures.len(), 1);
    }

    #[test]
    fn a_vanishing_coefficient_is_never_a_pivot() {
        // Row 0 reads x0 with a coefficient that vanishes on the sketch: x0 comes from row 1.
        let rows = vec![vec![(0, 1e-17), (1, 1.0)], vec![(0, 1.0)]];
        let t = tear(2, &rows, &[1.0, 2.0]).expect("torn");
        assert!(t.tears.is_empty());
        assert!(
            t.pivots.contains(&(1, 0)) && t.pivots.contains(&(0, 1)),
            "{t:?}"
        );
    }

    #[test]
    fn rows_that_leave_a_motion_free_are_no_system() {
        // x0 + x1 = 1 alone.
        assert_eq!(tear(2, &[vec![(0, 1.0), (1, 1.0)]], &[1.0]), None);
    }

    #[test]
    fn a_repeated_row_is_left_over_not_a_closure() {
        let rows = vec![
            vec![(0, 1.0), (1, 1.0)],
            vec![(0, 2.0), (1, 2.0)],
            vec![(0, 1.0), (1, -1.0)],
        ];
        let t = tear(2, &rows, &[1.0, 2.0, 0.0]).expect("torn");
        assert_eq!(t.pivots.len() + t.closures.len(), 2);
        assert!(!t.pivots.iter().any(|&(r, _)| r == 1) || !t.closures.contains(&0));
    }
}
