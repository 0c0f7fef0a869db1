//! Chains of bodies joined by revolute joints with parallel axes: planar sub-chains (issue 38,
//! 003's loci of bodies turning about known axes).
//!
//! Bodies `C1 … Ck` joined to each other and to a body `C0` by revolute joints whose axes are
//! all parallel move, relative to `C0`, in planes square to those axes: every point of `Ck`
//! stays at a constant offset along them from `C0`'s joint, whatever the joints' angles. That
//! offset is each body's own constant, the distance between its two joints along their axis,
//! summed along the chain, so the sub-chain is a macro-geom whose invariant is a plane fixed in
//! `C0`. When `Ck` holds a known point (a tool pinned to its target) and `C0` may only turn
//! about a known axis (an arm's base), `C0` turns so that its plane passes through that point:
//! a plane turned onto a point about an axis (IK-Geo's SP4), two roots, closed form. The chain
//! itself is then an ordinary two-circle problem: action and locus analysis take it from there.
//!
//! This is degrees-of-freedom reasoning, not a pattern of robots: it needs the chain's
//! revolutes still open, their axes parallel in each body between them (a constant of the body,
//! so read from its local geometry), a rigid `Ck` pivoted at a known point, and `C0`'s turn not
//! about the chain's own axis (then the plane would not move: a planar mechanism, which the
//! rest of the analysis already solves).

use super::plane::PlaneAtDistance;
use super::{local_dir, parallel, Locus, Rel, Spatial, Target, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, Reg, RotationAxis, SpatialOp, Ty};
use gcs_lang::constraints::ConstraintKind;
use gcs_lang::model::{ConstraintId, GeomId, Part};

/// A revolute joint still open: its constraint and its two markers.
#[derive(Clone, Copy, Debug)]
pub(super) struct Joint {
    pub(super) constraint: ConstraintId,
    pub(super) markers: [GeomId; 2],
}

/// One link of a planar sub-chain, from the pivoted end towards `C0`: the joint, the marker
/// of that joint on the body nearer the pivoted end, and the marker on the body nearer `C0`.
#[derive(Clone, Copy, Debug)]
struct Link {
    joint: Joint,
    near: GeomId,
    far: GeomId,
}

/// The most joints a sub-chain holds: six revolutes make an arm.
const MAX_JOINTS: usize = 6;

