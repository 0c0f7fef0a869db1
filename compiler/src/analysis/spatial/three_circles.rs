//! Three bodies in a chain of two revolutes, closed at both ends: the three-circle problem
//! (issue 38, 003's loci of bodies turning about known axes; IK-Geo's subproblem 5).
//!
//! A body `A` that may only turn about a known axis, a free body `B`, and a body `C` that may
//! only turn about a known point `P` of it, joined `A`–`B` and `B`–`C` by revolute joints: one
//! degree of freedom for `A`, six for `B`, three for `C`, and five removed by each joint. The
//! chain is rigid, yet no step of it has a locus alone: `P`, carried by `C` about the second
//! joint and by `B` about the first, must meet the place `A`'s turn leaves for it. Written as
//! `turn(first, θ1, P) = turn(second, θ2, turn(third, θ3, P'))`, with `P'` where `C` holds `P`
//! once the chain is assembled at any angles, both sides keep their distance from the second
//! axis's pivot and their height along it whatever `θ2` is: two equations in `θ1` and `θ3`
//! whose elimination is a quartic (`runtime::turn3d::three_circles`), every real root of which
//! is an assembly, and `θ2` then turns one side onto the other. Up to four roots: a branch.
//!
//! The analysis assembles `B` on `A` and `C` on `B` by their joints (a translation and a
//! rotation each), takes the three angles (`SpatialOp::ThreeCircles`), and turns `C` about
//! the second joint, `B` and `C` about the first, and the three about `A`'s axis. All three
//! are then known: a robot arm's position chain when its wrist centre is known and no two of
//! its first three axes are parallel or meet (the planar sub-chain and the pivoted pair solve
//! those).

use super::subchain::Joint;
use super::{local_dir, parallel, Spatial, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, Reg, RotationAxis, SpatialOp, Ty};
use gcs_lang::model::GeomId;

/// The chain's first body: cluster `k` turning about the unit `axis` through `pivot`, joined
/// by its marker `marker`.
#[derive(Clone, Copy)]
struct Turning {
    k: usize,
    marker: GeomId,
    pivot: Reg,
    axis: Reg,
}

/// The chain's middle body: cluster `k`, joined to the first by marker `near`, to the last by
/// marker `far`.
#[derive(Clone, Copy)]
struct Middle {
    k: usize,
    near: GeomId,
    far: GeomId,
}

/// The chain's last body: cluster `k` turning about its point `feature`, known at `at`, joined
/// by its marker `marker`.
#[derive(Clone, Copy)]
struct Pivoted {
    k: usize,
    marker: GeomId,
    at: Reg,
    feature: GeomId,
}

