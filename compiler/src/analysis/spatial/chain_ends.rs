//! A planar sub-chain between two bodies that each only turn about a known axis (issue 38,
//! 003's loci of bodies turning about known axes; IK-Geo's subproblem 6 as its
//! `three_parallel` arm uses it).
//!
//! Bodies `B`, `C`, `D` joined to each other and to a body `A` by revolutes with parallel
//! axes keep every point of `D` at a constant offset along those axes from `A`'s joint, and
//! `D`'s axis along `A`'s (a planar sub-chain, `subchain.rs`). When `A` may only turn about a
//! known axis and `D` is joined by a revolute across those axes to a body `E` that may only
//! turn about a known axis through a known point, the chain has 1 + 18 + 1 degrees of freedom
//! and loses 20 to its four joints. `E`'s turn keeps the angle any direction makes with its
//! axis, and the height along any direction of its pivot: so (1) the chain's axis, turned by
//! `A`'s turn and, as `D` sees it, by the joint `D`–`E`, makes the same angle with `E`'s axis
//! both ways, and (2) `E`'s pivot is at its height along the chain's axis from `A`'s joint: the
//! chain's offset to the joint `D`–`E` plus the height of the pivot from that joint, measured
//! in `E`. Two equations, each a term in `A`'s turn plus a term in the joint's angle: a quartic
//! (`runtime::turn3d::planar_chain_ends`), up to four roots, a branch.
//!
//! The analysis assembles `D` on `E` by their joint, takes the two angles
//! (`SpatialOp::PlanarChainEnds`), turns `A` and the joint by them, and turns `E` (with `D`)
//! about its axis until `D`'s chain axis is along `A`'s. `A`, `D` and `E` are then known;
//! `B` and `C` then only turn about the known joints at the chain's ends, and their meeting is
//! two circles in the chain's plane (locus analysis, the elbow's branch).
//!
//! With two free bodies (`B`, then `D`) the chain has one equation over: `B` must reach from
//! `A`'s joint to `D`'s, and its point turned about the one lands on its orbit where the
//! other's is, its distance from that orbit's sphere a signed error (the model keeps it in the
//! orbit's plane). That is what closes a general arm's one default (its last joint's turn,
//! chosen by the driver's look-ahead): a one-dimensional search, subproblem 6 at each step.

use super::subchain::Joint;
use super::{local_dir, parallel, Spatial, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, RotationAxis, SpatialOp, Ty};
use gcs_lang::model::GeomId;

/// One joint of the chain, from the body nearer `A` (marker `from`) to the next (marker `to`).
#[derive(Clone, Copy, Debug)]
struct Step {
    joint: Joint,
    from: GeomId,
    to: GeomId,
}

/// The most free bodies between the chain's ends: three balance its degrees of freedom; two
/// leave one equation over, the closing error of a default elsewhere (a general arm's
/// one-dimensional search), met when the first of the two is joined to both ends.
const CHAIN_BODIES: usize = 3;