impl Builder<'_, Spatial> {
    /// Finds a planar sub-chain whose far body may only turn about a known axis and whose near
    /// body is pivoted at a known point, and turns the far body so that the sub-chain's plane
    /// passes through that point. Returns whether it did.
    pub(super) fn planar_subchain(&mut self) -> bool {
        let joints = self.open_revolutes();
        if joints.is_empty() {
            return false;
        }
        let mut ends: Vec<(usize, GeomId, Reg)> = (0..self.clusters.len())
            .filter_map(|k| match self.clusters[k].record.trans {
                Trans::Pivot { at, feature }
                    if !self.clusters[k].geoms.is_empty()
                        && self.clusters[k].record.rigid()
                        && self.clusters[k].record.turn != Turn::Known =>
                {
                    Some((k, feature, at))
                }
                _ => None,
            })
            .collect();
        ends.sort_by_key(|&(_, f, _)| self.name(f));
        for (k, x, at) in ends {
            let mut path = Vec::new();
            let Some(chain) = self.chain_from(k, None, &joints, &mut path) else {
                continue;
            };
            // A pivot on the first joint's axis is that joint's own point: the plane passes
            // through it whatever the far body does, and the body before is the one pivoted.
            // Read in the body where both are in one; across the bodies of a macro-geom, on
            // the sketch.
            let first = chain[0].near;
            let on_own_axis = self.z_of(first).is_some_and(|z| {
                if self.model.top_level_of(first) == self.model.top_level_of(x) {
                    return super::on_axis(self.model, first, z, x);
                }
                let params = self.model.default_params();
                let Ok(sketch) =
                    crate::config::Config::<crate::config::D3>::from_sketch(self.model, &params)
                else {
                    return true;
                };
                let (p, q, d) = (
                    sketch.point(self.model, first),
                    sketch.point(self.model, x),
                    sketch.dir(self.model, z),
                );
                let w = q - p;
                let across = w - d * w.dot(&d) / d.dot(&d).max(f64::MIN_POSITIVE);
                across.norm() <= gcs_runtime::tol::LENGTH_REL * (1.0 + w.norm())
            });
            let last = *chain.last().expect("a chain has a joint");
            let slides = matches!(
                self.clusters[self.cluster(last.far)].record.trans,
                Trans::On { .. }
            );
            if slides {
                if self.slide_onto_subchain_plane(x, at, &chain) {
                    return true;
                }
            } else if !on_own_axis {
                self.turn_onto_subchain_plane(x, at, &chain);
                return true;
            }
        }
        self.subchain_onto_line(&joints)
    }

    /// Slides the chain's far body along the known line it is held on so that the plane its
    /// joint's axis fixes, at the chain's offset, passes through the known point `at` of
    /// feature `x` (a SCARA lifted at its base: the column slides until the arm's plane
    /// reaches the wrist). Returns whether it could.
    fn slide_onto_subchain_plane(&mut self, x: GeomId, at: Reg, chain: &[Link]) -> bool {
        let last = *chain.last().expect("a chain has a joint");
        let Some(z) = self.z_of(last.far) else {
            return false;
        };
        let Trans::On {
            locus: Locus::Line(line),
            ..
        } = self.clusters[self.cluster(last.far)].record.trans
        else {
            return false;
        };
        if !self.crosses_on_sketch(line, z) {
            return false;
        }
        let offset = self.subchain_offset(x, at, chain);
        let normal = self.direction(z);
        let bodies = self.chain_bodies(chain);
        let (xname, zname, far) = (self.name(x), self.name(z), self.name(last.far));
        let back = self.value(
            Op::Sum(vec![(-1.0, offset)]),
            Ty::Scalar,
            format!(
                "minus the offset of {xname} along the axes of {}",
                bodies.join(", ")
            ),
        );
        let words = format!(
            "the plane square to {zname} where {far} must be for {xname}, {} turning about axes along it, to reach its place",
            bodies.join(", ")
        );
        let plane = self.value(
            SpatialOp::Plane {
                point: at,
                normal,
                offset: Some(back),
            },
            Ty::Plane,
            words,
        );
        let c = last.joint.constraint;
        let Some(r) = self.serving(c) else {
            return false;
        };
        self.work_for(Some(c));
        let moved = self.move_point(last.far, Target::On(Locus::Plane(plane)), &r);
        self.work_for(None);
        moved
    }

    /// Finds a planar sub-chain whose near body holds a point on a known line and whose far
    /// body is known, and slides the near body along the line to where it crosses the plane
    /// the sub-chain keeps that point in: square to the chain's axes at its offset from the far
    /// body's joint, known with that body (a SCARA's quill: its axis, known from the tool,
    /// crosses the arm's plane at the wrist). The near body is then pivoted there, and locus
    /// analysis meets the chain's circles. A line that on the sketch runs along the plane
    /// (square to the axes to 1e-3) is left: it need not cross it. Returns whether it slid one.
    fn subchain_onto_line(&mut self, joints: &[Joint]) -> bool {
        let mut ends: Vec<(usize, GeomId, Reg)> = (0..self.clusters.len())
            .filter_map(|k| {
                let c = &self.clusters[k];
                match (c.record.trans, c.record.turn) {
                    (
                        Trans::On {
                            feature,
                            locus: Locus::Line(line),
                        },
                        turn,
                    ) if !c.geoms.is_empty() && c.record.rigid() && turn != Turn::Known => {
                        Some((k, feature, line))
                    }
                    _ => None,
                }
            })
            .collect();
        ends.sort_by_key(|&(_, f, _)| self.name(f));
        for (k, x, line) in ends {
            let mut path = Vec::new();
            let Some(chain) = self.chain_to(k, None, joints, &mut path, true) else {
                continue;
            };
            let last = *chain.last().expect("a chain has a joint");
            let Some(z) = self.z_of(last.far) else {
                continue;
            };
            if !self.crosses_on_sketch(line, z) {
                continue;
            }
            let at = self.point(x);
            let offset = self.subchain_offset(x, at, &chain);
            let (base, normal) = (self.point(last.far), self.direction(z));
            let bodies = self.chain_bodies(&chain);
            let words = format!(
                "the plane square to {} that {} keeps to, {} turning about axes along it",
                self.name(z),
                self.name(x),
                bodies.join(", ")
            );
            let plane = self.value(
                SpatialOp::Plane {
                    point: base,
                    normal,
                    offset: Some(offset),
                },
                Ty::Plane,
                words,
            );
            // The step serves the chain's first joint, which it does not satisfy.
            let first = chain[0].joint.constraint;
            let Some(r) = self.serving(first) else {
                continue;
            };
            self.work_for(Some(first));
            let moved = self.move_point(x, Target::On(Locus::Plane(plane)), &r);
            self.work_for(None);
            if moved {
                return true;
            }
        }
        false
    }

    /// Whether `line` crosses the planes square to direction feature `z` on the sketch: their
    /// directions not square to within 1e-3. Read by running the plan so far on the sketch
    /// (on a copy: measuring `z` writes a step).
    fn crosses_on_sketch(&self, line: Reg, z: GeomId) -> bool {
        (self.sketch_cosines(&[(z, line)])).is_some_and(|c| c[0] >= 1e-3)
    }

    /// The bodies of `chain`'s links, from the far end: how its words name the sub-chain.
    fn chain_bodies(&self, chain: &[Link]) -> Vec<String> {
        (chain.iter().rev())
            .map(|l| self.name(self.model.top_level_of(l.near)))
            .collect()
    }

    /// A relation of joint `c` for a step that serves it without satisfying it (the step's
    /// words and its branch name the joint).
    fn serving(&self, c: ConstraintId) -> Option<Rel> {
        let relation = self.relations_of(c).into_iter().next()?;
        Some(Rel {
            relation,
            constraint: c,
            last: false,
            duplicate: false,
        })
    }

    /// Whether a cluster whose record turns as `turn` turns only about an axis along the
    /// joint axis of its marker `far` (the feature of its axis parallel to `far`'s z, read in
    /// the body): planes square to the chain's axes then keep their tilt.
    fn turns_along(&self, turn: Turn, far: GeomId) -> bool {
        let model = self.model;
        match turn {
            Turn::Axis {
                feature: Some(f), ..
            } => {
                model.top_level_of(f) == model.top_level_of(far)
                    && (local_dir(model, f))
                        .zip(self.z_of(far).and_then(|z| local_dir(model, z)))
                        .is_some_and(|(u, v)| parallel(u, v))
            }
            _ => false,
        }
    }

    /// The revolute joints some relation of which is still pending, in name order.
    pub(super) fn open_revolutes(&self) -> Vec<Joint> {
        let model = self.model;
        let mut seen = std::collections::BTreeSet::new();
        let mut joints: Vec<Joint> = (self.pending.iter())
            .filter(|r| seen.insert(r.constraint))
            .filter_map(|r| {
                let c = &model.constraints[r.constraint];
                match (c.kind, c.args.as_slice()) {
                    (ConstraintKind::Revolute, &[a, b]) => Some(Joint {
                        constraint: r.constraint,
                        markers: [a, b],
                    }),
                    _ => None,
                }
            })
            .collect();
        joints.sort_by_key(|j| self.cname(j.constraint));
        joints
    }

    /// The marker's z axis.
    pub(super) fn z_of(&self, marker: GeomId) -> Option<GeomId> {
        self.model.part(marker, Part::AxisZ)
    }

    /// Walks from cluster `k` (entered through marker `entered`, none at the pivoted end) along
    /// open revolutes with axes parallel in each body, to a cluster that may only turn about a
    /// known axis across them. `path` holds the links so far; returns the whole chain.
    fn chain_from(
        &self,
        k: usize,
        entered: Option<GeomId>,
        joints: &[Joint],
        path: &mut Vec<Link>,
    ) -> Option<Vec<Link>> {
        self.chain_to(k, entered, joints, path, false)
    }

    /// [`Self::chain_from`]; with `to_known`, to a cluster that is known (fixed, or placed
    /// and oriented), or that turns only about an axis along the chain's through a known
    /// point, instead: the sub-chain's plane is then known with it.
    fn chain_to(
        &self,
        k: usize,
        entered: Option<GeomId>,
        joints: &[Joint],
        path: &mut Vec<Link>,
        to_known: bool,
    ) -> Option<Vec<Link>> {
        if path.len() >= MAX_JOINTS {
            return None;
        }
        let model = self.model;
        for j in joints {
            if path.iter().any(|l| l.joint.constraint == j.constraint) {
                continue;
            }
            for (near, far) in [(j.markers[0], j.markers[1]), (j.markers[1], j.markers[0])] {
                if self.cluster(near) != k || self.cluster(far) == k {
                    continue;
                }
                // Within the body, the joint's axis is parallel to the one it was entered by.
                if let Some(e) = entered {
                    let same_body = model.top_level_of(e) == model.top_level_of(near);
                    let axes = (self.z_of(e).and_then(|z| local_dir(model, z)))
                        .zip(self.z_of(near).and_then(|z| local_dir(model, z)));
                    if !same_body || !axes.is_some_and(|(u, v)| parallel(u, v)) {
                        continue;
                    }
                }
                let next = self.cluster(far);
                if path.iter().any(|l| self.cluster(l.near) == next) {
                    continue;
                }
                path.push(Link {
                    joint: *j,
                    near,
                    far,
                });
                let rec = &self.clusters[next].record;
                if to_known {
                    // Known, or turning only about an axis along the chain's through a known
                    // point: either way the plane square to that axis through `far` is known.
                    let along =
                        matches!(rec.trans, Trans::Pivot { .. }) && self.turns_along(rec.turn, far);
                    if !rec.movable() || rec.grounded() || along {
                        return Some(path.clone());
                    }
                    if rec.rigid() && rec.turn != Turn::Known {
                        if let Some(chain) = self.chain_to(next, Some(far), joints, path, true) {
                            return Some(chain);
                        }
                    }
                    path.pop();
                    continue;
                }
                // Turning only about an axis along the chain's (or not at all): the plane square
                // to it through `far` keeps its tilt.
                let keeps_tilt = rec.turn == Turn::Known || self.turns_along(rec.turn, far);
                match (rec.trans, rec.turn) {
                    // The far body slides on a known line, keeping its tilt: it slides the
                    // plane onto the pivot.
                    (
                        Trans::On {
                            locus: Locus::Line(_),
                            ..
                        },
                        _,
                    ) if keeps_tilt && rec.rigid() => return Some(path.clone()),
                    // The far body: its turn's axis known and across the chain's.
                    (
                        Trans::Pivot { .. },
                        Turn::Axis {
                            feature: Some(f), ..
                        },
                    ) => {
                        let across = model.top_level_of(f) == model.top_level_of(far)
                            && (local_dir(model, f))
                                .zip(self.z_of(far).and_then(|z| local_dir(model, z)))
                                .is_some_and(|(u, v)| !parallel(u, v));
                        if across {
                            return Some(path.clone());
                        }
                    }
                    _ if !rec.grounded() && rec.rigid() && rec.turn != Turn::Known => {
                        if let Some(chain) = self.chain_to(next, Some(far), joints, path, false) {
                            return Some(chain);
                        }
                    }
                    _ => {}
                }
                path.pop();
            }
        }
        None
    }

    /// The sense of revolute `c`'s z axes, the sketch's (its parallel relation's: one along
    /// `sense` times the other): 1 or -1.
    pub(super) fn joint_sense(&self, c: ConstraintId) -> f64 {
        use super::relation::Relation;
        (self.relations_of(c).into_iter())
            .find_map(|r| match r {
                Relation::Parallel { sense, .. } if sense != 0.0 => Some(sense),
                _ => None,
            })
            .unwrap_or(1.0)
    }

    /// The sign relating marker `m`'s z axis to marker `reference`'s, by the senses of the
    /// joints' parallel relations (the sketch's) and of the bodies' parallel axes.
    fn chain_senses(&self, chain: &[Link]) -> Vec<f64> {
        let model = self.model;
        // From the far end: the far body's marker is the reference, sense 1.
        let mut senses = vec![0.0; chain.len()];
        let mut sense = 1.0;
        for (i, l) in chain.iter().enumerate().rev() {
            let zn = self.z_of(l.near);
            // The joint's own sense: one z axis along `sense` times the other.
            sense *= self.joint_sense(l.joint.constraint);
            senses[i] = sense;
            // Into the next body towards the pivoted end: its two markers' axes.
            if i > 0 {
                let next = chain[i - 1].far;
                let (u, v) = (
                    zn.and_then(|z| local_dir(model, z)),
                    self.z_of(next).and_then(|z| local_dir(model, z)),
                );
                if let (Some(u), Some(v)) = (u, v) {
                    if super::dot(u, v) < 0.0 {
                        sense = -sense;
                    }
                }
            }
        }
        senses
    }

    /// Turns the chain's far body about its axis so that the plane its joint's axis fixes, at
    /// the chain's offset, passes through the known point `at` of feature `x`.
    fn turn_onto_subchain_plane(&mut self, x: GeomId, at: Reg, chain: &[Link]) {
        let offset = self.subchain_offset(x, at, chain);
        let last = *chain.last().expect("a chain has a joint");
        let bodies = self.chain_bodies(chain);
        let k = self.cluster(last.far);
        let (Trans::Pivot { at: pivot, .. }, Turn::Axis { axis, .. }) =
            (self.clusters[k].record.trans, self.clusters[k].record.turn)
        else {
            unreachable!("the chain ends at a body turning about an axis")
        };
        let z = self.z_of(last.far).expect("a revolute joins markers");
        let (base, normal) = (self.point(last.far), self.direction(z));
        let far = self.name(self.model.top_level_of(last.far));
        let (xname, zname) = (self.name(x), self.name(z));
        let meanings = vec![
            format!(
                "{far} turned counter-clockwise about {} from its turn nearest {xname}, the plane of {} square to {zname} through {xname}",
                self.word(axis),
                bodies.join(", ")
            ),
            "turned clockwise from there".to_string(),
        ];
        let words = format!(
            "the axis {zname} takes, turned about {}, for {xname} to be in the plane of {}",
            self.word(axis),
            bodies.join(", ")
        );
        let joints: Vec<String> = (chain.iter().rev())
            .map(|l| self.cname(l.joint.constraint))
            .collect();
        let explain = format!(
            "{} turn about parallel axes ({}): a planar sub-chain, which keeps {xname} in a plane square to {zname} at its offset along it. {far} may only turn about {}: turn it so that this plane passes through {xname}.",
            bodies.join(", "),
            joints.join(", "),
            self.word(axis)
        );
        self.work_for(Some(last.joint.constraint));
        self.turn_plane_about_axis(
            k,
            PlaneAtDistance {
                base,
                normal,
                point: at,
                d: offset,
            },
            (pivot, axis),
            (last.joint.constraint, meanings, words),
            (Vec::new(), explain),
        );
        self.work_for(None);
    }

    /// The offset along the axes of `chain` of its near body's point `x` (at `at`) from the
    /// far body's joint: each body's own, from the joint it is entered by to the next (or to
    /// `x`), with the senses of their axes.
    fn subchain_offset(&mut self, x: GeomId, at: Reg, chain: &[Link]) -> Reg {
        let senses = self.chain_senses(chain);
        // The offset along the axes from the far body's joint to `x`: each body's own, from
        // the joint it is entered by to the next (or to `x`).
        let mut terms = Vec::new();
        for (i, l) in chain.iter().enumerate() {
            let to = match i {
                0 => at,
                _ => self.point(chain[i - 1].far),
            };
            let (from, z) = (self.point(l.near), self.z_of(l.near));
            let Some(z) = z else { continue };
            let dir = self.direction(z);
            let words = format!(
                "how far {} is from {} along {}",
                if i == 0 {
                    self.name(x)
                } else {
                    self.name(chain[i - 1].far)
                },
                self.name(l.near),
                self.name(z)
            );
            let along = self.value(Op::Along { from, dir, to }, Ty::Scalar, words);
            terms.push((senses[i], along));
        }
        let bodies = self.chain_bodies(chain);
        let words = format!(
            "the offset of {} along the axes of {}",
            self.name(x),
            bodies.join(", ")
        );
        self.value(Op::Sum(terms), Ty::Scalar, words)
    }
}

