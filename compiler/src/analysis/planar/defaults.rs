//! Defaults in the plane (000, section 5.2.1): when neither action nor locus analysis nor a
//! rigid chain or loop applies, one freedom of one cluster is fixed at a default parameter.
//!
//! Each default has a geometric meaning, read from the cluster's invariants record: the
//! position of a feature along the line, circle or conic it is on, the angle of a body about
//! its pivot, the coordinates of a free point, the angle of a free direction, a lone line's
//! angle and its offset across itself, a free dimension (a segment pinned at its end is sized
//! from that end). The construction checker (`compiler/bench/tests/construction.rs`) probes
//! every state of its table for them: as many defaults as DOF left, least motion, and each
//! effective.
//! Its sketch value is what the plan measures there when it runs on the sketch, so that a
//! default at its sketch value moves nothing (002's least motion): an under-constrained
//! model solves to its sketch as far as the constraints allow. The driver then goes back to
//! action and locus analysis; a constraint that the default makes redundant becomes an error
//! function that an outer iteration drives to zero (`Builder::close_iterations`).

use super::{locus_reg, Locus, Planar, Pos, Rot};
use crate::analysis::driver::Builder;
use crate::plan::{Op, PlanarOp, Reg, RotationAxis, Ty};
use gcs_lang::model::{GeomId, GeomKind, Owner, Part};

