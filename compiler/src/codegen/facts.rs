//! What codegen knows at each step of the solve, so that it writes the same values with less
//! work: of each frame (its rotation still the identity, code equal to its origin), and of each
//! register (its code, whether it is finite, a unit direction, the x axis, a point at a constant
//! offset from an origin, a circle's constant radius or centre, a root kept with its chord);
//! and the code of a feature's global position or direction from what is known.

use super::solve::Solve;
use super::writer::float;
use crate::plan::Reg;
use gcs_lang::model::{GeomId, Owner, Part};
use std::collections::{HashMap, HashSet};

/// What codegen knows of a frame at the current step of the solve, so that it writes the same
/// values with less work: a rotation still the identity needs no product, an origin known to
/// equal a literal or an immutable local needs no reading, and an action that cannot move
/// the frame is left out.
#[derive(Clone, Debug, Default)]
pub(super) struct FrameFacts {
    /// The rotation is exactly the identity (nothing has turned the frame yet).
    pub(super) identity: bool,
    /// Code whose value is the frame's origin, to the bit.
    pub(super) origin: Option<Origin>,
}

/// Code equal to a frame's origin.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Origin {
    /// A constant point, which later constant offsets fold into.
    Literal(f64, f64),
    /// An immutable local, or an expression of params.
    Code(String),
}

impl Origin {
    pub(super) fn code(&self) -> String {
        match self {
            Origin::Literal(x, y) => format!("Point2::new({}, {})", float(*x), float(*y)),
            Origin::Code(c) => c.clone(),
        }
    }
}

/// What is known of the registers at the step being written.
#[derive(Debug, Default)]
pub(super) struct Facts {
    /// What is known of each frame.
    pub(super) frames: HashMap<GeomId, FrameFacts>,
    /// The Rust expression of each register (a local's name, or an inline expression).
    pub(super) regs: HashMap<Reg, String>,
    /// Registers that hold the x axis `(1, 0)` exactly.
    pub(super) unit_x: HashSet<Reg>,
    /// Scalar registers known to be finite: a param (checked on entry), a finite literal, or
    /// a value checked where it is computed. Their uses need no test of their own.
    pub(super) finite: HashSet<Reg>,
    /// Registers that hold a finite unit direction by construction (`direction_at` of a
    /// finite angle): a rotation onto one needs no test.
    pub(super) unit_dirs: HashSet<Reg>,
    /// Point registers read while their frame was unturned, with an origin whose code stays
    /// its value: that code and the point's constant local coordinates. The vector between
    /// two such points of one frame is a constant, known here.
    pub(super) at_offset: HashMap<Reg, (String, (f64, f64))>,
    /// The constant radius of the circle about a pivot through a point of the same rigid
    /// geom, by its (centre, through) registers: a rotation onto that circle knows it.
    pub(super) circle_radius: HashMap<(Reg, Reg), f64>,
    /// Names for registers that are a literal rather than a local (to name what is derived
    /// from them).
    pub(super) reg_names: HashMap<Reg, String>,
    /// The code of each circle register's centre.
    pub(super) circle_centers: HashMap<Reg, String>,
    /// Circle-circle roots kept with their chord, so that a rotation about either centre onto
    /// the root reads it from that centre (`root_from_a`, `root_from_b`).
    pub(super) chord_roots: HashMap<Reg, ChordRoot>,
}

/// A circle-circle root whose chord is a local: the chord, the branch index's code, and the
/// code of each circle's centre.
#[derive(Clone, Debug)]
pub(super) struct ChordRoot {
    pub(super) chord: String,
    pub(super) index: String,
    pub(super) centers: [String; 2],
}

