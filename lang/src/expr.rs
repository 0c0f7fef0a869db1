//! Resolved expressions: params by id, units folded, functions checked. They stay symbolic
//! because params are run-time inputs everywhere (a solver re-evaluates every coordinate and
//! value with the caller's params); [`Exprs::eval`] gives their value for given params.

use la_arena::{Arena, Idx};

/// A resolved expression node, in the model's expression arena.
pub type ExprId = Idx<ExprNode>;

/// A param, in the model's param arena.
pub type ParamId = Idx<crate::model::Param>;

/// One node of a resolved expression.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprNode {
    /// A literal, `pi`, or a folded unit factor.
    Const(f64),
    /// The run-time value of a param.
    Param(ParamId),
    /// `-a`
    Neg(ExprId),
    /// `a OP b`
    Binary(crate::syntax::BinaryOp, ExprId, ExprId),
    /// `f(a)` or `f(a, b)`.
    Call(Func, ExprId, Option<ExprId>),
    /// `a deg` (a times pi/180) or `a rad` (a): an angle.
    Unit(crate::syntax::AngleUnit, ExprId),
}

/// The functions of the language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Func {
    /// `sqrt(x)`
    Sqrt,
    /// `abs(x)`
    Abs,
    /// `sin(angle)`
    Sin,
    /// `cos(angle)`
    Cos,
    /// `tan(angle)`
    Tan,
    /// `asin(x)`, an angle
    Asin,
    /// `acos(x)`, an angle
    Acos,
    /// `atan(x)`, an angle
    Atan,
    /// `atan2(y, x)`, an angle
    Atan2,
    /// `min(a, b)`
    Min,
    /// `max(a, b)`
    Max,
}

impl Func {
    /// Every function, for lookups and suggestions.
    pub const ALL: [Func; 11] = [
        Func::Sqrt,
        Func::Abs,
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Atan2,
        Func::Min,
        Func::Max,
    ];

    /// The name in the language.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sqrt => "sqrt",
            Func::Abs => "abs",
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Atan2 => "atan2",
            Func::Min => "min",
            Func::Max => "max",
        }
    }

    /// The function called `name`, if any.
    pub fn from_name(name: &str) -> Option<Func> {
        Func::ALL.into_iter().find(|f| f.name() == name)
    }

    /// How many arguments it takes.
    pub fn arity(self) -> usize {
        match self {
            Func::Atan2 | Func::Min | Func::Max => 2,
            _ => 1,
        }
    }

    /// Applies the function.
    pub fn apply(self, a: f64, b: f64) -> f64 {
        match self {
            Func::Sqrt => a.sqrt(),
            Func::Abs => a.abs(),
            Func::Sin => a.sin(),
            Func::Cos => a.cos(),
            Func::Tan => a.tan(),
            Func::Asin => a.asin(),
            Func::Acos => a.acos(),
            Func::Atan => a.atan(),
            Func::Atan2 => a.atan2(b),
            Func::Min => a.min(b),
            Func::Max => a.max(b),
        }
    }
}

/// What an expression measures, for unit checking. Angles are radians; a bare number may stand
/// for an angle (in radians) or a length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dim {
    /// A plain number: fits an angle or a length slot.
    Number,
    /// A length (a distance, a coordinate, a radius).
    Length,
    /// An angle, in radians.
    Angle,
}

impl Dim {
    /// The word for messages.
    pub fn noun(self) -> &'static str {
        match self {
            Dim::Number => "a number",
            Dim::Length => "a length",
            Dim::Angle => "an angle",
        }
    }

    /// What `a op b` measures when `a` measures `self` and `b` measures `other`. The one
    /// place for these rules: the resolver checks the file with them, and a value given on
    /// the command line is checked with them too.
    pub fn of_binary(self, op: crate::syntax::BinaryOp, other: Dim) -> Dim {
        use crate::syntax::BinaryOp::*;
        match op {
            Add | Sub => self.sum(other),
            Mul => match (self, other) {
                (Dim::Number, d) | (d, Dim::Number) => d,
                (Dim::Length, _) | (_, Dim::Length) => Dim::Length,
                _ => Dim::Angle,
            },
            Div => match (self, other) {
                (d, Dim::Number) => d,
                (a, b) if a == b => Dim::Number,
                (d, _) => d,
            },
            Pow => self,
        }
    }

    /// What a sum (or a min, a max) of the two measures: a plain number takes the other's
    /// dimension; a length and an angle make a plain number (reported elsewhere).
    pub fn sum(self, other: Dim) -> Dim {
        match (self, other) {
            (a, b) if a == b => a,
            (Dim::Number, d) | (d, Dim::Number) => d,
            _ => Dim::Number,
        }
    }
}

