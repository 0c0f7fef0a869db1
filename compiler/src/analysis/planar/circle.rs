//! Plan fragments for circles of variable radius: fixed-distance lines and points (the last
//! slots of Table 2), and 002's reformulation rules that turn two of them into a locus of the
//! centre: two lines give an angular bisector (RR-1), a line and a point (or circle) a
//! parabola, two points (or circles) a hyperbola branch or an ellipse.
//!
//! A fixed distance ties the centre to the radius. While the radius is free it is only
//! recorded (its constraint is satisfied by the step that finally places the circle); once the
//! radius is fixed it becomes a locus of the centre; once the centre is fixed it gives the
//! radius.

use super::relation::{Nesting, Relation};
use super::{Locus, Planar, Pos, Rel, Target};
use crate::analysis::driver::Builder;
use crate::analysis::geometry::Invariants;
use crate::plan::{Op, PlanarOp, Reg, Ty};
use gcs_lang::model::{ConstraintId, GeomId, Part};

/// A fixed-distance invariant of a circle with centre `X` and free radius `ρ`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Fd {
    /// `sd_line(X) = ρ + a`: the circle on the line's left, its perimeter `a` from it.
    Line {
        /// The line, directed so that the circle is on its left.
        line: Reg,
        /// The gap.
        a: Reg,
        /// The line's features, a point on it and its direction, by which
        /// [`Builder::tangent_at_line`] tells a point constrained onto it.
        base: GeomId,
        /// See `base`.
        dir: GeomId,
        /// The constraint it records.
        constraint: ConstraintId,
        /// Whether that is the constraint's last relation.
        last: bool,
    },
    /// `|X - at| = ρ + b` (`plus`) or `b - ρ`.
    Point {
        /// The fixed point (a point, or the centre of a fixed circle).
        at: Reg,
        /// The offset.
        b: Reg,
        /// Which sense.
        plus: bool,
        /// The point feature at `at`, if it is one (not a circle's centre).
        p: Option<GeomId>,
        /// The constraint it records.
        constraint: ConstraintId,
        /// Whether that is the constraint's last relation.
        last: bool,
    },
}

impl Fd {
    /// Whether it is a fixed-distance line.
    pub fn is_line(&self) -> bool {
        matches!(self, Fd::Line { .. })
    }

    /// The constraint it records, and whether that is the constraint's last relation.
    pub fn constraint(&self) -> (ConstraintId, bool) {
        match *self {
            Fd::Line {
                constraint, last, ..
            }
            | Fd::Point {
                constraint, last, ..
            } => (constraint, last),
        }
    }

    /// The constraint this fixed distance satisfies once the circle is placed, if it is the
    /// constraint's last relation.
    pub fn satisfies(&self) -> Option<ConstraintId> {
        match *self {
            Fd::Line {
                constraint, last, ..
            }
            | Fd::Point {
                constraint, last, ..
            } => last.then_some(constraint),
        }
    }
}

