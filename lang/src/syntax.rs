//! The syntax tree of a `.gcs` file, exactly as written, with byte spans.
//!
//! Nothing here is checked beyond shape: names, kinds, arities, units and the form of each
//! declaration are the resolver's business, so that it can say what is wrong in the user's words.

use crate::source::Span;

/// A word as written, with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    /// The text.
    pub text: String,
    /// Where.
    pub span: Span,
}

/// A parsed file: its statements in source order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct File {
    /// The statements that parsed; statements with syntax errors are left out (and reported).
    pub statements: Vec<Statement>,
}

/// One statement.
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    /// What it says.
    pub kind: StatementKind,
    /// The whole statement, from its first token to its `;` or `}`.
    pub span: Span,
    /// The span of a leading `fixed`, on any statement (meaningful on geoms and bodies only).
    pub fixed: Option<Span>,
}

/// The statement forms of the language.
#[derive(Clone, Debug, PartialEq)]
pub enum StatementKind {
    /// `space 2d;`
    Space {
        /// The word after `space`.
        dim: Ident,
    },
    /// `param NAME = EXPR;`
    Param {
        /// The name.
        name: Ident,
        /// The default value.
        value: Expr,
    },
    /// `point P = ...;` and every other geom kind.
    Geom(GeomDecl),
    /// `body B ... { ... }`
    Body {
        /// The name.
        name: Ident,
        /// `at (...)`, if given.
        at: Option<SpecValue>,
        /// `rotated ANGLE [about (...)]`, if given.
        rotated: Option<Rotated>,
        /// Extra `at` or `rotated` clauses, reported as duplicates.
        repeated_placement: Vec<Span>,
        /// The members, in order.
        members: Vec<GeomDecl>,
    },
    /// `[LABEL:] NAME(ARGS) [= VALUE];`
    Constraint {
        /// The label, if any.
        label: Option<Ident>,
        /// The constraint's name.
        name: Ident,
        /// The arguments, as expressions: the resolver wants names.
        args: Vec<Expr>,
        /// The span from `(` to `)`.
        args_span: Span,
        /// The value after `=`, if any.
        value: Option<Expr>,
    },
    /// `output REF, ...;`
    Output {
        /// The references.
        refs: Vec<Path>,
    },
}

/// `rotated ANGLE [about (...)]`
#[derive(Clone, Debug, PartialEq)]
pub struct Rotated {
    /// The angle.
    pub angle: Expr,
    /// The axis, if given.
    pub about: Option<SpecValue>,
    /// The whole clause.
    pub span: Span,
}

/// A geom declaration, at top level or as a body member.
#[derive(Clone, Debug, PartialEq)]
pub struct GeomDecl {
    /// `point`, `vector`, `line`, `segment`, `circle`, `plane` or `marker`.
    pub keyword: Ident,
    /// The name.
    pub name: Ident,
    /// Everything after `=`.
    pub spec: Vec<SpecPart>,
    /// The span of everything after `=`.
    pub spec_span: Span,
    /// A leading `fixed`, if any.
    pub fixed: Option<Span>,
    /// The whole declaration.
    pub span: Span,
}

/// One part of a declaration's specification.
#[derive(Clone, Debug, PartialEq)]
pub enum SpecPart {
    /// `->`
    Arrow(Span),
    /// `center (0, 0)`, `radius 2`, `z (0, 0, 1)`, ...
    Tagged {
        /// The tag word.
        tag: Ident,
        /// The value after it.
        value: SpecValue,
    },
    /// A bare tuple or expression.
    Value(SpecValue),
}

/// A coordinate tuple or a single expression.
#[derive(Clone, Debug, PartialEq)]
pub enum SpecValue {
    /// `(e1, e2, ...)`, at least two entries.
    Tuple(Vec<Expr>, Span),
    /// A single expression.
    Expr(Expr),
}

impl SpecValue {
    /// The span of the whole value.
    pub fn span(&self) -> Span {
        match self {
            SpecValue::Tuple(_, span) => *span,
            SpecValue::Expr(e) => e.span,
        }
    }
}

/// A dotted reference such as `brick.b1`.
#[derive(Clone, Debug, PartialEq)]
pub struct Path {
    /// The words between the dots.
    pub parts: Vec<Ident>,
    /// The whole reference.
    pub span: Span,
}

impl Path {
    /// The reference as written, `a.b.c`.
    pub fn dotted(&self) -> String {
        let words: Vec<&str> = self.parts.iter().map(|p| p.text.as_str()).collect();
        words.join(".")
    }
}

/// An expression with its span.
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    /// What it is.
    pub kind: ExprKind,
    /// Where.
    pub span: Span,
}

/// The expression forms.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// A number literal.
    Number(f64),
    /// Something that starts like a number but is not one; reported by the resolver.
    BadNumber(String),
    /// `pi`
    Pi,
    /// A name or dotted name.
    Path(Path),
    /// `-e`
    Neg(Box<Expr>),
    /// `a OP b`
    Binary(BinaryOp, Box<Expr>, Box<Expr>),
    /// `e deg`, `e rad`
    Unit(Box<Expr>, AngleUnit, Span),
    /// `f(args)`
    Call(Ident, Vec<Expr>),
    /// `(e)`
    Paren(Box<Expr>),
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`
    Pow,
}

/// Angle units.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AngleUnit {
    /// Degrees: the value is multiplied by pi/180.
    Deg,
    /// Radians: the value is unchanged.
    Rad,
}
