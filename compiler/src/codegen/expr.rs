//! The model's expressions as Rust code: params are run-time inputs, so every coordinate and
//! value the model writes as an expression is written as one, with no more parentheses than
//! precedence needs; a constant one is written as its value.

use super::context::Context;
use super::facts::same_bits;
use super::writer::{float, typed_float};
use gcs_lang::expr::{ExprId, ExprNode, Func};
use gcs_lang::syntax::{AngleUnit, BinaryOp};

/// The precedence of an expression's outermost operator, lowest first.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Prec {
    Sum,
    Product,
    Negation,
    /// An atom or a method call.
    Atom,
}

impl Context<'_> {
    /// The Rust code of an expression, with the precedence of its outermost operator.
    fn expr_prec(&self, e: ExprId) -> (String, Prec) {
        let m = self.model;
        if m.exprs.is_constant(e) {
            return constant(m.exprs.eval(e, &[]));
        }
        match m.exprs.node(e) {
            ExprNode::Const(v) => constant(*v),
            ExprNode::Param(p) => {
                let index = p.into_raw().into_u32() as usize;
                (super::lift::param(index, &self.params[p]), Prec::Atom)
            }
            ExprNode::Neg(a) => (
                format!("-{}", self.wrap(*a, Prec::Negation)),
                Prec::Negation,
            ),
            ExprNode::Binary(op, a, b) => {
                let (symbol, prec) = match op {
                    BinaryOp::Add => ("+", Prec::Sum),
                    BinaryOp::Sub => ("-", Prec::Sum),
                    BinaryOp::Mul => ("*", Prec::Product),
                    BinaryOp::Div => ("/", Prec::Product),
                    BinaryOp::Pow => {
                        let code = format!("{}.powf({})", self.receiver(*a), self.expr(*b));
                        return (code, Prec::Atom);
                    }
                };
                // Left-associative: the right operand binds one level tighter.
                let right = match prec {
                    Prec::Sum => Prec::Product,
                    _ => Prec::Negation,
                };
                let code = format!("{} {symbol} {}", self.wrap(*a, prec), self.wrap(*b, right));
                (code, prec)
            }
            ExprNode::Call(f, a, b) => {
                let method = method(*f);
                let code = match b {
                    Some(b) => format!("{}.{method}({})", self.receiver(*a), self.expr(*b)),
                    None => format!("{}.{method}()", self.receiver(*a)),
                };
                (code, Prec::Atom)
            }
            ExprNode::Unit(AngleUnit::Deg, a) => {
                (format!("{}.to_radians()", self.receiver(*a)), Prec::Atom)
            }
            ExprNode::Unit(AngleUnit::Rad, a) => self.expr_prec(*a),
        }
    }

    /// The Rust code of an expression.
    pub(super) fn expr(&self, e: ExprId) -> String {
        self.expr_prec(e).0
    }

    /// The expression, parenthesised if its precedence is below `at`.
    pub(super) fn wrap(&self, e: ExprId, at: Prec) -> String {
        let (code, prec) = self.expr_prec(e);
        if prec < at {
            format!("({code})")
        } else {
            code
        }
    }

    /// The expression as the receiver of a method call: an atom, and a typed literal (a
    /// negative one in parentheses, as `-2.0_f64.powf(p)` is `-(2.0_f64.powf(p))`).
    fn receiver(&self, e: ExprId) -> String {
        if let Some(v) = self.constant(e) {
            let (literal, negative) = typed_float(v);
            return if negative {
                format!("({literal})")
            } else {
                literal
            };
        }
        self.wrap(e, Prec::Atom)
    }

    /// `Point2::new(x, y)` of a sketch's coordinates (a missing one is zero).
    pub(super) fn point_lit(&self, c: &[ExprId]) -> String {
        let (x, y) = self.coords_code(c);
        format!("Point2::new({x}, {y})")
    }

    /// `Vector2::new(x, y)` of a sketch's coordinates (a missing one is zero).
    pub(super) fn vector_lit(&self, c: &[ExprId]) -> String {
        let (x, y) = self.coords_code(c);
        format!("Vector2::new({x}, {y})")
    }

    fn coords_code(&self, c: &[ExprId]) -> (String, String) {
        let at = |i: usize| c.get(i).map_or("0.0".into(), |&e| self.expr(e));
        (at(0), at(1))
    }

    /// Whether two sketch coordinates (a missing one is zero) are one value for any params:
    /// equal constants, bit for bit, or the same expression of params.
    pub(super) fn same_coordinate(&self, a: Option<ExprId>, b: Option<ExprId>) -> bool {
        match (a, b) {
            (Some(a), Some(b)) => self.same_expr(a, b),
            (Some(e), None) | (None, Some(e)) => {
                self.constant(e).is_some_and(|v| same_bits(v, 0.0))
            }
            (None, None) => true,
        }
    }

    /// Whether two expressions are one value for any params: equal constants (bit for bit),
    /// or the same operations on the same params and such expressions.
    fn same_expr(&self, a: ExprId, b: ExprId) -> bool {
        let m = self.model;
        match (self.constant(a), self.constant(b)) {
            (Some(x), Some(y)) => return same_bits(x, y),
            (None, None) => {}
            _ => return false,
        }
        let same = |a: &ExprId, b: &ExprId| self.same_expr(*a, *b);
        match (m.exprs.node(a), m.exprs.node(b)) {
            (ExprNode::Unit(AngleUnit::Rad, x), _) => self.same_expr(*x, b),
            (_, ExprNode::Unit(AngleUnit::Rad, y)) => self.same_expr(a, *y),
            (ExprNode::Param(p), ExprNode::Param(q)) => p == q,
            (ExprNode::Neg(x), ExprNode::Neg(y))
            | (ExprNode::Unit(AngleUnit::Deg, x), ExprNode::Unit(AngleUnit::Deg, y)) => same(x, y),
            (ExprNode::Binary(o, x1, x2), ExprNode::Binary(p, y1, y2)) => {
                o == p && same(x1, y1) && same(x2, y2)
            }
            (ExprNode::Call(f, x1, x2), ExprNode::Call(g, y1, y2)) => {
                f == g
                    && same(x1, y1)
                    && match (x2, y2) {
                        (Some(x), Some(y)) => same(x, y),
                        (None, None) => true,
                        _ => false,
                    }
            }
            _ => false,
        }
    }

    /// The value of an expression without params.
    fn constant(&self, e: ExprId) -> Option<f64> {
        let exprs = &self.model.exprs;
        exprs.is_constant(e).then(|| exprs.eval(e, &[]))
    }
}

/// A constant's code: a negative one is a negation.
fn constant(v: f64) -> (String, Prec) {
    let prec = if v < 0.0 { Prec::Negation } else { Prec::Atom };
    (float(v), prec)
}

/// The `f64` method of a function of the language.
fn method(f: Func) -> &'static str {
    match f {
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
