//! What codegen knows at each step of the solve, so that it writes the same values with less
//! work: of each frame (its rotation still the identity, the value of its origin), and of each
//! register (its value, whether it is finite or a unit direction, a point at a constant offset
//! from an origin, a circle's constant radius or centre, a root kept with its chord); and the
//! value of a feature's global position or direction from what is known.
//!
//! Facts are typed values, never read back from generated code: a literal is a [`Value`]
//! literal whatever its spelling, and two values are compared as values.
//!
//! What they buy, each giving the same value as the plain code: no products by an identity
//! rotation or a zero coordinate (the compiler cannot fold `x * 0.0`, NaN times zero being
//! NaN); no move that cannot move anything; `place_origin` when the point moved is the origin,
//! `set_rotation`/`turn_by` about the origin; only the branch's root of a circle-circle
//! intersection (`circle_circle_chord`, kept when a rotation reads the root from the pivot's
//! centre, `root_from_a`/`root_from_b`, without the cancellation of `root - pivot` far from the
//! origin); and a rotation onto a rigid point's circle from its known radius and constant arm
//! (`rotation_on_circle`, `rotation_on_circle_from`).
//!
//! What they check: a value the params give can overflow, and is then
//! `ErrorKind::InvalidValue` naming its constraint; so is a size (an unsigned distance, a
//! length, a radius: `Model::value_is_size`) that is negative, which the plan evaluates with
//! `Op::Size` rather than `Op::Expr`, so that it is said to be negative instead of surfacing as
//! loci that miss. A sketch that params can make unusable (a zero direction, coinciding
//! points, a negative radius, an overflow) is tested on entry, in the model's order, with the
//! interpreter's words (`config::SketchFault`), so that both report the same geom.

use super::context::Context;
use super::writer::float;
use crate::plan::{Op, Reg};
use gcs_lang::expr::ExprId;
use gcs_lang::model::GeomId;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// A value of the generated code as codegen knows it: what it is decides what can be done
/// with it (fold a constant into a literal, skip a test, see that two values are one, name
/// what derives from it), and [`Value::code`] spells it.
#[derive(Clone, Debug)]
pub(super) enum Value {
    /// A local of the solve, by name.
    Local(String),
    /// Entry `k` of an iteration's trial, the array local `name`: `name[k]`.
    Entry(String, usize),
    /// A param, by its index in model order and its field of `Params`.
    Param(usize, String),
    /// A default, by its index in the plan and its field of `Defaults`.
    Default(usize, String),
    /// A scalar literal.
    Scalar(f64),
    /// A point literal.
    Point(f64, f64),
    /// A vector literal.
    Vector(f64, f64),
    /// A point literal of space.
    Point3([f64; 3]),
    /// A vector literal of space.
    Vector3([f64; 3]),
    /// A point of the sketch that params give: its coordinates' expressions (a missing one is
    /// zero), and its code.
    Sketched([Option<ExprId>; 2], String),
    /// Any other expression: nothing compares it, and a register does not stand for it
    /// without a local of its own.
    Expr(String),
}

impl Value {
    /// The value's code.
    pub(super) fn code(&self) -> String {
        match self {
            Value::Local(name) => name.clone(),
            Value::Entry(name, k) => format!("{name}[{k}]"),
            Value::Param(index, field) => super::lift::param(*index, field),
            Value::Default(index, field) => super::lift::default(*index, field),
            Value::Scalar(v) => float(*v),
            Value::Point(x, y) => format!("Point2::new({}, {})", float(*x), float(*y)),
            Value::Vector(x, y) => format!("Vector2::new({}, {})", float(*x), float(*y)),
            Value::Point3([x, y, z]) => {
                format!("Point3::new({}, {}, {})", float(*x), float(*y), float(*z))
            }
            Value::Vector3(v) => match v.map(|c| c.to_bits()) {
                b if b == [1.0f64, 0.0, 0.0].map(f64::to_bits) => "Vector3::x()".into(),
                b if b == [0.0f64, 1.0, 0.0].map(f64::to_bits) => "Vector3::y()".into(),
                b if b == [0.0f64, 0.0, 1.0].map(f64::to_bits) => "Vector3::z()".into(),
                _ => format!(
                    "Vector3::new({}, {}, {})",
                    float(v[0]),
                    float(v[1]),
                    float(v[2])
                ),
            },
            Value::Sketched(_, code) | Value::Expr(code) => code.clone(),
        }
    }