impl Func {
    /// What the function's value measures, given its arguments'.
    pub fn dim(self, a: Dim, b: Option<Dim>) -> Dim {
        match self {
            Func::Sin | Func::Cos | Func::Tan => Dim::Number,
            Func::Asin | Func::Acos | Func::Atan | Func::Atan2 => Dim::Angle,
            Func::Sqrt | Func::Abs => a,
            Func::Min | Func::Max => a.sum(b.unwrap_or(Dim::Number)),
        }
    }
}

/// The expression arena of a model.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Exprs {
    arena: Arena<ExprNode>,
}

impl Exprs {
    /// Adds a node.
    pub fn alloc(&mut self, node: ExprNode) -> ExprId {
        self.arena.alloc(node)
    }

    /// The node behind an id.
    pub fn node(&self, id: ExprId) -> &ExprNode {
        &self.arena[id]
    }

    /// The value of `id` with `params` (indexed by param id, in declaration order). Evaluation
    /// follows IEEE arithmetic: a division by zero gives an infinity, not a panic.
    pub fn eval(&self, id: ExprId, params: &[f64]) -> f64 {
        match &self.arena[id] {
            ExprNode::Const(v) => *v,
            ExprNode::Param(p) => params
                .get(p.into_raw().into_u32() as usize)
                .copied()
                .unwrap_or(f64::NAN),
            ExprNode::Neg(a) => -self.eval(*a, params),
            ExprNode::Binary(op, a, b) => {
                let (a, b) = (self.eval(*a, params), self.eval(*b, params));
                use crate::syntax::BinaryOp::*;
                match op {
                    Add => a + b,
                    Sub => a - b,
                    Mul => a * b,
                    Div => a / b,
                    Pow => a.powf(b),
                }
            }
            ExprNode::Call(f, a, b) => {
                let a = self.eval(*a, params);
                let b = b.map_or(0.0, |b| self.eval(b, params));
                f.apply(a, b)
            }
            ExprNode::Unit(u, a) => {
                let a = self.eval(*a, params);
                match u {
                    crate::syntax::AngleUnit::Deg => a.to_radians(),
                    crate::syntax::AngleUnit::Rad => a,
                }
            }
        }
    }

    /// Whether the expression depends on no param.
    pub fn is_constant(&self, id: ExprId) -> bool {
        match &self.arena[id] {
            ExprNode::Const(_) => true,
            ExprNode::Param(_) => false,
            ExprNode::Neg(a) | ExprNode::Unit(_, a) => self.is_constant(*a),
            ExprNode::Binary(_, a, b) => self.is_constant(*a) && self.is_constant(*b),
            ExprNode::Call(_, a, b) => {
                self.is_constant(*a) && b.is_none_or(|b| self.is_constant(b))
            }
        }
    }

    /// The params the expression reads, in first-use order, without repeats.
    pub fn params(&self, id: ExprId, out: &mut Vec<ParamId>) {
        match &self.arena[id] {
            ExprNode::Const(_) => {}
            ExprNode::Param(p) => {
                if !out.contains(p) {
                    out.push(*p);
                }
            }
            ExprNode::Neg(a) | ExprNode::Unit(_, a) => self.params(*a, out),
            ExprNode::Binary(_, a, b) => {
                self.params(*a, out);
                self.params(*b, out);
            }
            ExprNode::Call(_, a, b) => {
                self.params(*a, out);
                if let Some(b) = b {
                    self.params(*b, out);
                }
            }
        }
    }

    /// Every node, in allocation order.
    pub fn iter(&self) -> impl Iterator<Item = (ExprId, &ExprNode)> {
        self.arena.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::BinaryOp;

    #[test]
    fn evaluates_with_ieee_semantics() {
        let mut e = Exprs::default();
        let one = e.alloc(ExprNode::Const(1.0));
        let zero = e.alloc(ExprNode::Const(0.0));
        let div = e.alloc(ExprNode::Binary(BinaryOp::Div, one, zero));
        assert!(e.eval(div, &[]).is_infinite());
        let at = e.alloc(ExprNode::Call(Func::Atan2, one, Some(zero)));
        assert!((e.eval(at, &[]) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        assert!(e.is_constant(at));
    }

    #[test]
    fn function_table_is_consistent() {
        for f in Func::ALL {
            assert_eq!(Func::from_name(f.name()), Some(f));
        }
        assert_eq!(Func::from_name("sine"), None);
    }
}