/// Whether generated code is a plain identifier (a local), not a literal or an expression.
pub(super) fn is_ident(code: &str) -> bool {
    !code.is_empty()
        && !code.starts_with(|c: char| c.is_ascii_digit())
        && code.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Code for the point at local coordinates `local` of frame `f`, with origin `origin`: the
/// rotation's products by a zero coordinate left out (the compiler may not fold them, as a
/// NaN times zero is NaN), and nothing at all for the origin itself.
pub(super) fn point_in(f: &str, origin: &str, local: (f64, f64)) -> String {
    match local {
        (0.0, 0.0) => origin.to_string(),
        (x, 0.0) => offset(origin, &format!("{f}.x_axis() * {}", float(x))),
        (0.0, y) => offset(origin, &format!("{f}.y_axis() * {}", float(y))),
        (x, y) => format!(
            "{f}.point_to_global(&Point2::new({}, {}))",
            float(x),
            float(y)
        ),
    }
}

/// Code for the point `origin + v`; just `v` as a point when the origin is the literal zero.
fn offset(origin: &str, v: &str) -> String {
    if origin == "Point2::new(0.0, 0.0)" {
        format!("Point2::from({v})")
    } else {
        format!("{origin} + {v}")
    }
}

/// Code for the direction at local unit vector `local` of frame `f` (see [`point_in`]).
pub(super) fn direction_in(f: &str, local: (f64, f64)) -> String {
    match local {
        (1.0, 0.0) => format!("{f}.x_axis()"),
        (0.0, 1.0) => format!("{f}.y_axis()"),
        (x, y) => format!(
            "{f}.vector_to_global(&Vector2::new({}, {}))",
            float(x),
            float(y)
        ),
    }
}

impl Solve<'_> {
    /// The local of top-level geom `g`'s frame, noted as read.
    pub(super) fn frame(&self, g: GeomId) -> String {
        self.frame_reads.borrow_mut().insert(g);
        self.frames.get(&g).cloned().unwrap_or_default()
    }

    /// Code for the origin of top-level geom `g`'s frame now: what is known of it, or a read.
    pub(super) fn origin_code(&self, g: GeomId) -> String {
        match self.facts.frames.get(&g).and_then(|f| f.origin.as_ref()) {
            Some(o) => o.code(),
            None => format!("{}.origin", self.frame(g)),
        }
    }

    /// For a point of a frame not yet turned, whose origin's code stays its value: that code
    /// and the point's constant offset from it (the local coordinates themselves).
    pub(super) fn offset_from_origin(&self, g: GeomId) -> Option<(String, (f64, f64))> {
        let m = self.cx.model;
        let top = m.top_level_of(g);
        let facts = self.facts.frames.get(&top)?;
        let origin = facts.origin.as_ref().filter(|_| facts.identity)?;
        let local = match m.geoms[g].owner {
            Owner::Member(_) => self.local_value(g, true)?,
            Owner::TopLevel => (0.0, 0.0),
            Owner::Part(..) => return None,
        };
        Some((origin.code(), local))
    }

    /// The vector from register `pivot` to register `from` when it is a constant: two points
    /// read from one unturned frame, or a point of it and the frame's origin.
    pub(super) fn constant_arm(&self, pivot: Reg, from: Reg) -> Option<(f64, f64)> {
        let (origin, (fx, fy)) = self.facts.at_offset.get(&from)?;
        let (px, py) = match self.facts.at_offset.get(&pivot) {
            Some((o, local)) if o == origin => *local,
            _ if self.r(pivot) == *origin => (0.0, 0.0),
            _ => return None,
        };
        Some((fx - px, fy - py))
    }

    /// The global position of a point feature, read from the frames now.
    pub(super) fn point_code(&self, g: GeomId) -> String {
        let m = self.cx.model;
        let top = m.top_level_of(g);
        let facts = self.facts.frames.get(&top).cloned().unwrap_or_default();
        match m.geoms[g].owner {
            Owner::Member(_) => {
                let value = self.local_value(g, true);
                match (facts.identity, &facts.origin, value) {
                    // Not turned yet: the origin plus the local coordinates, a literal when both are.
                    (true, Some(Origin::Literal(ox, oy)), Some((x, y))) => {
                        format!("Point2::new({}, {})", float(ox + x), float(oy + y))
                    }
                    (true, _, Some((0.0, 0.0))) => self.origin_code(top),
                    (true, _, Some((x, y))) => format!(
                        "{} + Vector2::new({}, {})",
                        self.origin_code(top),
                        float(x),
                        float(y)
                    ),
                    (true, _, None) => {
                        format!(
                            "{} + {}.coords",
                            self.origin_code(top),
                            self.local_code(g, true)
                        )
                    }
                    (false, _, Some(local)) => {
                        let origin = self.origin_code(top);
                        point_in(&self.frame(top), &origin, local)
                    }
                    (false, _, None) => {
                        // Set by params, but one coordinate may still be a literal zero.
                        let (f, l) = (self.frame(top), self.local_code(g, true));
                        match self.cx.zero_coordinate(g) {
                            Some(1) => {
                                offset(&self.origin_code(top), &format!("{f}.x_axis() * {l}.x"))
                            }
                            Some(0) => {
                                offset(&self.origin_code(top), &format!("{f}.y_axis() * {l}.y"))
                            }
                            _ => format!("{f}.point_to_global(&{l})"),
                        }
                    }
                }
            }
            Owner::Part(owner, Part::End) => {
                let dim = self.dims.get(&owner).cloned().unwrap_or_default();
                let origin = self.origin_code(top);
                if facts.identity {
                    format!("{origin} + Vector2::new({dim}, 0.0)")
                } else {
                    format!("{origin} + {}.x_axis() * {dim}", self.frame(top))
                }
            }
            Owner::TopLevel | Owner::Part(..) => self.origin_code(top),
        }
    }

    pub(super) fn local_code(&self, g: GeomId, point: bool) -> String {
        match self.locals.get(&g) {
            Some(l) => l.clone(),
            None => self.cx.local_literal(g, point),
        }
    }

    /// The global direction of a vector feature, read from the frames now.
    pub(super) fn dir_code(&self, g: GeomId) -> String {
        let m = self.cx.model;
        let top = m.top_level_of(g);
        let identity = self.facts.frames.get(&top).is_some_and(|f| f.identity);
        let literal = |(x, y): (f64, f64)| format!("Vector2::new({}, {})", float(x), float(y));
        match m.geoms[g].owner {
            Owner::Member(_) | Owner::Part(_, Part::AxisX) => {
                match (identity, self.local_value(g, false)) {
                    (true, Some(local)) => literal(local),
                    (true, None) => self.local_code(g, false),
                    (false, Some(local)) => direction_in(&self.frame(top), local),
                    (false, None) => format!(
                        "{}.vector_to_global(&{})",
                        self.frame(top),
                        self.local_code(g, false)
                    ),
                }
            }
            _ if identity => literal((1.0, 0.0)),
            _ => format!("{}.x_axis()", self.frame(top)),
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