impl Builder<'_, Planar> {
    /// The relations that involve a circle's radius, when not implied (`action` checks
    /// those). Returns whether the relation was satisfied or recorded.
    pub(super) fn circle_relation(&mut self, r: &Rel) -> bool {
        match r.relation.clone() {
            Relation::PointCircle {
                p,
                circle,
                gap,
                outside,
            } => {
                let centre = self.centre(circle);
                let circle_known = self.record(circle).grounded();
                let p_known = self.point_known(p);
                let sign = if outside { 1.0 } else { -1.0 };
                if circle_known && gap.is_none() {
                    if let Some(foot) = self.touching_point(p, circle) {
                        return self.move_feature(p, Target::Point(foot), r);
                    }
                }
                if circle_known {
                    let at = self.point(centre);
                    let radius = self.dim_of(circle);
                    let mut terms = vec![(1.0, radius)];
                    if let Some(g) = gap {
                        terms.push((sign, self.expr(g)));
                    }
                    let rr = self.sum(terms);
                    let words = format!(
                        "the circle of radius {} about {}",
                        self.word(rr),
                        self.name(centre)
                    );
                    let c = self.value(
                        PlanarOp::Circle {
                            center: at,
                            radius: rr,
                        },
                        Ty::Circle,
                        words,
                    );
                    self.centers.insert(c, self.name(centre));
                    let done = self.move_feature(p, Target::On(Locus::Circle(c)), r);
                    if done && gap.is_none() && self.end_of_segment(p).is_some() {
                        let k = self.cluster(p);
                        self.clusters[k].record.on_circle = Some((p, circle));
                    }
                    return done;
                }
                if p_known && gap.is_none() {
                    if let Some(foot) = self.centre_from_joint(p, circle) {
                        return self.move_feature(centre, Target::Point(foot), r);
                    }
                }
                if p_known {
                    let at = self.point(p);
                    let b = match gap {
                        Some(g) => {
                            let e = self.expr(g);
                            self.sum(vec![(sign, e)])
                        }
                        None => self.value(Op::Const(0.0), Ty::Scalar, "0".into()),
                    };
                    let fd = Fd::Point {
                        at,
                        b,
                        plus: true,
                        p: Some(p),
                        constraint: r.constraint,
                        last: r.last,
                    };
                    let radius_known = self.record(circle).free_dim.is_none();
                    let done = self.add_fd(circle, fd, r);
                    if done && radius_known && gap.is_none() {
                        let k = self.cluster(circle);
                        self.clusters[k].record.joint = Some(p);
                    }
                    return done;
                }
                false
            }
            Relation::CircleLine {
                circle,
                base,
                dir,
                gap,
                side,
            } => {
                let done = self.circle_line(r, circle, base, dir, gap, side);
                if done && gap.is_none() {
                    let k = self.cluster(circle);
                    self.clusters[k].record.tangent.push(dir);
                }
                done
            }
            _ => self.circle_pair(r),
        }
    }

    /// The segment `p` is an end of, and its direction feature; `None` for any other point.
    fn end_of_segment(&self, p: GeomId) -> Option<(GeomId, GeomId)> {
        match self.model.geoms[p].owner {
            gcs_lang::model::Owner::Part(seg, Part::Start | Part::End) => {
                Some((seg, self.model.part(seg, Part::Dir)?))
            }
            _ => None,
        }
    }

    /// A segment's end `p` to be put on `circle`, when the segment's line is known and was
    /// made tangent to the circle: the touching point, the foot of the centre on the line.
    fn touching_point(&mut self, p: GeomId, circle: GeomId) -> Option<Reg> {
        let (seg, dir) = self.end_of_segment(p)?;
        let start = self.model.part(seg, Part::Start)?;
        if !self.record(circle).tangent.contains(&dir) || !self.line_fixed(start, dir) {
            return None;
        }
        let anchor = self.line_point(start).unwrap_or(start);
        let (at, d) = (self.point(anchor), self.dir(super::Dir::Feature(dir)));
        let line = self.value(
            Op::Line {
                point: at,
                dir: d,
                offset: None,
            },
            Ty::Line,
            format!("the line of {}", self.name(seg)),
        );
        let centre = self.centre(circle);
        let c = self.point(centre);
        Some(self.value(
            Op::Nearest {
                locus: line,
                point: c,
            },
            Ty::Point,
            format!(
                "where {} touches {} (the foot of {} on it)",
                self.name(seg),
                self.name(circle),
                self.name(centre)
            ),
        ))
    }

    /// The centre of `circle`, of known radius and already on the line its tangency to a
    /// segment made, when known point `p`, an end of that segment, must be on it too: `p`'s
    /// foot on that line (the point on the line of centres), where the circle about `p` and
    /// the line only touch, a double root an intersection would find to the square root of
    /// rounding.
    fn centre_from_joint(&mut self, p: GeomId, circle: GeomId) -> Option<Reg> {
        let (_, dir) = self.end_of_segment(p)?;
        let rec = self.record(circle);
        let centre = self.centre(circle);
        let (
            true,
            None,
            Pos::On {
                feature,
                locus: Locus::Line(line),
            },
        ) = (rec.tangent.contains(&dir), rec.free_dim, rec.pos)
        else {
            return None;
        };
        if feature != centre {
            return None;
        }
        let at = self.point(p);
        Some(self.value(
            Op::Nearest {
                locus: line,
                point: at,
            },
            Ty::Point,
            format!(
                "the centre across from {} (the foot of {} on {})",
                self.name(p),
                self.name(p),
                self.word(line)
            ),
        ))
    }

    /// The centre of `circle`, of known radius and already on the circle about its joint (an
    /// end of the segment along `dir`), when that segment's line must touch it: the joint's
    /// foot on the line of centres `fd` makes, where the two loci only touch.
    fn joint_foot(&mut self, circle: GeomId, dir: GeomId, fd: Fd) -> Option<Reg> {
        let rec = self.record(circle).clone();
        let centre = self.centre(circle);
        let (Some(joint), None, Pos::On { feature, .. }) = (rec.joint, rec.free_dim, rec.pos)
        else {
            return None;
        };
        let (_, joint_dir) = self.end_of_segment(joint)?;
        if feature != centre || joint_dir != dir {
            return None;
        }
        let Locus::Line(line) = self.fd_locus(circle, fd) else {
            return None;
        };
        let at = self.point(joint);
        Some(self.value(
            Op::Nearest {
                locus: line,
                point: at,
            },
            Ty::Point,
            format!(
                "the centre across from {} (its foot on {})",
                self.name(joint),
                self.word(line)
            ),
        ))
    }

    /// A segment end already on known `circle` (and turning nowhere: the segment's direction
    /// is known) whose line must now touch the circle at signed distance `d` from its centre:
    /// the end and the touching point, the centre's foot on the tangent line.
    fn end_touching(
        &mut self,
        circle: GeomId,
        base: GeomId,
        dir: GeomId,
        d: Reg,
    ) -> Option<(GeomId, Reg)> {
        let rec = self.record(base).clone();
        let (q, c) = rec.on_circle?;
        let (seg, end_dir) = self.end_of_segment(q)?;
        if c != circle
            || rec.rot != super::Rot::Known
            || end_dir != dir
            || !matches!(rec.pos, Pos::On { feature, .. } if feature == q)
        {
            return None;
        }
        let centre = self.centre(circle);
        let at = self.point(centre);
        let dv = self.dir(super::Dir::Feature(dir));
        let back = self.neg(d);
        let line = self.value(
            Op::Line {
                point: at,
                dir: dv,
                offset: Some(back),
            },
            Ty::Line,
            format!(
                "the tangent to {} along {}",
                self.name(circle),
                self.name(dir)
            ),
        );
        let t = self.value(
            Op::Nearest {
                locus: line,
                point: at,
            },
            Ty::Point,
            format!(
                "where {} touches {} (the foot of its centre)",
                self.name(seg),
                self.name(circle)
            ),
        );
        Some((q, t))
    }

    /// The circle-line relation (see [`Self::circle_relation`]).
    fn circle_line(
        &mut self,
        r: &Rel,
        circle: GeomId,
        base: GeomId,
        dir: GeomId,
        gap: Option<gcs_lang::expr::ExprId>,
        side: f64,
    ) -> bool {
        {
            let centre = self.centre(circle);
            let circle_known = self.record(circle).grounded();
            let on_line = self.line_point(base);
            let line_known = self.line_fixed(base, dir);
            let line_base = base;
            let base = on_line.unwrap_or(base);
            let a = match gap {
                Some(g) => self.expr(g),
                None => self.value(Op::Const(0.0), Ty::Scalar, "0".into()),
            };
            if line_known {
                let bp = self.point(base);
                let dv = self.dir(super::Dir::Feature(dir));
                let words = format!(
                    "the line through {} along {}",
                    self.name(base),
                    self.name(dir)
                );
                let mut line = self.value(
                    Op::Line {
                        point: bp,
                        dir: dv,
                        offset: None,
                    },
                    Ty::Line,
                    words,
                );
                if side < 0.0 {
                    let words = format!("{} reversed", self.word(line));
                    line = self.value(PlanarOp::Reversed(line), Ty::Line, words);
                }
                let fd = Fd::Line {
                    line,
                    a,
                    base: line_base,
                    dir,
                    constraint: r.constraint,
                    last: r.last,
                };
                if gap.is_none() {
                    if let Some(foot) = self.joint_foot(circle, dir, fd) {
                        let centre = self.centre(circle);
                        return self.move_feature(centre, Target::Point(foot), r);
                    }
                }
                return self.add_fd(circle, fd, r);
            }
            if circle_known {
                // The line must pass at signed distance side * (r + gap) from the centre.
                let radius = self.dim_of(circle);
                let d = self.sum(vec![(side, radius), (side, a)]);
                if gap.is_none() {
                    if let Some((q, t)) = self.end_touching(circle, base, dir, d) {
                        return self.move_feature(q, Target::Point(t), r);
                    }
                }
                return self.move_line_to_point(centre, base, dir, Some(d), r);
            }
            false
        }
    }

    /// The relations between two circles (see [`Self::circle_relation`]).
    fn circle_pair(&mut self, r: &Rel) -> bool {
        match r.relation.clone() {
            Relation::CircleCircle { a, b, gap, mode } => {
                let (ka, kb) = (self.record(a).grounded(), self.record(b).grounded());
                let (known, free, known_first) = match (ka, kb) {
                    (true, false) => (a, b, true),
                    (false, true) => (b, a, false),
                    _ => return false,
                };
                let at = {
                    let c = self.centre(known);
                    self.point(c)
                };
                let rk = self.dim_of(known);
                let g = gap.map(|g| self.expr(g));
                let with_gap = |s: &mut Self, sign_r: f64, sign_g: f64| {
                    let mut terms = vec![(sign_r, rk)];
                    if let Some(g) = g {
                        terms.push((sign_g, g));
                    }
                    s.sum(terms)
                };
                // |X - c_known| in terms of the free radius, per nesting (see `Nesting`).
                let free_inside = matches!(
                    (mode, known_first),
                    (Nesting::SecondInside, true) | (Nesting::FirstInside, false)
                );
                let known_inside = matches!(
                    (mode, known_first),
                    (Nesting::FirstInside, true) | (Nesting::SecondInside, false)
                );
                let (b, plus) = if free_inside {
                    (with_gap(self, 1.0, -1.0), false)
                } else if known_inside {
                    (with_gap(self, -1.0, -1.0), true)
                } else {
                    (with_gap(self, 1.0, 1.0), true)
                };
                let fd = Fd::Point {
                    at,
                    b,
                    plus,
                    p: None,
                    constraint: r.constraint,
                    last: r.last,
                };
                self.add_fd(free, fd, r)
            }
            _ => false,
        }
    }

    /// The centre feature of a circle.
    fn centre(&self, circle: GeomId) -> GeomId {
        self.model.part(circle, Part::Center).unwrap_or(circle)
    }

    pub(super) fn dim_of(&mut self, g: GeomId) -> Reg {
        let what = if self.model.geoms[g].kind == gcs_lang::model::GeomKind::Circle {
            "radius"
        } else {
            "length"
        };
        let words = format!("the {what} of {}", self.name(g));
        self.value(Op::DimOf(g), Ty::Scalar, words)
    }

    pub(super) fn sum(&mut self, terms: Vec<(f64, Reg)>) -> Reg {
        // Zero constants (a tangency's gap) add nothing.
        let zero = |s: &Self, r: Reg| s.def(r).is_some_and(|st| st.op == Op::Const(0.0));
        let mut terms: Vec<(f64, Reg)> = terms.into_iter().filter(|t| !zero(self, t.1)).collect();
        if terms.is_empty() {
            return self.value(Op::Const(0.0), Ty::Scalar, "0".into());
        }
        let terms = std::mem::take(&mut terms);
        if let [(s, r)] = terms.as_slice() {
            if *s == 1.0 {
                return *r;
            }
        }
        let words = terms
            .iter()
            .enumerate()
            .map(|(i, (s, r))| {
                let w = self.word(*r);
                match (i, *s < 0.0) {
                    (0, true) => format!("-{w}"),
                    (0, false) => w,
                    (_, true) => format!(" - {w}"),
                    (_, false) => format!(" + {w}"),
                }
            })
            .collect::<String>();
        self.value(Op::Sum(terms), Ty::Scalar, words)
    }

    /// Records a fixed-distance invariant on a circle, turning it into a locus of the centre
    /// when the radius is fixed, or into the radius when the centre is.
    fn add_fd(&mut self, circle: GeomId, fd: Fd, r: &Rel) -> bool {
        let k = self.cluster(circle);
        let rec = self.clusters[k].record.clone();
        let centre = self.centre(circle);
        if rec.free_dim.is_none() {
            // Radius fixed: the centre lies on a curve.
            let locus = self.fd_locus(circle, fd);
            return self.move_feature(centre, Target::On(locus), r);
        }
        if rec.pos == Pos::Fixed {
            self.clusters[k].record.fd.push(fd);
            self.settle(k);
            return true;
        }
        match (rec.fd.as_slice(), rec.pos) {
            ([], _) => {
                self.clusters[k].record.fd.push(fd);
                true
            }
            ([first, second], Pos::On { feature, locus }) if rec.fd_locus && feature == centre => {
                // A third fixed distance: the centre is where the locus of the first two meets
                // that of this one with one of them (Apollonius' problems: a circle through
                // three points, tangent to three lines, through two points and tangent to a
                // line...). Of the two, a straight locus if there is one; else not a parabola
                // with the same directrix as the first locus (two such meet in two points, and
                // their quartic has two more at infinity).
                let (first, second) = (*first, *second);
                // Both parabolas about the first locus's directrix: the record's pair is a
                // line and a point, and so would be this one, with the same line.
                let same_directrix =
                    |x: Fd| x.is_line() && !fd.is_line() && first.is_line() != second.is_line();
                let rank = |s: &Self, x: Fd| {
                    if s.straight(x, fd) {
                        0
                    } else if same_directrix(x) {
                        2
                    } else {
                        1
                    }
                };
                let with = if rank(self, second) < rank(self, first) {
                    second
                } else {
                    first
                };
                let other = self.centre_locus(with, fd, circle);
                self.centre_where_loci_meet(k, circle, super::locus_reg(locus), other, fd, r);
                true
            }
            // The centre already on a locus of its own (a distance to a known point, a point
            // on a line), and two fixed distances: on their locus too.
            ([first], Pos::On { feature, locus }) if !rec.fd_locus && feature == centre => {
                let other = self.centre_locus(*first, fd, circle);
                self.centre_where_loci_meet(k, circle, super::locus_reg(locus), other, fd, r);
                true
            }
            ([first], Pos::Free) => {
                let locus = self.centre_locus(*first, fd, circle);
                let rec = &mut self.clusters[k].record;
                rec.fd.push(fd);
                rec.pos = Pos::On {
                    feature: centre,
                    locus,
                };
                rec.fd_locus = true;
                true
            }
            _ => false,
        }
    }

    /// Places the centre of `circle` (cluster `k`) where the locus `own` it is on meets `other`,
    /// records `fd`, and sets the radius (which satisfies every fixed distance recorded).
    fn centre_where_loci_meet(
        &mut self,
        k: usize,
        circle: GeomId,
        own: Reg,
        other: Locus,
        fd: Fd,
        r: &Rel,
    ) {
        let centre = self.centre(circle);
        let from = self.point(centre);
        let to = self.meet(own, Target::On(other), from, r);
        let geoms = self.clusters[k].geoms.clone();
        let explain = format!(
            "The centre of {} must be on {} and on {}: translate {} to where they meet ({}).",
            self.name(circle),
            self.word(own),
            self.word(super::locus_reg(other)),
            self.name(circle),
            self.cname(r.constraint)
        );
        self.emit(Op::Translate { geoms, from, to }, None, Vec::new(), explain);
        let rec = &mut self.clusters[k].record;
        rec.fd.push(fd);
        rec.pos = Pos::Fixed;
        self.settle(k);
    }

    /// Whether the locus of the centre under fixed distances `f1` and `f2` is straight: an
    /// angular bisector, or the perpendicular bisector of two points at the same offset
    /// (the same register, or equal constants: a circle through both).
    fn straight(&self, f1: Fd, f2: Fd) -> bool {
        match (f1, f2) {
            (Fd::Line { .. }, Fd::Line { .. }) => true,
            (
                Fd::Point {
                    b: b1, plus: p1, ..
                },
                Fd::Point {
                    b: b2, plus: p2, ..
                },
            ) => p1 == p2 && self.same_value(b1, b2),
            _ => false,
        }
    }

    /// Whether registers `a` and `b` hold the same value whatever the params: the same
    /// register, or the same constant.
    fn same_value(&self, a: Reg, b: Reg) -> bool {
        let constant = |r: Reg| {
            (self.plan.steps.iter().rev())
                .find(|s| s.out.map(|(o, _)| o) == Some(r))
                .and_then(|s| match s.op {
                    Op::Const(c) => Some(c),
                    _ => None,
                })
        };
        a == b || matches!((constant(a), constant(b)), (Some(x), Some(y)) if x == y)
    }

    /// The perpendicular bisector of `c1` and `c2`: the centres equally far from both.
    fn perpendicular_bisector(&mut self, c1: Reg, c2: Reg, name: &str) -> Locus {
        let towards = self.value(
            Op::DirectionTo { from: c1, to: c2 },
            Ty::Vector,
            format!("the direction from {} to {}", self.word(c1), self.word(c2)),
        );
        let words = format!("{} turned by pi/2", self.word(towards));
        let across = self.quarter_turned(towards, 1.0, words);
        let apart = self.value(
            Op::Along {
                from: c1,
                dir: towards,
                to: c2,
            },
            Ty::Scalar,
            format!("the distance from {} to {}", self.word(c1), self.word(c2)),
        );
        // The line through c1 across the segment, moved half the distance towards c2 (to the
        // right of its direction).
        let back = self.sum(vec![(-0.5, apart)]);
        let words = format!("the perpendicular bisector of centres of {name}");
        Locus::Line(self.value(
            Op::Line {
                point: c1,
                dir: across,
                offset: Some(back),
            },
            Ty::Line,
            words,
        ))
    }

    /// The locus of the centre of `circle`, whose radius is known, that fixed distance `fd`
    /// makes: a line moved off the fixed-distance line, or a circle about the fixed point.
    pub(super) fn fd_locus(&mut self, circle: GeomId, fd: Fd) -> Locus {
        let radius = self.dim_of(circle);
        match fd {
            Fd::Line { line, a, .. } => {
                let by = self.sum(vec![(1.0, radius), (1.0, a)]);
                let words = format!("{} moved {} to its left", self.word(line), self.word(by));
                Locus::Line(self.value(PlanarOp::OffsetLine { line, by }, Ty::Line, words))
            }
            Fd::Point { at, b, plus, .. } => {
                let rr = if plus {
                    self.sum(vec![(1.0, radius), (1.0, b)])
                } else {
                    self.sum(vec![(1.0, b), (-1.0, radius)])
                };
                let words = format!(
                    "the circle of radius {} about {}",
                    self.word(rr),
                    self.word(at)
                );
                let c = self.value(
                    PlanarOp::Circle {
                        center: at,
                        radius: rr,
                    },
                    Ty::Circle,
                    words,
                );
                self.centers.insert(c, self.word(at));
                Locus::Circle(c)
            }
        }
    }

    /// The locus of the centre of a circle of free radius under two fixed distances.
    fn centre_locus(&mut self, f1: Fd, f2: Fd, circle: GeomId) -> Locus {
        let name = self.name(circle);
        if let Some(l) = self.tangent_at(f1, f2, &name) {
            return l;
        }
        if let Some(l) = self.tangent_at_line(f1, f2, &name) {
            return l;
        }
        if let (Fd::Point { at: c1, .. }, Fd::Point { at: c2, .. }) = (f1, f2) {
            if self.straight(f1, f2) {
                return self.perpendicular_bisector(c1, c2, &name);
            }
        }
        match (f1, f2) {
            (
                Fd::Line {
                    line: l1, a: a1, ..
                },
                Fd::Line {
                    line: l2, a: a2, ..
                },
            ) => {
                let words = format!("the bisector of centres of {name}");
                Locus::Line(self.value(
                    PlanarOp::CentresLineLine { l1, a1, l2, a2 },
                    Ty::Line,
                    words,
                ))
            }
            (Fd::Line { line, a, .. }, Fd::Point { at, b, plus, .. })
            | (Fd::Point { at, b, plus, .. }, Fd::Line { line, a, .. }) => {
                let words = format!("the parabola of centres of {name}");
                Locus::Conic(self.value(
                    PlanarOp::CentresLinePoint {
                        line,
                        a,
                        at,
                        b,
                        plus,
                    },
                    Ty::Conic,
                    words,
                ))
            }
            (
                Fd::Point {
                    at: c1,
                    b: b1,
                    plus: p1,
                    ..
                },
                Fd::Point {
                    at: c2,
                    b: b2,
                    plus: p2,
                    ..
                },
            ) => {
                let words = format!("the conic of centres of {name}");
                Locus::Conic(self.value(
                    PlanarOp::CentresPointPoint {
                        c1,
                        b1,
                        p1,
                        c2,
                        b2,
                        p2,
                    },
                    Ty::Conic,
                    words,
                ))
            }
        }
    }

    /// Through a point that lies on a known circle (an `on` constraint already met) and
    /// tangent to that circle: the two fixed distances' conic degenerates (the hyperbola's foci
    /// are as far apart as its difference of distances, the ellipse's as its sum) into the
    /// line of the circle's centre and the point, the normal to the circle there, on which
    /// every circle tangent to it at the point has its centre. `None` otherwise.
    fn tangent_at(&mut self, f1: Fd, f2: Fd, name: &str) -> Option<Locus> {
        let (Fd::Point { at: c1, b: b1, .. }, Fd::Point { at: c2, b: b2, .. }) = (f1, f2) else {
            return None;
        };
        // Which is the point (offset zero) and which the circle's centre (offset its radius).
        let (centre, radius, at) = if self.is_zero(b2) {
            (c1, b1, c2)
        } else if self.is_zero(b1) {
            (c2, b2, c1)
        } else {
            return None;
        };
        let on_it = (self.model.constraints.iter()).any(|(_, c)| {
            let [p, known] = c.args[..] else {
                return false;
            };
            c.kind == gcs_lang::constraints::ConstraintKind::On
                && self.model.geoms[known].kind == gcs_lang::model::GeomKind::Circle
                && self.radius_of(radius) == Some(known)
                && (self.model.part(known, Part::Center))
                    .is_some_and(|k| self.point_known(k) && self.point(k) == centre)
                && self.point_known(p)
                && (self.point(p) == at || self.coincident_at(p, at))
                && self.is_done(&Relation::PointCircle {
                    p,
                    circle: known,
                    gap: None,
                    outside: false,
                })
        });
        if !on_it {
            return None;
        }
        let towards = self.value(
            Op::DirectionTo {
                from: centre,
                to: at,
            },
            Ty::Vector,
            format!(
                "the direction from {} to {}",
                self.word(centre),
                self.word(at)
            ),
        );
        let words = format!(
            "the normal at {} to the circle it lies on, where {name} is tangent",
            self.word(at)
        );
        Some(Locus::Line(self.value(
            Op::Line {
                point: at,
                dir: towards,
                offset: None,
            },
            Ty::Line,
            words,
        )))
    }

    /// Through a point that lies on a known line (an end of the line's segment, or put on the
    /// line by an `on` or a coincidence already met) and tangent to that line, the point and
    /// the line at the same offset: the parabola of centres has its focus on its directrix
    /// and degenerates into the normal to the line at the point, on which every circle
    /// tangent to the line there has its centre. `None` otherwise.
    fn tangent_at_line(&mut self, f1: Fd, f2: Fd, name: &str) -> Option<Locus> {
        let (line, a, base, dir, at, b, p) = match (f1, f2) {
            (
                Fd::Line {
                    line, a, base, dir, ..
                },
                Fd::Point {
                    at,
                    b,
                    plus: true,
                    p: Some(p),
                    ..
                },
            )
            | (
                Fd::Point {
                    at,
                    b,
                    plus: true,
                    p: Some(p),
                    ..
                },
                Fd::Line {
                    line, a, base, dir, ..
                },
            ) => (line, a, base, dir, at, b, p),
            _ => return None,
        };
        if !self.same_value(a, b) || !self.on_line(p, base, dir) {
            return None;
        }
        let along = self.value(
            PlanarOp::LineDir(line),
            Ty::Vector,
            format!("the direction of {}", self.word(line)),
        );
        // Turned to the line's left, where the circle is.
        let words = format!("{} turned by pi/2", self.word(along));
        let normal = self.quarter_turned(along, 1.0, words);
        let words = format!(
            "the normal at {} to {}, where {name} is tangent",
            self.word(at),
            self.word(line)
        );
        Some(Locus::Line(self.value(
            Op::Line {
                point: at,
                dir: normal,
                offset: None,
            },
            Ty::Line,
            words,
        )))
    }

    /// Whether point feature `p` lies on the line through `base` along `dir` whatever the
    /// params: it is `base` or an end of the line's segment, or is put on the line by an `on`
    /// already met, or is coincident with such a point by a `coincident` already met. (A
    /// relation's key does not tell a zero distance from another, so the constraints are
    /// read by kind.)
    fn on_line(&self, p: GeomId, base: GeomId, dir: GeomId) -> bool {
        use gcs_lang::constraints::ConstraintKind as K;
        let lies = |q: GeomId| {
            q == base
                || self.end_of_segment(q).is_some_and(|(_, d)| d == dir)
                || (self.model.constraints.iter()).any(|(_, c)| {
                    c.kind == K::On
                        && matches!(c.args[..], [x, l] if x == q
                            && self.model.line_features(l) == Some((base, dir)))
                        && self.is_done(&Relation::PointLine {
                            p: q,
                            base,
                            dir,
                            d: None,
                        })
                })
        };
        lies(p)
            || (self.model.constraints.iter()).any(|(_, c)| {
                let q = match c.args[..] {
                    [x, y] if c.kind == K::Coincident && x == p => y,
                    [x, y] if c.kind == K::Coincident && y == p => x,
                    _ => return false,
                };
                lies(q)
                    && self.is_done(&Relation::PointPoint {
                        a: p,
                        b: q,
                        d: None,
                    })
            })
    }

    /// Whether register `r` holds the constant zero.
    fn is_zero(&self, r: Reg) -> bool {
        (self.plan.steps.iter().rev())
            .find(|s| s.out.map(|(o, _)| o) == Some(r))
            .is_some_and(|s| matches!(s.op, Op::Const(c) if c == 0.0))
    }

    /// Whether a point known at register `at` is made coincident with point `p` by a
    /// `coincident` constraint already met.
    fn coincident_at(&mut self, p: GeomId, at: Reg) -> bool {
        let others: Vec<GeomId> = (self.model.constraints.iter())
            .filter(|(_, c)| c.kind == gcs_lang::constraints::ConstraintKind::Coincident)
            .filter_map(|(_, c)| match c.args[..] {
                [a, b] if a == p => Some(b),
                [a, b] if b == p => Some(a),
                _ => None,
            })
            .collect();
        others.into_iter().any(|q| {
            self.point_known(q)
                && self.point(q) == at
                && self.is_done(&Relation::PointPoint {
                    a: p,
                    b: q,
                    d: None,
                })
        })
    }

    /// The circle whose radius register `r` reads (`dim_of`), if it reads one.
    fn radius_of(&self, r: Reg) -> Option<GeomId> {
        (self.plan.steps.iter().rev())
            .find(|s| s.out.map(|(o, _)| o) == Some(r))
            .and_then(|s| match s.op {
                Op::DimOf(g) => Some(g),
                _ => None,
            })
    }

    /// A circle whose centre has just become fixed: its radius follows from its first fixed
    /// distance, and that step satisfies every fixed distance recorded (the centre was placed
    /// on their common locus).
    pub(super) fn settle(&mut self, k: usize) {
        let rec = self.clusters[k].record.clone();
        let (Some(circle), Some(first)) = (rec.free_dim, rec.fd.first().copied()) else {
            return;
        };
        if rec.pos != Pos::Fixed {
            return;
        }
        let centre = self.centre(circle);
        let x = self.point(centre);
        let radius = match first {
            Fd::Line { line, a, .. } => {
                let words = format!(
                    "the distance of {} from {} less {}",
                    self.name(centre),
                    self.word(line),
                    self.word(a)
                );
                self.value(
                    PlanarOp::RadiusFromLine { line, a, centre: x },
                    Ty::Scalar,
                    words,
                )
            }
            Fd::Point { at, b, plus, .. } => {
                let words = format!(
                    "the radius that keeps {} at its distance from {}",
                    self.name(circle),
                    self.word(at)
                );
                self.value(
                    PlanarOp::RadiusFromPoint {
                        at,
                        b,
                        plus,
                        centre: x,
                    },
                    Ty::Scalar,
                    words,
                )
            }
        };
        let satisfies: Vec<ConstraintId> = rec.fd.iter().filter_map(Fd::satisfies).collect();
        let texts: Vec<String> = satisfies.iter().map(|c| self.cname(*c)).collect();
        let explain = format!(
            "The centre of {} is placed: set its radius to {} ({}).",
            self.name(circle),
            self.word(radius),
            texts.join("; ")
        );
        self.emit(
            Op::SetDim {
                geom: circle,
                value: radius,
            },
            None,
            satisfies,
            explain,
        );
        let rec = &mut self.clusters[k].record;
        rec.fd.clear();
        rec.fd_locus = false;
        rec.free_dim = None;
        rec.fixed_dims.push(circle);
    }
}