    /// Whether `self` and `other` are one value to the bit, as far as codegen can tell: the
    /// same local or param, equal literals (bit for bit: a negative zero is not zero), or the
    /// same sketch expressions.
    pub(super) fn same(&self, other: &Value, cx: &Context<'_>) -> bool {
        match (self, other) {
            (Value::Local(a), Value::Local(b))
            | (Value::Param(_, a), Value::Param(_, b))
            | (Value::Default(_, a), Value::Default(_, b)) => a == b,
            (Value::Entry(a, i), Value::Entry(b, j)) => a == b && i == j,
            (Value::Scalar(a), Value::Scalar(b)) => same_bits(*a, *b),
            (Value::Point(ax, ay), Value::Point(bx, by))
            | (Value::Vector(ax, ay), Value::Vector(bx, by)) => {
                same_bits(*ax, *bx) && same_bits(*ay, *by)
            }
            (Value::Point3(a), Value::Point3(b)) | (Value::Vector3(a), Value::Vector3(b)) => {
                a.iter().zip(b).all(|(a, b)| same_bits(*a, *b))
            }
            (Value::Sketched(a, _), Value::Sketched(b, _)) => {
                a.iter().zip(b).all(|(&a, &b)| cx.same_coordinate(a, b))
            }
            _ => false,
        }
    }

    /// A plain local or literal, which a register can stand for without a local of its own.
    pub(super) fn is_atom(&self) -> bool {
        matches!(
            self,
            Value::Local(_)
                | Value::Entry(..)
                | Value::Param(..)
                | Value::Default(..)
                | Value::Scalar(_)
                | Value::Point(..)
                | Value::Vector(..)
                | Value::Point3(_)
                | Value::Vector3(_)
        )
    }

    /// A literal, which has no name of its own.
    pub(super) fn is_literal(&self) -> bool {
        matches!(
            self,
            Value::Scalar(_)
                | Value::Point(..)
                | Value::Vector(..)
                | Value::Point3(_)
                | Value::Vector3(_)
        )
    }

    /// The x axis `(1, 0)`, bit for bit.
    pub(super) fn is_x_axis(&self) -> bool {
        matches!(self, Value::Vector(x, y) if *x == 1.0 && is_plus_zero(*y))
    }

    /// The point `(0, 0)`, bit for bit.
    fn is_zero_point(&self) -> bool {
        matches!(self, Value::Point(x, y) if is_plus_zero(*x) && is_plus_zero(*y))
    }

    /// The code of the local the value is, if it is one (to name what derives from it).
    pub(super) fn local(&self) -> Option<String> {
        match self {
            Value::Local(_) | Value::Entry(..) => Some(self.code()),
            _ => None,
        }
    }

    /// The local the value reads, if it is one: what the ledger notes as read.
    pub(super) fn reads(&self) -> Option<&str> {
        match self {
            Value::Local(name) | Value::Entry(name, _) => Some(name),
            _ => None,
        }
    }

    /// The value as a key of [`Made`]: `None` for code that no key stands for.
    fn key(&self) -> Option<ValueKey> {
        let bits = |tag: u8, v: &[f64]| {
            let mut b = [0u64; 3];
            for (b, v) in b.iter_mut().zip(v) {
                *b = v.to_bits();
            }
            Some(ValueKey::Bits(tag, b))
        };
        match self {
            Value::Local(name) => Some(ValueKey::Local(name.clone(), None)),
            Value::Entry(name, k) => Some(ValueKey::Local(name.clone(), Some(*k))),
            Value::Param(i, _) => Some(ValueKey::Input(false, *i)),
            Value::Default(i, _) => Some(ValueKey::Input(true, *i)),
            Value::Scalar(v) => bits(0, &[*v]),
            Value::Point(x, y) => bits(1, &[*x, *y]),
            Value::Vector(x, y) => bits(2, &[*x, *y]),
            Value::Point3(p) => bits(3, p),
            Value::Vector3(v) => bits(4, v),
            Value::Sketched(..) | Value::Expr(_) => None,
        }
    }
}

/// A [`Value`] as a key: equal keys are one value, written alike.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum ValueKey {
    /// A local, or an entry of one.
    Local(String, Option<usize>),
    /// A param (`false`) or a default (`true`), by index.
    Input(bool, usize),
    /// A literal: its kind and its coordinates' bits.
    Bits(u8, [u64; 3]),
}