impl Builder<'_, Spatial> {
    /// Two bodies that each only turn about a known point, joined by a revolute joint (an
    /// arm's upper arm about its shoulder and forearm about its wrist centre, IK-Geo's SP3):
    /// the distance between the two points depends on the joint's angle alone, so the joint
    /// turns until it is the known one (two roots: elbow up or down), and the pair is then one
    /// rigid body with two known points, which may only turn about the line through them.
    /// Returns whether it placed such a pair.
    pub(super) fn pivoted_pair(&mut self) -> bool {
        let model = self.model;
        for j in self.open_revolutes() {
            let [m1, m2] = j.markers;
            let (k1, k2) = (self.cluster(m1), self.cluster(m2));
            if k1 == k2 {
                continue;
            }
            let pivot = |b: &Self, k: usize| match (
                b.clusters[k].record.trans,
                b.clusters[k].record.turn,
            ) {
                (Trans::Pivot { at, feature }, Turn::Free) if b.clusters[k].record.rigid() => {
                    Some((at, feature))
                }
                _ => None,
            };
            let (Some((a, fa)), Some((b, fb))) = (pivot(self, k1), pivot(self, k2)) else {
                continue;
            };
            // The distance must vary with the joint's angle: neither pivot on the joint's axis
            // (where the body's own geometry tells; across the bodies of a macro-geom, a pivot
            // that is on it is a degenerate configuration at run time).
            let off_axis = |m: GeomId, f: GeomId| {
                model.top_level_of(m) != model.top_level_of(f)
                    || self.z_of(m).is_some_and(|z| {
                        local_dir(model, z).is_some() && !super::on_axis(model, m, z, f)
                    })
            };
            if !off_axis(m1, fa) || !off_axis(m2, fb) {
                continue;
            }
            self.join_pivoted_pair(j, (k1, a, fa), (k2, b, fb));
            return true;
        }
        false
    }

    /// Assembles the second body of a pivoted pair on the first by joint `j`, turns the joint
    /// so that the second pivot is at its distance from the first, and turns the pair about the
    /// first pivot so that the second lands on its place.
    fn join_pivoted_pair(
        &mut self,
        j: Joint,
        (k1, a, fa): (usize, Reg, GeomId),
        (k2, b, fb): (usize, Reg, GeomId),
    ) {
        use super::{Locus, Target};
        let [m1, m2] = j.markers;
        let c = j.constraint;
        let cname = self.cname(c);
        // Both bodies leave their places on the way: nothing of them is invariant meanwhile.
        self.forget_known(k1);
        self.forget_known(k2);
        self.clusters[k2].record.trans = Trans::Free;
        self.work_for(Some(c));
        let geoms2 = self.clusters[k2].geoms.clone();
        let (n1, n2) = (
            self.group_name(&self.clusters[k1].geoms.clone()),
            self.group_name(&geoms2),
        );
        // The second body onto the joint: its marker onto the first's, its axis along it.
        let (to, from) = (self.point(m1), self.point(m2));
        let explain = format!(
            "{n1} and {n2} each only turn about a known point ({}, {}), and {cname} joins them: assemble {n2} on {n1} by the joint, turn the joint until {} is at its distance from {}, then turn the pair about {} until {} is back in its place; the pair then moves as one body.\n   Translate {n2} so that {} lands on {}.",
            self.name(fa),
            self.name(fb),
            self.name(fb),
            self.name(fa),
            self.name(fa),
            self.name(fb),
            self.name(m2),
            self.name(m1)
        );
        self.emit(
            Op::Translate {
                geoms: geoms2.clone(),
                from,
                to,
            },
            None,
            Vec::new(),
            explain,
        );
        let (z1, z2) = (
            self.z_of(m1).expect("a marker"),
            self.z_of(m2).expect("a marker"),
        );
        let axis1 = self.direction(z1);
        self.align_joint(&geoms2, (m1, z1, axis1), z2, c);
        let pivot = self.point(m1);
        // The joint's angle: the second pivot's orbit about the joint meets the sphere about
        // the first through the second's place.
        let now = self.point(fb);
        let orbit = self.orbit(pivot, axis1, fb, now);
        let words = format!(
            "the sphere about {} through {}'s place",
            self.name(fa),
            self.name(fb)
        );
        let sphere = self.value(
            SpatialOp::SphereThrough {
                center: a,
                through: b,
                radius: None,
            },
            Ty::Sphere,
            words,
        );
        let rel = super::Rel {
            relation: super::relation::Relation::PointPoint {
                a: m1,
                b: m2,
                d: None,
            },
            constraint: c,
            last: false,
            duplicate: false,
        };
        let Some(Target::Point(meeting)) = self.meet(
            Locus::Circle(orbit),
            Target::On(Locus::Sphere(sphere)),
            now,
            &rel,
        ) else {
            unreachable!("a circle meets a sphere at a point")
        };
        let explain = format!(
            "Turn {n2} about the joint's axis so that {} is at its distance from {} ({cname}).",
            self.name(fb),
            self.name(fa)
        );
        self.emit(
            Op::RotatePoint {
                geoms: geoms2,
                pivot,
                axis: RotationAxis::Along(axis1),
                from: now,
                to: meeting,
            },
            None,
            Vec::new(),
            explain,
        );
        // The pair turns about the first pivot until the second is back in its place.
        let mut geoms = self.clusters[k1].geoms.clone();
        geoms.extend(self.clusters[k2].geoms.iter().copied());
        let words = format!("the direction from {} to {}", self.name(fa), self.name(fb));
        let away = self.value(
            Op::DirectionTo {
                from: a,
                to: meeting,
            },
            Ty::Vector,
            words.clone(),
        );
        let home = self.value(
            Op::DirectionTo { from: a, to: b },
            Ty::Vector,
            format!("{words}'s place"),
        );
        let explain = format!(
            "Rotate {n1} and {n2} together about {} so that {} is back in its place ({cname}); they may then only turn about the line through both.",
            self.name(fa),
            self.name(fb)
        );
        self.emit(
            Op::RotateDir {
                geoms,
                pivot: a,
                axis: RotationAxis::Shortest,
                from: away,
                to: home,
            },
            None,
            vec![c],
            explain,
        );
        self.work_for(None);
        self.merge_clusters(k1, k2);
        let rec = &mut self.clusters[k1].record;
        rec.trans = Trans::Pivot { at: a, feature: fa };
        rec.turn = Turn::Axis {
            axis: home,
            feature: None,
        };
        // The joint's relations hold by these steps.
        self.settle_where(|r| r.constraint == c);
    }
}

impl Builder<'_, Spatial> {
    /// Whether clusters `a` and `b` only turn, each about a known point, and it is the same
    /// point: the same register, or one pivots at a point of the other that coincides with the
    /// other's own pivot in its body.
    pub(super) fn share_pivot(&self, a: usize, b: usize) -> bool {
        let pivot = |k: usize| match (self.clusters[k].record.trans, self.clusters[k].record.turn) {
            (Trans::Pivot { at, feature }, Turn::Free) => Some((at, feature)),
            _ => None,
        };
        let (Some((at_a, fa)), Some((at_b, fb))) = (pivot(a), pivot(b)) else {
            return false;
        };
        // `at` measured from a point of cluster `k` at its pivot `f`.
        let on_pivot_of = |at: Reg, k: usize, f: GeomId| match self.def(at).map(|s| &s.op) {
            Some(&Op::PointOf(g)) => {
                self.cluster(g) == k && (g == f || self.model.constant_distance(g, f) == Some(0.0))
            }
            _ => false,
        };
        at_a == at_b || on_pivot_of(at_b, a, fa) || on_pivot_of(at_a, b, fb)
    }
}
