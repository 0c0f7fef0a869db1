//! Defaults in space (000, section 5.2.1): when neither action nor locus analysis nor a rigid
//! chain or loop applies, one freedom of one cluster is fixed at a default parameter with a
//! geometric meaning, read from its record: a segment's length or a circle's radius, a
//! feature's place on the line, circle or surface it is held on, a free point's coordinates, a
//! line's or plane's place across itself, a direction's tilt and roll, a body's turns about
//! its pivot or its one axis. Each sketch value moves nothing (least motion).

use super::relation::Relation;
use super::{Locus, Shape, Spatial, Target, Trans, Turn};
use crate::analysis::driver::Builder;
use crate::plan::{Op, Reg, SpatialOp, Ty};
use gcs_lang::model::{GeomId, GeomKind, Part};

/// How near parallel (one less the cosine) a direction and an axis are, on the sketch, for a
/// turn about that axis to be taken as unable to change the angle to it
/// ([`Builder::default_leaves_degenerate`]): the sketch's own rounding, well below any angle
/// drawn on purpose.
const PARALLEL_AT_SKETCH: f64 = 1e-9;

impl Builder<'_, Spatial> {
    /// One default on cluster `k` (000, section 5.2.1), each with its geometric meaning and
    /// a sketch value that moves nothing (least motion): a feature's place along the line or
    /// circle it is held on; a turn about the one axis left (the idle spin of an RSSR's
    /// coupler about its own line); a free point's coordinates; a body's turns about the
    /// world's axes through its pivot or the feature it holds on a locus. A translation left
    /// on a plane or sphere with the orientation known, and a free direction, have none yet.
    pub(super) fn default_on(&mut self, k: usize) -> bool {
        let rec = self.clusters[k].record.clone();
        if !rec.movable() {
            return false;
        }
        match (rec.trans, rec.turn) {
            // A segment's length or a circle's radius first, while the record still says which
            // point is held (a new length keeps the start: a held end is moved back).
            _ if rec.shape.size_free() && !self.size_pending(k) => self.size_default(k),
            // A direction's free turn: two turns across it (a third, about itself, would
            // move nothing).
            (_, Turn::Free) if rec.shape.one_direction() => self.orient_direction(k),
            (
                Trans::On {
                    feature,
                    locus: locus @ (Locus::Line(_) | Locus::Circle(_)),
                },
                _,
            ) => self.slide(k, feature, locus),
            (_, Turn::Axis { axis, .. }) => self.spin(k, axis),
            // A line whose direction is known: its place across itself, two coordinates on the
            // plane through its point across it (sliding along itself moves nothing).
            (Trans::Free, _) if rec.shape == Shape::Line => self.place_across(k),
            // A plane whose normal is known: its place along its normal (sliding within
            // itself moves nothing).
            (Trans::Free, _) if rec.shape == Shape::Plane => self.place_along_normal(k),
            (Trans::Free, _) => self.place(k),
            // Held on a surface with nothing left to turn: its two coordinates on it.
            (
                Trans::On {
                    feature,
                    locus:
                        locus @ (Locus::Plane(_)
                        | Locus::Sphere(_)
                        | Locus::Cylinder(_)
                        | Locus::Torus(_)),
                },
                Turn::Known | Turn::None,
            ) => self.place_on(k, feature, locus),
            // About a pivot, or a feature held on a plane or sphere: its turns first (the
            // feature stays on its locus), then what the constraints can do with them.
            (_, Turn::Free) if rec.shape == Shape::Body => self.orient(k),
            _ => false,
        }
    }

    /// Whether the default [`Self::default_on`] would give cluster `k`, a turn about its one
    /// axis, leaves a pending angle (or parallel) relation degenerate at the sketch: one
    /// between a direction of `k` and one of a cluster `j` that turns about an axis, where
    /// `k`'s direction lies along `j`'s axis. Every turn of `j` then keeps the angle, so the
    /// relation does not fix `j`'s turn; a default on `j` instead leaves `k` to turn to the
    /// angle. What the choice of the cluster to default reads from the sketch (000 picks by
    /// DOF, which cannot tell the two apart).
    pub(super) fn default_leaves_degenerate(&self, k: usize) -> bool {
        if !self.takes_spin(k) {
            return false;
        }
        let pairs: Vec<(GeomId, Reg)> = (self.pending.iter())
            .filter_map(|r| match r.relation {
                Relation::Angle { u, v, .. } | Relation::Parallel { u, v, .. } => Some((u, v)),
                _ => None,
            })
            .flat_map(|(u, v)| [(u, v), (v, u)])
            .filter(|&(mine, other)| self.cluster(mine) == k && self.cluster(other) != k)
            .filter_map(
                |(mine, other)| match self.clusters[self.cluster(other)].record.turn {
                    Turn::Axis { axis, .. } => Some((mine, axis)),
                    _ => None,
                },
            )
            .collect();
        if pairs.is_empty() {
            return false;
        }
        (self.sketch_cosines(&pairs).unwrap_or_default().iter())
            .any(|&c| c >= 1.0 - PARALLEL_AT_SKETCH)
    }

    /// Whether [`Self::default_on`] would give cluster `k` its turn about its one axis.
    fn takes_spin(&self, k: usize) -> bool {
        let rec = &self.clusters[k].record;
        if !rec.movable() || (rec.shape.size_free() && !self.size_pending(k)) {
            return false;
        }
        match (rec.trans, rec.turn) {
            (_, Turn::Free) => false,
            (
                Trans::On {
                    locus: Locus::Line(_) | Locus::Circle(_),
                    ..
                },
                _,
            ) => false,
            (_, Turn::Axis { .. }) => true,
            _ => false,
        }
    }

    fn assume(meaning: &str, name: &str) -> String {
        format!(
            "No constraint, chain or loop fixes this yet: assume {meaning} is the default `{name}` (the sketch's value unless given)"
        )
    }

    /// Whether a relation still to come can set the size of cluster `k`'s segment or circle
    /// (a length or radius, an `equal`, a point on the circle): its size then takes no
    /// default, so that the relation sets it rather than being closed by an iteration.
    fn size_pending(&self, k: usize) -> bool {
        let [g] = self.clusters[k].geoms[..] else {
            return false;
        };
        self.pending.iter().any(|p| match p.relation {
            Relation::Size { geom, .. } => geom == g,
            Relation::SameSize { a, b } => a == g || b == g,
            // A circle through a known point sets its radius once its centre is held
            // (`circle_through`); carried with its centre free, it keeps it.
            Relation::PointCircle {
                circle, d: None, ..
            } => {
                circle == g
                    && (self.model.part(circle, Part::Center)).is_some_and(|c| self.point_known(c))
            }
            _ => false,
        })
    }

    /// A segment's length or a circle's radius still free: a default, the size where the
    /// constraints leave it (least motion).
    fn size_default(&mut self, k: usize) -> bool {
        let [g] = self.clusters[k].geoms[..] else {
            return false;
        };
        let what = match self.clusters[k].record.shape {
            Shape::Circle { .. } => "radius",
            _ => "length",
        };
        let gname = self.name(g);
        let measure = self.size_of(g);
        let (name, meaning) = (format!("{gname}_{what}"), format!("the {what} of {gname}"));
        let size = self.default_value(g, name.clone(), meaning.clone(), measure);
        let held_end = self.held_end(k, g);
        let explain = format!(
            "{}: give {gname} that {what}.",
            Self::assume(&meaning, &name)
        );
        self.resize(g, size, held_end, explain, Vec::new());
        let rec = &mut self.clusters[k].record;
        rec.shape = rec.shape.sized();
        true
    }

    /// A line (cluster `k`) whose direction is known, free to move across itself: its point's
    /// two coordinates on the plane through it across the line (`place_on`).
    fn place_across(&mut self, k: usize) -> bool {
        let line = self.clusters[k].geoms[0];
        let Some(dir) = self.model.part(line, Part::Dir) else {
            return false;
        };
        let (point, normal) = (self.point(line), self.direction(dir));
        let words = format!("the plane through {} across it", self.name(line));
        let plane = self.value(
            SpatialOp::Plane {
                point,
                normal,
                offset: None,
            },
            Ty::Plane,
            words,
        );
        self.place_on(k, line, Locus::Plane(plane))
    }

    /// A plane whose normal is known, free to translate: default its place on the line
    /// through its point along its normal.
    fn place_along_normal(&mut self, k: usize) -> bool {
        let plane = self.clusters[k].geoms[0];
        let Some(normal) = self.model.part(plane, Part::Normal) else {
            return false;
        };
        let (point, dir) = (self.point(plane), self.direction(normal));
        let words = format!("the line through {} along its normal", self.name(plane));
        let line = self.line(point, dir, words);
        self.slide(k, plane, Locus::Line(line))
    }

    /// Feature `f` of cluster `k` held on a line or circle: default its place on it (the
    /// distance along the line from its point, the angle about the circle's axis).
    fn slide(&mut self, k: usize, f: GeomId, locus: Locus) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let fname = self.name(f);
        let from = self.point(f);
        let l = locus.reg();
        let measure = self.value(
            Op::LocusParam {
                locus: l,
                point: from,
            },
            Ty::Scalar,
            format!("the place of {fname} on {}", self.word(l)),
        );
        let meaning = format!("the place of {fname} on {}", self.word(l));
        let name = format!("{fname}_place");
        let at = self.default_value(f, name.clone(), meaning.clone(), measure);
        let to = self.value(
            Op::LocusPoint { locus: l, at },
            Ty::Point,
            format!("{fname}'s default place"),
        );
        let explain = format!(
            "{}: move {} so that {fname} is there.",
            Self::assume(&meaning, &name),
            self.group_name(&geoms)
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.placed(k, f, to, Target::Point(to));
        true
    }

    /// Cluster `k` with feature `f` held on a surface (a plane, a sphere, a cylinder) and
    /// nothing left to turn: default `f`'s two coordinates on it (`runtime::locus3d::Surface`
    /// says which), where the constraints leave it.
    fn place_on(&mut self, k: usize, f: GeomId, locus: Locus) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let fname = self.name(f);
        let from = self.point(f);
        let l = locus.reg();
        let words = match locus {
            Locus::Sphere(_) => ["longitude", "latitude"],
            Locus::Cylinder(_) => ["angle", "height"],
            Locus::Torus(_) => ["angle about its axis", "angle about its circle"],
            _ => ["first coordinate", "second coordinate"],
        };
        // An angle's name ends in `_angle`: an iteration steps and wraps it as one.
        let suffixes = match locus {
            Locus::Sphere(_) => ["longitude_angle", "latitude_angle"],
            Locus::Cylinder(_) => ["angle", "height"],
            Locus::Torus(_) => ["axis_angle", "tube_angle"],
            _ => ["u", "v"],
        };
        let mut uv = [Reg(0); 2];
        for (i, (what, suffix)) in words.into_iter().zip(suffixes).enumerate() {
            let meaning = format!("the {what} of {fname} on {}", self.word(l));
            let measure = self.value(
                SpatialOp::SurfaceParam {
                    locus: l,
                    point: from,
                    component: i as u8,
                },
                Ty::Scalar,
                meaning.clone(),
            );
            uv[i] = self.default_value(f, format!("{fname}_{suffix}"), meaning, measure);
        }
        let to = self.value(
            SpatialOp::SurfacePoint {
                locus: l,
                u: uv[0],
                v: uv[1],
            },
            Ty::Point,
            format!("{fname}'s default place on {}", self.word(l)),
        );
        let explain = format!(
            "{}: move {} so that {fname} is there.",
            Self::assume(
                &format!("the place of {fname} on {}", self.word(l)),
                &format!("{fname}_{}, {fname}_{}", suffixes[0], suffixes[1])
            ),
            self.group_name(&geoms)
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.placed(k, f, to, Target::Point(to));
        true
    }

    /// Cluster `k` free to translate: default its first point's coordinates.
    fn place(&mut self, k: usize) -> bool {
        let Some(f) = self.first_point(k) else {
            return false;
        };
        let geoms = self.clusters[k].geoms.clone();
        let fname = self.name(f);
        let from = self.point(f);
        let mut coords = [Reg(0); 3];
        for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
            let meaning = format!("the {axis} coordinate of {fname}");
            let measure = self.value(
                SpatialOp::Coordinate {
                    point: from,
                    axis: i as u8,
                },
                Ty::Scalar,
                meaning.clone(),
            );
            coords[i] = self.default_value(f, format!("{fname}_{axis}"), meaning, measure);
        }
        let to = self.value(
            SpatialOp::PointAt {
                x: coords[0],
                y: coords[1],
                z: coords[2],
            },
            Ty::Point,
            format!("{fname}'s default position"),
        );
        let explain = format!(
            "{}: translate {} so that {fname} is there.",
            Self::assume(
                &format!("the position of {fname}"),
                &format!("{fname}_x, {fname}_y, {fname}_z")
            ),
            self.group_name(&geoms)
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        self.placed(k, f, to, Target::Point(to));
        true
    }

    /// The first point feature of cluster `k`'s geoms: a point geom itself, else a body's
    /// first member point or marker, else the body's origin.
    fn first_point(&self, k: usize) -> Option<GeomId> {
        let g = *self.clusters[k].geoms.first()?;
        let geom = &self.model.geoms[g];
        if geom.kind == GeomKind::Point {
            return Some(g);
        }
        let member =
            (geom.parts.iter().copied()).find(|&m| self.model.geoms[m].kind.is_pointlike());
        Some(member.unwrap_or(g))
    }

    /// A body about a fixed point, free to turn: default its turns about the world's x, y
    /// and z axes through that point, in that order, from where the constraints leave it.
    fn orient(&mut self, k: usize) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let gname = self.name(geoms[0]);
        let pivot = self.pivot_of(k);
        for (i, axis) in ["x", "y", "z"].into_iter().enumerate() {
            let words = format!("the {} axis", axis.to_uppercase());
            let a = self.value(SpatialOp::WorldAxis(i as u8), Ty::Vector, words);
            self.turn_by_default(&geoms, pivot, a, format!("{gname}_{axis}_angle"));
        }
        self.turned(k);
        true
    }

    /// Turns `geoms` about the axis through `pivot` along `axis` by a default named `name`,
    /// counted from where the constraints leave them (0: least motion).
    fn turn_by_default(&mut self, geoms: &[GeomId], pivot: Reg, axis: Reg, name: String) {
        let gname = self.name(geoms[0]);
        // A world axis is named with the point it turns about; a body's own axis says it.
        let through = match self.def(axis).map(|s| &s.op) {
            Some(Op::Spatial(SpatialOp::WorldAxis(_))) => format!(" through {}", self.word(pivot)),
            _ => String::new(),
        };
        let meaning = format!(
            "the turn of {gname} about {}{through}, from where the constraints leave it",
            self.word(axis)
        );
        let zero = self.value(Op::Const(0.0), Ty::Scalar, "0".into());
        let angle = self.default_value(geoms[0], name.clone(), meaning.clone(), zero);
        let explain = format!(
            "No constraint, chain or loop fixes this yet: assume {meaning} is the default `{name}` (0, least motion, unless given): turn {} about that axis by it.",
            self.group_name(geoms)
        );
        self.emit(
            SpatialOp::RotateBy {
                geoms: geoms.to_vec(),
                pivot,
                axis,
                angle,
            },
            None,
            Vec::new(),
            explain,
        );
    }

    /// A direction free to turn (a vector's, a line's, a plane's normal, a circle's normal):
    /// two defaults, its turns about a direction across it and about the direction across
    /// both, from where the constraints leave it (turning about itself moves nothing).
    fn orient_direction(&mut self, k: usize) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let Some(dir) = self.own_direction(geoms[0]) else {
            return false;
        };
        let gname = self.name(geoms[0]);
        let pivot = self.pivot_of(k);
        let d = self.direction(dir);
        let words = format!("a direction across {}", self.name(dir));
        let across = self.value(SpatialOp::Across(d), Ty::Vector, words);
        let quarter = self.value(
            Op::Const(std::f64::consts::FRAC_PI_2),
            Ty::Scalar,
            "a right angle".into(),
        );
        let words = format!("the direction across {} and that direction", self.name(dir));
        let both = self.value(
            SpatialOp::TurnedAbout {
                dir: across,
                axis: d,
                angle: quarter,
            },
            Ty::Vector,
            words,
        );
        self.turn_by_default(&geoms, pivot, across, format!("{gname}_tilt_angle"));
        self.turn_by_default(&geoms, pivot, both, format!("{gname}_roll_angle"));
        self.turned(k);
        true
    }

    /// The direction feature that is a one-direction geom's orientation: a vector itself, a
    /// line's or segment's direction, a plane's or circle's normal.
    fn own_direction(&self, g: GeomId) -> Option<GeomId> {
        match self.model.geoms[g].kind {
            GeomKind::Vector => Some(g),
            GeomKind::Plane | GeomKind::Circle => self.model.part(g, Part::Normal),
            GeomKind::Line | GeomKind::Segment => self.model.line_features(g).map(|(_, d)| d),
            _ => None,
        }
    }

    /// A body that may only turn about `axis`: default that turn.
    fn spin(&mut self, k: usize, axis: Reg) -> bool {
        let geoms = self.clusters[k].geoms.clone();
        let pivot = self.pivot_of(k);
        let name = format!("{}_spin_angle", self.name(geoms[0]));
        self.turn_by_default(&geoms, pivot, axis, name);
        self.turned(k);
        true
    }
}