/// What a value of locals alone is made from, so that one made twice is computed once: the
/// plan's op (its kind and what it carries besides registers), the values it reads with what
/// each is (`tag`, a locus's kind), and the constraint its code's error names, if it has one.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) struct Made {
    op: std::mem::Discriminant<Op>,
    /// The kind of a space's own op (`Op::Planar`, `Op::Spatial`).
    own: Option<OwnOp>,
    residual: Option<std::mem::Discriminant<crate::plan::Residual>>,
    fields: Vec<u64>,
    operands: Vec<(ValueKey, u8)>,
    fails: Option<gcs_lang::model::ConstraintId>,
}

/// The kind of an op of one space.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum OwnOp {
    Planar(std::mem::Discriminant<crate::plan::PlanarOp>),
    Spatial(std::mem::Discriminant<crate::plan::SpatialOp>),
}

impl Made {
    /// The key of `op` reading `operands` (each value with its tag), whose code names
    /// constraint `fails` in an error; `None` when an operand has no key.
    pub(super) fn new(
        op: &Op,
        operands: &[(&Value, u8)],
        fails: Option<gcs_lang::model::ConstraintId>,
    ) -> Option<Made> {
        use crate::plan::{Residual, SpatialOp};
        let own = match op {
            Op::Planar(p) => Some(OwnOp::Planar(std::mem::discriminant(p))),
            Op::Spatial(p) => Some(OwnOp::Spatial(std::mem::discriminant(p))),
            _ => None,
        };
        let (residual, mut fields) = match op {
            Op::Spatial(SpatialOp::Coordinate { axis, .. }) => (None, vec![u64::from(*axis)]),
            Op::Spatial(SpatialOp::SurfaceParam { component, .. }) => {
                (None, vec![u64::from(*component)])
            }
            Op::Spatial(SpatialOp::WorldAxis(k)) => (None, vec![u64::from(*k)]),
            Op::Spatial(SpatialOp::SphereThrough { radius, .. }) => {
                (None, radius.map(f64::to_bits).into_iter().collect())
            }
            Op::Spatial(SpatialOp::TurnReaching { reach, screw, .. }) => (
                None,
                vec![
                    u64::from(matches!(reach, crate::plan::Reach::Helix(_))),
                    u64::from(screw.is_some()),
                ],
            ),
            Op::Line { offset, .. } => (None, vec![u64::from(offset.is_some())]),
            Op::Error {
                residual,
                component,
            } => {
                let mut fields = match residual {
                    Residual::CircleLine { side, gap, .. } => {
                        vec![side.to_bits(), u64::from(gap.is_some())]
                    }
                    Residual::PointCircle { outside, gap, .. } => {
                        vec![u64::from(*outside), u64::from(gap.is_some())]
                    }
                    Residual::CircleCircle { nesting, gap, .. } => {
                        vec![*nesting as u64, u64::from(gap.is_some())]
                    }
                    Residual::Parallel { sense, .. } => vec![sense.to_bits()],
                    _ => Vec::new(),
                };
                fields.push(u64::from(*component));
                (Some(std::mem::discriminant(residual)), fields)
            }
            _ => (None, Vec::new()),
        };
        fields.push(operands.len() as u64);
        let operands = (operands.iter())
            .map(|(v, tag)| Some((v.key()?, *tag)))
            .collect::<Option<Vec<_>>>()?;
        Some(Made {
            op: std::mem::discriminant(op),
            own,
            residual,
            fields,
            operands,
            fails,
        })
    }
}

/// Whether two literals are one value bit for bit.
pub(super) fn same_bits(a: f64, b: f64) -> bool {
    a.to_bits() == b.to_bits()
}

/// Whether `v` is `0.0` bit for bit: facts compare literals by their bits, so a negative zero
/// (which the runtime's arithmetic may keep) is never taken for zero.
fn is_plus_zero(v: f64) -> bool {
    same_bits(v, 0.0)
}

/// What codegen knows of a frame at the current step of the solve, so that it writes the same
/// values with less work: a rotation still the identity needs no product, an origin whose
/// value is known needs no reading, and an action that cannot move the frame is left out.
#[derive(Clone, Debug, Default)]
pub(super) struct FrameFacts {
    /// The rotation is exactly the identity (nothing has turned the frame yet).
    pub(super) identity: bool,
    /// The frame's origin, to the bit.
    pub(super) origin: Option<Value>,
    /// In space, the whole frame, to the bit, while every step that moved it had literal
    /// inputs: what it does is then computed here, and what reads it is a literal.
    pub(super) literal3: Option<gcs_runtime::frame::Frame3>,
}