impl Builder<'_, Spatial> {
    /// Finds a planar sub-chain of three free bodies between two bodies that each only turn
    /// about a known axis, the last joint across the chain's axes, and closes it. Returns
    /// whether it did.
    pub(super) fn planar_chain_between_turns(&mut self) -> bool {
        let joints = self.open_revolutes();
        if joints.len() < 3 {
            return false;
        }
        let mut ends: Vec<usize> = (0..self.clusters.len())
            .filter(|&k| self.turns_about_known_axis(k))
            .collect();
        ends.sort_by_key(|&k| self.clusters[k].geoms.first().map(|&g| self.name(g)));
        for ka in ends {
            let mut path = Vec::new();
            if let Some(steps) = self.walk_parallel(ka, None, &joints, &mut path) {
                self.close_chain_ends(ka, &steps);
                return true;
            }
        }
        false
    }

    /// A rigid cluster that may only turn about a known axis through a known point of it.
    fn turns_about_known_axis(&self, k: usize) -> bool {
        let rec = &self.clusters[k].record;
        !self.clusters[k].geoms.is_empty()
            && rec.rigid()
            && matches!(
                (rec.trans, rec.turn),
                (Trans::Pivot { .. }, Turn::Axis { .. })
            )
    }

    /// Walks from cluster `k` (entered by marker `entered`; none at `A`) along open revolutes:
    /// through free rigid bodies whose joints' axes are parallel in each, then, after two or
    /// [`CHAIN_BODIES`] of them, by a joint across the chain's axes to a cluster that only turns
    /// about a known axis. `path` holds the steps so far; returns them all.
    fn walk_parallel(
        &self,
        k: usize,
        entered: Option<GeomId>,
        joints: &[Joint],
        path: &mut Vec<Step>,
    ) -> Option<Vec<Step>> {
        let model = self.model;
        let axis = |m: GeomId| self.z_of(m).and_then(|z| local_dir(model, z));
        for j in joints {
            if path.iter().any(|s| s.joint.constraint == j.constraint) {
                continue;
            }
            for (from, to) in [(j.markers[0], j.markers[1]), (j.markers[1], j.markers[0])] {
                let next = self.cluster(to);
                if self.cluster(from) != k || next == k {
                    continue;
                }
                let Some(v) = axis(from) else { continue };
                // Within a body, the axis it leaves by against the one it was entered by.
                let along = match entered {
                    None => {
                        // `A`: its joint's axis across its own turn's (else a planar mechanism).
                        let Turn::Axis { feature, .. } = self.clusters[k].record.turn else {
                            continue;
                        };
                        let across = feature.is_none_or(|f| {
                            model.top_level_of(f) != model.top_level_of(from)
                                || local_dir(model, f).is_some_and(|d| !parallel(d, v))
                        });
                        if !across {
                            continue;
                        }
                        true
                    }
                    Some(e) => {
                        if model.top_level_of(e) != model.top_level_of(from) {
                            continue;
                        }
                        let Some(u) = axis(e) else { continue };
                        parallel(u, v)
                    }
                };
                let bodies = path.len();
                path.push(Step {
                    joint: *j,
                    from,
                    to,
                });
                if along && bodies < CHAIN_BODIES {
                    // Into the next free body of the chain, by a joint along the chain's axes.
                    let rec = &self.clusters[next].record;
                    let free = rec.rigid() && rec.trans == Trans::Free && rec.turn == Turn::Free;
                    let new = !path[..bodies].iter().any(|s| self.cluster(s.from) == next);
                    if free && new {
                        if let Some(steps) = self.walk_parallel(next, Some(to), joints, path) {
                            return Some(steps);
                        }
                    }
                } else if !along
                    && bodies >= 2
                    && self.turns_about_known_axis(next)
                    && next != self.cluster(path[0].from)
                {
                    // Out of the last by a joint across the chain's axes, to the far end.
                    return Some(path.clone());
                }
                path.pop();
            }
        }
        None
    }

    /// Closes the chain `steps` from cluster `ka` (see the module's doc).
    fn close_chain_ends(&mut self, ka: usize, steps: &[Step]) {
        let model = self.model;
        let last = *steps.last().expect("a chain has joints");
        let (kd, ke) = (self.cluster(last.from), self.cluster(last.to));
        let (
            (Trans::Pivot { at: pa, .. }, Turn::Axis { axis: a1, .. }),
            (Trans::Pivot { at: pe, .. }, Turn::Axis { axis: ae, .. }),
        ) = (
            (
                self.clusters[ka].record.trans,
                self.clusters[ka].record.turn,
            ),
            (
                self.clusters[ke].record.trans,
                self.clusters[ke].record.turn,
            ),
        )
        else {
            unreachable!("the chain's ends turn about known axes")
        };
        let z = |b: &Self, m: GeomId| b.z_of(m).expect("a revolute joins markers");
        // The free bodies, and the sense of each one's entering axis against `A`'s.
        let n = steps.len() - 1;
        let mut senses = Vec::with_capacity(n);
        let mut sense = 1.0;
        for (i, s) in steps[..n].iter().enumerate() {
            if i > 0 {
                // Through the body between: its entering axis against the one it leaves by.
                let (e, f) = (steps[i - 1].to, s.from);
                let (u, v) = (local_dir(model, z(self, e)), local_dir(model, z(self, f)));
                if let (Some(u), Some(v)) = (u, v) {
                    if super::dot(u, v) < 0.0 {
                        sense = -sense;
                    }
                }
            }
            sense *= self.joint_sense(s.joint.constraint);
            senses.push(sense);
        }
        let (ga, gd, ge) = (
            self.clusters[ka].geoms.clone(),
            self.clusters[kd].geoms.clone(),
            self.clusters[ke].geoms.clone(),
        );
        let (na, nd, ne) = (
            self.group_name(&ga),
            self.group_name(&gd),
            self.group_name(&ge),
        );
        let c = last.joint.constraint;
        let cname = self.cname(c);
        let names: Vec<String> = (steps.iter())
            .map(|s| self.cname(s.joint.constraint))
            .collect();
        let bodies: Vec<String> = (steps[..n].iter())
            .map(|s| self.name(model.top_level_of(s.to)))
            .collect();
        let (a_word, e_word) = (self.word(a1), self.word(ae));
        for k in [ka, kd, ke] {
            self.forget_known(k);
        }
        self.work_for(Some(c));
        let explain = format!(
            "{} turn about parallel axes ({}): a planar sub-chain. {na} may only turn about {a_word}, {ne} only about {e_word}, and {cname} joins the chain to {ne} across its axes: the chain closes where its axis makes the same angle with {e_word} seen from both ends, and {ne}'s pivot is at its height along that axis. Assemble {nd} on {ne} by the joint at any angle, find {na}'s turn and the joint's angle that close it (a quartic: up to four assemblies), turn both by them, and turn {ne} about its axis until the chain's axes agree.\n   Translate {nd} so that {} lands on {}.",
            bodies.join(", "),
            names[..n].join(", "),
            self.name(last.from),
            self.name(last.to)
        );
        let (to, from) = (self.point(last.to), self.point(last.from));
        self.emit(
            Op::Translate {
                geoms: gd.clone(),
                from,
                to,
            },
            None,
            Vec::new(),
            explain,
        );
        let (ze, zd) = (z(self, last.to), z(self, last.from));
        let joint_dir = self.direction(ze);
        self.align_joint(&gd, (last.to, ze, joint_dir), zd, c);
        // The chain's axis and joint in `A`, its axis in `D` (entered by the third step).
        let first_joint = steps[0].from;
        let (h, base) = (
            self.direction(z(self, first_joint)),
            self.point(first_joint),
        );
        let d_entry = steps[n - 1].to;
        let far = self.direction(z(self, d_entry));
        let joint_at = self.point(last.to);
        // The chain's offset along its axes from `A`'s joint to the joint with `E`: each free
        // body's own, from the joint it is entered by to the one it leaves by.
        let mut terms = Vec::with_capacity(n);
        for i in 0..n {
            let entry = steps[i].to;
            let exit = if i + 1 < n {
                steps[i + 1].from
            } else {
                last.from
            };
            let (from, to) = (self.point(entry), self.point(exit));
            let zi = z(self, entry);
            let dir = self.direction(zi);
            let words = format!(
                "how far {} is from {} along {}",
                self.name(exit),
                self.name(entry),
                self.name(zi)
            );
            let along = self.value(Op::Along { from, dir, to }, Ty::Scalar, words);
            terms.push((senses[i], along));
        }
        let words = format!(
            "the offset of {} from {} along the axes of {}",
            self.name(last.from),
            self.name(first_joint),
            bodies.join(", ")
        );
        let offset = self.value(Op::Sum(terms), Ty::Scalar, words);
        let meanings = super::three_circles::turn_ranks(&na, &a_word, true);
        let branch = self.branch(c, meanings);
        let words = format!("{na}'s turn and the angle of {cname} that close the chain");
        let angles = self.value(
            SpatialOp::PlanarChainEnds {
                first: [pa, a1],
                h,
                base,
                joint: [joint_at, joint_dir],
                far,
                last: [pe, ae],
                offset,
                sense: senses[n - 1],
                branch,
                constraint: c,
            },
            Ty::Values,
            words,
        );
        let mut angle = |index: u16, words: String| {
            self.value(Op::Unknown { of: angles, index }, Ty::Scalar, words)
        };
        let turn = angle(0, format!("the turn of {na} about {a_word}"));
        let bend = angle(1, format!("the angle of {cname}"));
        let explain = format!("Turn {na} about {a_word} by the turn that closes the chain.");
        self.emit(
            SpatialOp::RotateBy {
                geoms: ga,
                pivot: pa,
                axis: a1,
                angle: turn,
            },
            None,
            Vec::new(),
            explain,
        );
        let rec = &mut self.clusters[ka].record;
        rec.trans = Trans::Fixed;
        rec.turn = Turn::Known;
        let explain = format!(
            "Turn {nd} about {} by the angle of {cname} that closes the chain.",
            self.name(ze)
        );
        self.emit(
            SpatialOp::RotateBy {
                geoms: gd.clone(),
                pivot: joint_at,
                axis: joint_dir,
                angle: bend,
            },
            None,
            Vec::new(),
            explain,
        );
        // `E` with `D` about its axis, until `D`'s chain axis is along `A`'s: the turn that
        // aligns the chain's last axis with its first, which the joint `D` is entered by
        // carries (its parallel axes then hold by construction, not by redundancy).
        let entering = steps[n - 1].joint.constraint;
        let mut both = ge;
        both.extend(gd);
        let target = self.direction(z(self, first_joint));
        let to = self.in_sense(target, z(self, first_joint), senses[n - 1]);
        let from = self.direction(z(self, d_entry));
        let explain = format!(
            "Rotate {ne} and {nd} together about {e_word} so that {} points along {} ({cname}); the chain's ends are then known.",
            self.name(z(self, d_entry)),
            self.name(z(self, first_joint))
        );
        self.emit(
            Op::RotateDir {
                geoms: both,
                pivot: pe,
                axis: RotationAxis::Along(ae),
                from,
                to,
            },
            None,
            vec![c],
            explain,
        );
        self.work_for(None);
        self.merge_clusters(ke, kd);
        let rec = &mut self.clusters[ke].record;
        rec.trans = Trans::Fixed;
        rec.turn = Turn::Known;
        // The joint `D`–`E` holds by these steps; so do the parallel axes of the joint `D` is
        // entered by, once the chain's other bodies are turned onto the axes of the joints
        // before them (each body's axes parallel in it): no check, no redundancy.
        let taken = self.settle_where(|r| {
            r.constraint == c
                || (r.constraint == entering
                    && matches!(r.relation, super::relation::Relation::Parallel { .. }))
        });
        // The last of the entering joint's relations to be met now says it is met.
        if taken.iter().any(|r| r.constraint == entering && r.last) {
            if let Some(r) = (self.pending.iter_mut().rev()).find(|r| r.constraint == entering) {
                r.last = true;
            }
        }
    }
}
