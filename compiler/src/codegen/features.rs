//! What a step reads of the frames now: the locals of frames and dimensions, and a feature's
//! global position or direction, as the cheapest code the facts (see `facts`) allow.

use super::facts::{direction_in, offset, point_in, Value};
use super::solve::Solve;
use super::writer::float;
use crate::plan::Reg;
use gcs_lang::model::{GeomId, Owner, Part};

impl Solve<'_> {
    /// The local of top-level geom `g`'s frame, noted as read: a frame is declared only when
    /// noted, so ask for it only for code that is written.
    pub(super) fn frame(&self, g: GeomId) -> String {
        self.frame_reads.borrow_mut().insert(g);
        self.frame_local(g)
    }

    /// The local of top-level geom `g`'s frame, to move it (moves are noted apart).
    pub(super) fn frame_local(&self, g: GeomId) -> String {
        match self.frames.get(&g) {
            Some(frame) => {
                self.note_read(frame);
                frame.clone()
            }
            None => self.undeclared("frame", g),
        }
    }

    /// The local of geom `g`'s dimension, noted as read.
    pub(super) fn dim(&self, g: GeomId) -> String {
        let dim = self.dim_local(g);
        self.note_read(&dim);
        dim
    }

    /// The local of geom `g`'s dimension, to stand for a register or to bind.
    pub(super) fn dim_local(&self, g: GeomId) -> String {
        match self.dims.get(&g) {
            Some(dim) => dim.clone(),
            None => self.undeclared("dimension", g),
        }
    }

    /// The panic of a plan that reads what the sketch does not declare: a bug in gcs.
    #[cold]
    fn undeclared(&self, what: &str, g: GeomId) -> ! {
        panic!(
            "bug in gcs: codegen reads the {what} of `{}`, which the solve does not declare",
            self.cx.model.geoms[g].name
        )
    }

    /// The origin of top-level geom `g`'s frame now: its known value, or a read of it.
    fn origin(&self, g: GeomId) -> Value {
        match self.facts.frames.get(&g).and_then(|f| f.origin.as_ref()) {
            Some(o) => o.clone(),
            None => Value::Expr(format!("{}.origin", self.frame(g))),
        }
    }

    /// For a point of a frame not yet turned whose origin's value is known: that value and the
    /// point's constant offset from it (the local coordinates themselves).
    pub(super) fn offset_from_origin(&self, g: GeomId) -> Option<(Value, (f64, f64))> {
        let m = self.cx.model;
        let top = m.top_level_of(g);
        let facts = self.facts.frames.get(&top)?;
        let origin = facts.origin.as_ref().filter(|_| facts.identity)?;
        let local = match m.geoms[g].owner {
            Owner::Member(_) => self.local_value(g, true)?,
            Owner::TopLevel => (0.0, 0.0),
            Owner::Part(..) => return None,
        };
        Some((origin.clone(), local))
    }

    /// The vector from register `pivot` to register `from` when it is a constant: two points
    /// read from unturned frames with one origin, or a point of one and that origin.
    pub(super) fn constant_arm(&self, pivot: Reg, from: Reg) -> Option<(f64, f64)> {
        let (origin, (fx, fy)) = self.facts.at_offset.get(&from)?;
        let (px, py) = match self.facts.at_offset.get(&pivot) {
            Some((o, local)) if o.same(origin, self.cx) => *local,
            _ if self.facts.value(pivot).same(origin, self.cx) => (0.0, 0.0),
            _ => return None,
        };
        Some((fx - px, fy - py))
    }

    /// The global position of a point feature, read from the frames now.
    pub(super) fn point_value(&self, g: GeomId) -> Value {
        let m = self.cx.model;
        let top = m.top_level_of(g);
        let identity = self.facts.frames.get(&top).is_some_and(|f| f.identity);
        match m.geoms[g].owner {
            Owner::Member(_) => match (identity, self.local_value(g, true)) {
                (true, Some(local)) => self.unturned_point(top, local),
                (true, None) => Value::Expr(format!(
                    "{} + {}.coords",
                    self.code(&self.origin(top)),
                    self.local_code(g, true)
                )),
                (false, Some(local)) => {
                    let origin = self.origin(top);
                    // Only a point on one of the frame's axes is written from the origin.
                    if local != (0.0, 0.0) && (local.0 == 0.0 || local.1 == 0.0) {
                        self.note(&origin);
                    }
                    point_in(|| self.frame(top), &origin, local)
                }
                (false, None) => {
                    // Set by params, but one coordinate may still be a literal zero.
                    let (f, l) = (self.frame(top), self.local_code(g, true));
                    let from_origin = |v: String| {
                        let origin = self.origin(top);
                        self.note(&origin);
                        offset(&origin, &v)
                    };
                    match self.cx.zero_coordinate(g) {
                        Some(1) => from_origin(format!("{f}.x_axis() * {l}.x")),
                        Some(0) => from_origin(format!("{f}.y_axis() * {l}.y")),
                        _ => Value::Expr(format!("{f}.point_to_global(&{l})")),
                    }
                }
            },
            Owner::Part(owner, Part::End) => {
                let dim = self.dim(owner);
                let origin = self.code(&self.origin(top));
                Value::Expr(if identity {
                    format!("{origin} + Vector2::new({dim}, 0.0)")
                } else {
                    format!("{origin} + {}.x_axis() * {dim}", self.frame(top))
                })
            }
            Owner::TopLevel | Owner::Part(..) => self.origin(top),
        }
    }

    /// The point at constant local coordinates `local` of frame `top`, not turned yet: the
    /// origin plus the local coordinates, a literal when the origin is one.
    fn unturned_point(&self, top: GeomId, local: (f64, f64)) -> Value {
        match (self.origin(top), local) {
            (Value::Point(ox, oy), (x, y)) => Value::Point(ox + x, oy + y),
            (origin, (0.0, 0.0)) => origin,
            (origin, (x, y)) => Value::Expr(format!(
                "{} + Vector2::new({}, {})",
                self.code(&origin),
                float(x),
                float(y)
            )),
        }
    }

    /// The code of a member's local coordinates: the local that holds them, or their literal.
    fn local_code(&self, g: GeomId, point: bool) -> String {
        match self.locals.get(&g) {
            Some(l) => l.clone(),
            None => self.cx.local_literal(g, point).code(),
        }
    }

    /// The global direction of a vector feature, read from the frames now.
    pub(super) fn dir_value(&self, g: GeomId) -> Value {
        let m = self.cx.model;
        let top = m.top_level_of(g);
        let identity = self.facts.frames.get(&top).is_some_and(|f| f.identity);
        match m.geoms[g].owner {
            Owner::Member(_) | Owner::Part(_, Part::AxisX) => {
                match (identity, self.local_value(g, false)) {
                    (true, Some((x, y))) => Value::Vector(x, y),
                    (true, None) => Value::Local(self.local_code(g, false)),
                    (false, Some(local)) => Value::Expr(direction_in(&self.frame(top), local)),
                    (false, None) => Value::Expr(format!(
                        "{}.vector_to_global(&{})",
                        self.frame(top),
                        self.local_code(g, false)
                    )),
                }
            }
            _ if identity => Value::Vector(1.0, 0.0),
            _ => Value::Expr(format!("{}.x_axis()", self.frame(top))),
        }
    }

    /// A member's local coordinates when they are a literal, `None` when params set them (a
    /// local of the solve then holds them).
    pub(super) fn local_value(&self, g: GeomId, point: bool) -> Option<(f64, f64)> {
        if self.locals.contains_key(&g) {
            return None;
        }
        Some(self.cx.literal_coords(g, point))
    }
}