/// What is known of the registers at the step being written.
#[derive(Clone, Debug, Default)]
pub(super) struct Facts {
    /// What is known of each frame.
    pub(super) frames: HashMap<GeomId, FrameFacts>,
    /// The value of each register the solve has defined.
    pub(super) regs: HashMap<Reg, Value>,
    /// Scalar registers known to be finite beyond what their value shows: a value checked
    /// where it is computed, or the negation of a finite one. Their uses need no test of
    /// their own.
    pub(super) known_finite: HashSet<Reg>,
    /// Scalar registers checked to be finite and not negative: a size ([`crate::plan::Op::Size`]).
    /// Setting a dimension from one, or a circle of that radius, needs no test of its own.
    pub(super) known_sizes: HashSet<Reg>,
    /// Registers that hold a finite unit direction by construction (`direction_at` of a
    /// finite angle): a rotation onto one needs no test.
    pub(super) unit_dirs: HashSet<Reg>,
    /// Point registers read while their frame was unturned, with the origin's value then and
    /// the point's constant local coordinates. The vector between two such points of frames
    /// with one origin is a constant, known here.
    pub(super) at_offset: HashMap<Reg, (Value, (f64, f64))>,
    /// The constant radius of the circle about a pivot through a point of the same rigid
    /// geom, by its (centre, through) registers: a rotation onto that circle knows it.
    pub(super) circle_radius: HashMap<(Reg, Reg), f64>,
    /// Names for registers whose value is a literal (to name what is derived from them).
    pub(super) literal_names: HashMap<Reg, String>,
    /// The value of each circle register's centre.
    pub(super) circle_centers: HashMap<Reg, Value>,
    /// Circle-circle roots kept with their chord, so that a rotation about either centre onto
    /// the root reads it from that centre (`root_from_a`, `root_from_b`).
    pub(super) chord_roots: HashMap<Reg, ChordRoot>,
    /// In space, the local already holding each value computed from locals alone (reading no
    /// frame), by what it is made from: the same locus or point asked for twice is computed
    /// once.
    pub(super) computed: HashMap<Made, String>,
}

impl Facts {
    /// The value of register `r`. A valid plan defines a register before any step reads it,
    /// so one without a value is a bug in gcs, never written as a made-up value.
    pub(super) fn value(&self, r: Reg) -> &Value {
        self.regs.get(&r).unwrap_or_else(|| {
            panic!(
                "bug in gcs: codegen reads r{} before a step defines it (the plan is malformed)",
                r.0
            )
        })
    }

    /// Whether scalar register `r` is known to be finite: a param (checked on entry), a finite
    /// literal, or a value checked where it is computed.
    pub(super) fn is_finite(&self, r: Reg) -> bool {
        match self.value(r) {
            // Inputs are checked finite on entry.
            Value::Param(..) | Value::Default(..) => true,
            Value::Scalar(v) => v.is_finite(),
            _ => self.known_finite.contains(&r),
        }
    }
}

/// A circle-circle root whose chord is a local: the chord, the branch index's code, and the
/// value of each circle's centre (when known).
#[derive(Clone, Debug)]
pub(super) struct ChordRoot {
    pub(super) chord: String,
    pub(super) index: String,
    pub(super) centers: [Option<Value>; 2],
}

/// The point at local coordinates `local` of a frame with origin `origin`: the rotation's
/// products by a zero coordinate left out (the compiler may not fold them, as a NaN times zero
/// is NaN), and nothing at all for the origin itself. `frame` gives the frame's code, asked
/// for only when the point reads the frame (see [`Solve::frame`]).
pub(super) fn point_in(frame: impl FnOnce() -> String, origin: &Value, local: (f64, f64)) -> Value {
    if let (0.0, 0.0) = local {
        return origin.clone();
    }
    let f = frame();
    match local {
        (x, 0.0) => offset(origin, &format!("{f}.x_axis() * {}", float(x))),
        (0.0, y) => offset(origin, &format!("{f}.y_axis() * {}", float(y))),
        (x, y) => Value::Expr(format!(
            "{f}.point_to_global(&Point2::new({}, {}))",
            float(x),
            float(y)
        )),
    }
}

/// The point `origin + v`; just `v` as a point when the origin is the literal zero.
pub(super) fn offset(origin: &Value, v: &str) -> Value {
    Value::Expr(if origin.is_zero_point() {
        format!("Point2::from({v})")
    } else {
        format!("{} + {v}", origin.code())
    })
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