impl Builder<'_, Planar> {
    /// Fixes one freedom of the first of `candidates` that has one a default can name.
    pub(super) fn add_default(&mut self, candidates: &[usize]) -> bool {
        candidates.iter().any(|&k| self.default_on(k))
    }

    /// One default on cluster `k`: its position along its locus first, then its rotation
    /// about its pivot, then its position, then its direction, then its dimension.
    fn default_on(&mut self, k: usize) -> bool {
        let rec = self.clusters[k].record.clone();
        // A segment held by its end while its length is free: turning it about that end or
        // sizing it (which keeps its start) would let the end go. Its fragments are the
        // segment's own (`segment.rs`), not a default's.
        let held_by_its_dimension = match rec.pos {
            Pos::Pivot { feature, .. } | Pos::On { feature, .. } => {
                rec.free_dim.is_some() && super::depends_on_dim(self.model, feature)
            }
            _ => false,
        };
        if held_by_its_dimension {
            // Pinned at its end: turn it about the end, then size it from the end (its start
            // moves). Its end on a locus with its length free: not yet.
            return match (rec.pos, rec.rot) {
                (Pos::Pivot { at, feature }, Rot::Free) => {
                    let turned = self.turn_about(k, at, feature);
                    if turned {
                        self.clusters[k].record.pos = Pos::Pivot { at, feature };
                    }
                    turned
                }
                (Pos::Pivot { at, .. }, Rot::Known) => self.size_from_end(k, at),
                _ => false,
            };
        }
        match (rec.pos, rec.rot) {
            (
                Pos::On {
                    feature,
                    locus: locus @ (Locus::Line(_) | Locus::Circle(_) | Locus::Conic(_)),
                },
                _,
            ) => {
                self.slide(k, feature, locus);
                true
            }
            (Pos::Pivot { at, feature }, Rot::Free) => self.turn_about(k, at, feature),
            (Pos::Free, _) if !rec.line => self.place(k),
            (Pos::Free, Rot::Free) if rec.line => self.turn_line(k),
            (Pos::Free, Rot::Known) if rec.line => self.shift_line(k),
            (Pos::None, Rot::Free) => self.turn_direction(k),
            _ if rec.free_dim.is_some() && rec.fd.is_empty() => self.size(k),
            _ => false,
        }
    }

    /// The explanation's opening: why a default is needed, and what it assumes.
    fn assume(&self, meaning: &str, name: &str) -> String {
        format!(
            "No constraint, chain or loop fixes this yet: assume {meaning} is the default \
             `{name}` (the sketch's value unless given)"
        )
    }

    /// Feature `f` of cluster `k` slides along `locus`: default its place on it.
    fn slide(&mut self, k: usize, f: GeomId, locus: Locus) {
        let geoms = self.clusters[k].geoms.clone();
        let lreg = locus_reg(locus);
        let fname = self.name(f);
        let from = self.point(f);
        let measure = self.value(
            Op::LocusParam {
                locus: lreg,
                point: from,
            },
            Ty::Scalar,
            format!("where {fname} is on {}", self.word(lreg)),
        );
        let (name, meaning) = match locus {
            Locus::Circle(_) => (
                format!("{fname}_angle"),
                format!(
                    "the angle of {fname} about the centre of {}, from the x axis",
                    self.word(lreg)
                ),
            ),
            Locus::Conic(_) => (
                format!("{fname}_position"),
                format!(
                    "where {fname} is along {}, by its parameter",
                    self.word(lreg)
                ),
            ),
            Locus::Line(_) => (
                format!("{fname}_position"),
                format!(
                    "the position of {fname} along {}, from its base point",
                    self.word(lreg)
                ),
            ),
        };
        let explain = format!(
            "{}: move {} so that {fname} is there.",
            self.assume(&meaning, &name),
            self.group_name(&geoms)
        );
        let t = self.default_value(f, name, meaning, measure);
        let to = self.value(
            Op::LocusPoint { locus: lreg, at: t },
            Ty::Point,
            format!("{fname}'s default place"),
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.placed(k, f, to);
    }

    /// Feature `f` of cluster `k` is now at `to`: the cluster may still turn about it, if it
    /// turns at all. A circle whose centre is now fixed takes the radius its recorded fixed
    /// distances give (the default placed the centre on their common locus), as when an
    /// action places it.
    fn placed(&mut self, k: usize, f: GeomId, to: Reg) {
        let rec = &mut self.clusters[k].record;
        if rec.rot == Rot::Free {
            rec.pos = Pos::Pivot { at: to, feature: f };
            self.insert_known(f, to);
        } else {
            rec.pos = Pos::Fixed;
            self.settle(k);
        }
    }

    /// Cluster `k` may only turn about `feature` at `at`: default its angle, the direction
    /// from the pivot to another of its points (or of one of its directions).
    fn turn_about(&mut self, k: usize, at: Reg, feature: GeomId) -> bool {
        let Some((reference, is_point)) = self.reference(k, feature) else {
            return false;
        };
        let geoms = self.clusters[k].geoms.clone();
        let (gname, pname, rname) = (
            self.name(geoms[0]),
            super::pivot_name(self.model, feature),
            self.name(reference),
        );
        let from = if is_point {
            let p = self.point(reference);
            self.value(
                Op::DirectionTo { from: at, to: p },
                Ty::Vector,
                format!("the direction from {pname} to {rname}"),
            )
        } else {
            self.direction(reference)
        };
        let meaning = if is_point {
            format!(
                "the angle of {gname} about {pname} (of the direction from {pname} to {rname}, from the x axis)"
            )
        } else {
            format!("the angle of {gname} about {pname} (of {rname}, from the x axis)")
        };
        let name = format!("{gname}_angle");
        let explain = format!(
            "{}: turn {} about {pname} to it.",
            self.assume(&meaning, &name),
            self.group_name(&geoms)
        );
        self.turn_to(geoms, at, from, name, meaning, explain);
        let model = self.model;
        let rec = &mut self.clusters[k].record;
        // A segment pinned at its midpoint with its length free still sizes about it.
        if super::pinned_at_midpoint(model, rec).is_none() {
            rec.pos = Pos::Fixed;
        }
        rec.rot = Rot::Known;
        true
    }

    /// A lone line's base point and direction features.
    fn line_features(&self, k: usize) -> Option<(GeomId, GeomId)> {
        let line = *self.clusters[k].geoms.first()?;
        let part = |want: Part| {
            (self.model.geoms[line].parts.iter().copied())
                .find(|&f| matches!(self.model.geoms[f].owner, Owner::Part(_, p) if p == want))
        };
        Some((part(Part::BasePoint)?, part(Part::Dir)?))
    }

    /// A lone line free to turn: default its direction's angle, turning it about its base
    /// point (its place across itself stays free).
    fn turn_line(&mut self, k: usize) -> bool {
        let Some((base, dir)) = self.line_features(k) else {
            return false;
        };
        let geoms = self.clusters[k].geoms.clone();
        let lname = self.name(geoms[0]);
        let pivot = self.point(base);
        let from = self.direction(dir);
        let meaning = format!("the angle of {lname}'s direction from the x axis");
        let name = format!("{lname}_angle");
        let explain = format!(
            "{}: turn {lname} about {} to it.",
            self.assume(&meaning, &name),
            self.name(base)
        );
        self.turn_to(geoms, pivot, from, name, meaning, explain);
        self.clusters[k].record.rot = Rot::Known;
        self.place_by_passes(k, dir);
        true
    }

    /// A lone line whose direction is known, free to move across itself: default how far it
    /// moves to the left of its direction from where it is (zero on the sketch: least motion).
    fn shift_line(&mut self, k: usize) -> bool {
        let Some((base, dir)) = self.line_features(k) else {
            return false;
        };
        let geoms = self.clusters[k].geoms.clone();
        let lname = self.name(geoms[0]);
        let from = self.point(base);
        let d = self.direction(dir);
        let measure = self.value(Op::Const(0.0), Ty::Scalar, "0".into());
        let meaning = format!(
            "how far {lname} moves across itself, to the left of its direction, from its sketch place"
        );
        let name = format!("{lname}_offset");
        let explain = format!(
            "{}: move {lname} across itself by it.",
            self.assume(&meaning, &name)
        );
        let by = self.default_value(geoms[0], name, meaning, measure);
        let moved = self.value(
            Op::Line {
                point: from,
                dir: d,
                offset: Some(by),
            },
            Ty::Line,
            format!("{lname} moved across itself"),
        );
        let to = self.value(
            Op::Nearest {
                locus: moved,
                point: from,
            },
            Ty::Point,
            format!("{}'s default place", self.name(base)),
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.clusters[k].record.pos = Pos::Fixed;
        true
    }

    /// A free direction (a vector geom): default its angle.
    fn turn_direction(&mut self, k: usize) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let v = geoms[0];
        if self.model.geoms[v].kind != GeomKind::Vector {
            return false;
        }
        let vname = self.name(v);
        let from = self.direction(v);
        let origin = self.origin();
        let meaning = format!("the angle of {vname} from the x axis");
        let name = format!("{vname}_angle");
        let explain = format!("{}: turn {vname} to it.", self.assume(&meaning, &name));
        self.turn_to(geoms, origin, from, name, meaning, explain);
        self.clusters[k].record.rot = Rot::Known;
        true
    }

    /// Turns `geoms` about `pivot` so that direction `from` makes a default angle with the x
    /// axis, measured on the sketch from `from` itself.
    fn turn_to(
        &mut self,
        geoms: Vec<GeomId>,
        pivot: Reg,
        from: Reg,
        name: String,
        meaning: String,
        explain: String,
    ) {
        let measure = self.value(
            PlanarOp::AngleOf(from),
            Ty::Scalar,
            format!("the angle of {}", self.word(from)),
        );
        let angle = self.default_value(geoms[0], name.clone(), meaning, measure);
        let x = self.value(PlanarOp::Axis(1.0, 0.0), Ty::Vector, "the X axis".into());
        let to = self.value(
            PlanarOp::Rotated { dir: x, angle },
            Ty::Vector,
            format!("the direction at `{name}`"),
        );
        self.emit(
            Op::RotateDir {
                geoms,
                pivot,
                axis: RotationAxis::Normal,
                from,
                to,
            },
            None,
            Vec::new(),
            explain,
        );
    }

    /// Cluster `k` is free to translate: default the coordinates of its first point.
    fn place(&mut self, k: usize) -> bool {
        let Some(f) = self.first_point_feature(k) else {
            return false;
        };
        let geoms = self.clusters[k].geoms.clone();
        let fname = self.name(f);
        let from = self.point(f);
        let origin = self.origin();
        let mut coords = [Reg(0); 2];
        for (i, (axis, (x, y))) in [("x", (1.0, 0.0)), ("y", (0.0, 1.0))]
            .into_iter()
            .enumerate()
        {
            let words = format!("the {} axis", axis.to_uppercase());
            let dir = self.value(PlanarOp::Axis(x, y), Ty::Vector, words);
            let measure = self.value(
                Op::Along {
                    from: origin,
                    dir,
                    to: from,
                },
                Ty::Scalar,
                format!("the {axis} coordinate of {fname}"),
            );
            let meaning = format!("the {axis} coordinate of {fname}");
            coords[i] = self.default_value(f, format!("{fname}_{axis}"), meaning, measure);
        }
        let to = self.value(
            PlanarOp::PointXY {
                x: coords[0],
                y: coords[1],
            },
            Ty::Point,
            format!("{fname}'s default position"),
        );
        let explain = format!(
            "{}: translate {} so that {fname} is there.",
            self.assume(
                &format!("the position of {fname}"),
                &format!("{fname}_x, {fname}_y")
            ),
            self.group_name(&geoms)
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.placed(k, f, to);
        true
    }

    /// A free dimension (a circle's radius, a segment's length): default it.
    fn size(&mut self, k: usize) -> bool {
        let Some(g) = self.clusters[k].record.free_dim else {
            return false;
        };
        let gname = self.name(g);
        let what = if self.model.geoms[g].kind == GeomKind::Circle {
            "radius"
        } else {
            "length"
        };
        let measure = self.value(Op::DimOf(g), Ty::Scalar, format!("the {what} of {gname}"));
        let meaning = format!("the {what} of {gname}");
        let name = format!("{gname}_{what}");
        let explain = format!("{}: size {gname} to it.", self.assume(&meaning, &name));
        let value = self.default_value(g, name, meaning, measure);
        let midpoint = super::pinned_at_midpoint(self.model, &self.clusters[k].record);
        self.emit(Op::SetDim { geom: g, value }, None, Vec::new(), explain);
        if let Some((at, seg)) = midpoint {
            // Sizing keeps the start: move the segment back so that its midpoint is where it
            // is pinned.
            self.back_to_midpoint(k, seg, at, Vec::new(), "");
        }
        let rec = &mut self.clusters[k].record;
        rec.free_dim = None;
        rec.fixed_dims.push(g);
        true
    }

    /// A segment pinned at its end (at `at`) with its direction known and its length free:
    /// default the length, keeping the end: the start goes to the end less the length along
    /// the direction, then the length is set.
    fn size_from_end(&mut self, k: usize, at: Reg) -> bool {
        let Some(seg) = self.clusters[k].record.free_dim else {
            return false;
        };
        let (Some(start), Some(dir)) = (
            self.model.part(seg, Part::Start),
            self.model.part(seg, Part::Dir),
        ) else {
            return false;
        };
        let geoms = self.clusters[k].geoms.clone();
        let sname = self.name(seg);
        let d = self.direction(dir);
        let line = self.value(
            Op::Line {
                point: at,
                dir: d,
                offset: None,
            },
            Ty::Line,
            format!("the line of {sname} through its end"),
        );
        let measure = self.value(Op::DimOf(seg), Ty::Scalar, format!("the length of {sname}"));
        let meaning = format!("the length of {sname}");
        let name = format!("{sname}_length");
        let explain = format!(
            "{}: move {sname}'s start back from its end by it, and size {sname} to it.",
            self.assume(&meaning, &name)
        );
        let len = self.default_value(seg, name, meaning, measure);
        let back = self.value(
            Op::Neg(len),
            Ty::Scalar,
            format!("minus the length of {sname}"),
        );
        let to = self.value(
            Op::LocusPoint {
                locus: line,
                at: back,
            },
            Ty::Point,
            format!("{}'s default place", self.name(start)),
        );
        let from = self.point(start);
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.emit(
            Op::SetDim {
                geom: seg,
                value: len,
            },
            None,
            Vec::new(),
            format!("Size {sname} to `{sname}_length`: its end is back where it is pinned."),
        );
        let rec = &mut self.clusters[k].record;
        rec.pos = Pos::Fixed;
        rec.free_dim = None;
        rec.fixed_dims.push(seg);
        true
    }

    /// The world's origin, for coordinates and turns of free directions.
    fn origin(&mut self) -> Reg {
        let zero = self.value(Op::Const(0.0), Ty::Scalar, "0".into());
        self.value(
            PlanarOp::PointXY { x: zero, y: zero },
            Ty::Point,
            "the origin".into(),
        )
    }

    /// A feature of cluster `k` other than `pivot` whose direction from the pivot (a point) or
    /// whose own direction (a vector) tells the cluster's angle: the first in model order.
    fn reference(&self, k: usize, pivot: GeomId) -> Option<(GeomId, bool)> {
        let model = self.model;
        // A segment pinned at its midpoint turns about it: its own direction tells its angle.
        if model.geoms[pivot].kind == GeomKind::Segment {
            return model.part(pivot, Part::Dir).map(|d| (d, false));
        }
        let mut features = Vec::new();
        for &g in &self.clusters[k].geoms {
            features.push(g);
            features.extend(model.geoms[g].parts.iter().copied());
        }
        // A line's `L.point` is its base point again: its direction tells the angle.
        let base_point =
            |f: GeomId| matches!(model.geoms[f].owner, Owner::Part(_, Part::BasePoint));
        let distinct_point = |f: GeomId| {
            model.geoms[f].kind.is_pointlike()
                && f != pivot
                && !base_point(f)
                && model.constant_distance(pivot, f).is_none_or(|d| d > 0.0)
        };
        if let Some(&p) = features.iter().find(|&&f| distinct_point(f)) {
            return Some((p, true));
        }
        features
            .into_iter()
            .find(|&f| model.geoms[f].kind == GeomKind::Vector)
            .map(|v| (v, false))
    }
}