impl Builder<'_, Spatial> {
    /// Finds a chain of a body turning about a known axis, a free body and a body turning
    /// about a known point, joined by two open revolutes, and solves it by the three-circle
    /// problem. Returns whether it did.
    pub(super) fn three_circle_chain(&mut self) -> bool {
        let joints = self.open_revolutes();
        if joints.len() < 2 {
            return false;
        }
        for &j1 in &joints {
            for &j2 in &joints {
                if j1.constraint == j2.constraint {
                    continue;
                }
                for (ma, mb1) in [
                    (j1.markers[0], j1.markers[1]),
                    (j1.markers[1], j1.markers[0]),
                ] {
                    for (mb2, mc) in [
                        (j2.markers[0], j2.markers[1]),
                        (j2.markers[1], j2.markers[0]),
                    ] {
                        if let Some((a, b, c)) = self.three_circle_ends(ma, (mb1, mb2), mc) {
                            self.join_three_circles((j1, j2), a, b, c);
                            return true;
                        }
                    }
                }
            }
        }
        false
    }

    /// The chain's three bodies when marker `ma` is on a body turning about a known axis, the
    /// markers `mb` on one free body, and `mc` on a body turning about a known point, with
    /// nothing degenerate in the bodies' own geometry: the middle body's axes not parallel
    /// (a planar sub-chain), the first joint's axis not along the first body's, the point off
    /// the last joint's axis (it would not move).
    fn three_circle_ends(
        &self,
        ma: GeomId,
        (mb1, mb2): (GeomId, GeomId),
        mc: GeomId,
    ) -> Option<(Turning, Middle, Pivoted)> {
        let model = self.model;
        let (ka, kb, kc) = (self.cluster(ma), self.cluster(mb1), self.cluster(mc));
        if self.cluster(mb2) != kb || ka == kb || kb == kc || ka == kc {
            return None;
        }
        let (ra, rb, rc) = (
            &self.clusters[ka].record,
            &self.clusters[kb].record,
            &self.clusters[kc].record,
        );
        let (Trans::Pivot { at: pivot, .. }, Turn::Axis { axis, feature }) = (ra.trans, ra.turn)
        else {
            return None;
        };
        let (Trans::Pivot { at, feature: fc }, Turn::Free) = (rc.trans, rc.turn) else {
            return None;
        };
        let free = rb.trans == Trans::Free && rb.turn == Turn::Free;
        if !(ra.rigid() && rb.rigid() && rc.rigid() && free) {
            return None;
        }
        if model.top_level_of(mb1) != model.top_level_of(mb2) || mb1 == mb2 {
            return None;
        }
        let dir = |m: GeomId| self.z_of(m).and_then(|z| local_dir(model, z));
        let (Some(u), Some(v)) = (dir(mb1), dir(mb2)) else {
            return None;
        };
        if parallel(u, v) {
            return None;
        }
        // The first joint's axis along the first body's: a turn about it moves the chain in
        // planes square to both (a planar mechanism, which the rest of the analysis solves).
        if let (Some(f), Some(w)) = (feature, dir(ma)) {
            let same_body = model.top_level_of(f) == model.top_level_of(ma);
            if same_body && local_dir(model, f).is_some_and(|d| parallel(d, w)) {
                return None;
            }
        }
        // The point on the last joint's axis: turning about it does not move the point.
        let z = self.z_of(mc)?;
        if model.top_level_of(fc) != model.top_level_of(mc) || super::on_axis(model, mc, z, fc) {
            return None;
        }
        Some((
            Turning {
                k: ka,
                marker: ma,
                pivot,
                axis,
            },
            Middle {
                k: kb,
                near: mb1,
                far: mb2,
            },
            Pivoted {
                k: kc,
                marker: mc,
                at,
                feature: fc,
            },
        ))
    }

    /// Assembles the chain at any angles, takes the three joints' angles that close it, and
    /// turns its bodies by them, innermost first. The three are then one known body.
    fn join_three_circles(&mut self, (j1, j2): (Joint, Joint), a: Turning, b: Middle, c: Pivoted) {
        let (ga, gb, gc) = (
            self.clusters[a.k].geoms.clone(),
            self.clusters[b.k].geoms.clone(),
            self.clusters[c.k].geoms.clone(),
        );
        let (na, nb, nc) = (
            self.group_name(&ga),
            self.group_name(&gb),
            self.group_name(&gc),
        );
        let (c1, c2) = (j1.constraint, j2.constraint);
        let (cname1, cname2) = (self.cname(c1), self.cname(c2));
        let (za, zb1) = (self.z_of(a.marker), self.z_of(b.near));
        let (zb2, zc) = (self.z_of(b.far), self.z_of(c.marker));
        let (Some(za), Some(zb1), Some(zb2), Some(zc)) = (za, zb1, zb2, zc) else {
            unreachable!("a revolute joins markers")
        };
        // Where the middle body's far joint is before the chain is assembled: the sketch's
        // root leaves it nearest there.
        let near = self.point(b.far);
        // The three bodies leave their places on the way: nothing of them is invariant
        // meanwhile.
        for k in [a.k, b.k, c.k] {
            self.forget_known(k);
        }
        self.clusters[c.k].record.trans = Trans::Free;
        self.work_for(Some(c1));
        let axis_word = self.word(a.axis);
        let (fc, ma, mb1) = (self.name(c.feature), self.name(a.marker), self.name(b.near));
        let explain = format!(
            "{na} may only turn about {axis_word}, {nc} only about {fc}, and {nb} joins them by {cname1} and {cname2}: a chain closed at both ends, which the three-circle problem solves. Assemble it by its joints at any angles, find the angles of {na}'s turn and of the two joints that bring {fc} back to its place (a quartic: up to four assemblies), and turn the chain by them.\n   Translate {nb} so that {mb1} lands on {ma}."
        );
        let (to, from) = (self.point(a.marker), self.point(b.near));
        self.emit(
            Op::Translate {
                geoms: gb.clone(),
                from,
                to,
            },
            None,
            Vec::new(),
            explain,
        );
        let first_joint = self.direction(za);
        self.align_joint(&gb, (a.marker, za, first_joint), zb1, c1);
        self.work_for(Some(c2));
        let (to, from) = (self.point(b.far), self.point(c.marker));
        let explain = format!(
            "Translate {nc} so that {} lands on {} ({cname2}).",
            self.name(c.marker),
            self.name(b.far)
        );
        self.emit(
            Op::Translate {
                geoms: gc.clone(),
                from,
                to,
            },
            None,
            Vec::new(),
            explain,
        );
        let second_joint = self.direction(zb2);
        self.align_joint(&gc, (b.far, zb2, second_joint), zc, c2);
        // The three angles.
        let (second_at, third_at) = (self.point(a.marker), self.point(b.far));
        let b_point = self.point(c.feature);
        let meanings = turn_ranks(&na, &axis_word, false);
        let branch = self.branch(c2, meanings);
        let words = format!(
            "the angles of {na}'s turn, {cname1} and {cname2} that bring {fc} back to its place"
        );
        let angles = self.value(
            SpatialOp::ThreeCircles {
                first: [a.pivot, a.axis],
                a: c.at,
                second: [second_at, first_joint],
                third: [third_at, second_joint],
                b: b_point,
                near,
                branch,
                constraint: c2,
            },
            Ty::Values,
            words,
        );
        let mut angle = |index: u16, words: String| {
            self.value(Op::Unknown { of: angles, index }, Ty::Scalar, words)
        };
        let back = angle(0, format!("the turn of {na} about {axis_word}, backwards"));
        let second = angle(1, format!("the angle of {cname1}"));
        let third = angle(2, format!("the angle of {cname2}"));
        let turn = self.value(Op::Neg(back), Ty::Scalar, format!("the turn of {na}"));
        let explain = format!(
            "Turn {nc} about {} by the angle of {cname2} the three-circle problem gives.",
            self.name(zb2)
        );
        self.emit(
            SpatialOp::RotateBy {
                geoms: gc.clone(),
                pivot: third_at,
                axis: second_joint,
                angle: third,
            },
            None,
            Vec::new(),
            explain,
        );
        let mut chain = gb.clone();
        chain.extend(gc.iter().copied());
        let explain = format!(
            "Turn {nb} and {nc} together about {} by the angle of {cname1}.",
            self.name(za)
        );
        self.emit(
            SpatialOp::RotateBy {
                geoms: chain.clone(),
                pivot: second_at,
                axis: first_joint,
                angle: second,
            },
            None,
            Vec::new(),
            explain,
        );
        let mut all = ga;
        all.extend(chain);
        let explain = format!(
            "Turn {na}, {nb} and {nc} together about {axis_word} by {na}'s turn: {fc} is back in its place, and the three are known ({cname1}, {cname2})."
        );
        self.emit(
            SpatialOp::RotateBy {
                geoms: all,
                pivot: a.pivot,
                axis: a.axis,
                angle: turn,
            },
            None,
            vec![c1, c2],
            explain,
        );
        self.work_for(None);
        self.merge_clusters(a.k, b.k);
        self.merge_clusters(a.k, c.k);
        let rec = &mut self.clusters[a.k].record;
        rec.trans = Trans::Fixed;
        rec.turn = Turn::Known;
        // Both joints' relations hold by these steps.
        self.settle_where(|r| r.constraint == c1 || r.constraint == c2);
    }

    /// Rotates `geoms` about the joint's marker `at` so that their marker's z axis `z` points
    /// along the other marker's, `axis` (in the sense of the joint `c`'s parallel relation).
    pub(super) fn align_joint(
        &mut self,
        geoms: &[GeomId],
        (at, z_at, axis): (GeomId, GeomId, Reg),
        z: GeomId,
        c: gcs_lang::model::ConstraintId,
    ) {
        let sense = self.joint_sense(c);
        let target = self.in_sense(axis, z_at, sense);
        let from = self.direction(z);
        let pivot = self.point(at);
        let explain = format!(
            "Rotate {} about {} so that {} points along {} ({}).",
            self.group_name(geoms),
            self.name(at),
            self.name(z),
            self.name(z_at),
            self.cname(c)
        );
        self.emit(
            Op::RotateDir {
                geoms: geoms.to_vec(),
                pivot,
                axis: RotationAxis::Shortest,
                from,
                to: target,
            },
            None,
            Vec::new(),
            explain,
        );
    }
}

/// The meanings of a quartic's four roots ordered by the turn of `body` about `axis` from where
/// it was: the smallest first where `ascending`, else the largest.
pub(super) fn turn_ranks(body: &str, axis: &str, ascending: bool) -> Vec<String> {
    let ranks = if ascending {
        ["smallest", "second smallest", "third smallest", "largest"]
    } else {
        ["largest", "second largest", "third largest", "smallest"]
    };
    (ranks.iter())
        .map(|rank| {
            format!("the assembly whose counter-clockwise turn of {body} about {axis} from where it was (in (-180°, 180°]) is the {rank} of the chain's (up to four)")
        })
        .collect()
}
