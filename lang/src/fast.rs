//! A fast path for the plainest statements, tried before pest.
//!
//! Most statements of a large model are plain: `point q = (1.1, 0.1);`, `on(q, axis);`,
//! `distance(a, b) = gap;`, `param p = a * 2;`. Pest spends hundreds of combinator calls on each;
//! this recogniser reads them in one pass. It accepts only a strict subset of the grammar and
//! builds exactly the tree pest and the `Builder` would; anything else — comments, labels, bodies,
//! tags, units, calls, parentheses, `^`, `pi`, reserved words, anything malformed — returns `None`
//! and goes to pest, so every diagnostic still comes from the one grammar. The tests compare both
//! paths on every model in the repository and on edge cases.

use crate::source::Span;
use crate::syntax::*;

/// Most operators a fast-path expression may hold; longer ones go to pest.
const MAX_FAST_OPERATORS: usize = 32;

/// The words that the grammar treats as keywords somewhere: a statement that uses one as a name
/// or as the first word of a reference is left to pest.
const KEYWORDS: &[&str] = &[
    "space", "param", "fixed", "point", "vector", "line", "segment", "circle", "plane", "body",
    "marker", "output", "deg", "rad", "pi", "at", "rotated", "about", "center", "radius", "normal",
    "offset", "z", "x",
];

const GEOM_KEYWORDS: &[&str] = &[
    "point", "vector", "line", "segment", "circle", "plane", "marker",
];

/// The statement in `span` of `text`, if it is plain enough for the fast path.
pub(crate) fn statement(text: &str, span: Span) -> Option<Statement> {
    let mut c = Cursor {
        b: text.as_bytes(),
        text,
        pos: span.start,
        end: span.end,
    };
    c.ws()?;
    let start = c.pos;
    let first = c.word()?;
    let mut fixed = None;
    let mut kw = first;
    if &text[first.range()] == "fixed" {
        fixed = Some(first);
        c.ws()?;
        kw = c.word()?;
    }
    let kw_text = &text[kw.range()];
    let kind = if kw_text == "param" {
        c.ws()?;
        let name = c.name()?;
        c.ws()?;
        c.eat(b'=')?;
        let value = c.expr()?;
        c.ws()?;
        c.eat(b';')?;
        StatementKind::Param { name, value }
    } else if GEOM_KEYWORDS.contains(&kw_text) {
        c.ws()?;
        let name = c.name()?;
        c.ws()?;
        c.eat(b'=')?;
        c.ws()?;
        let spec_start = c.pos;
        let mut spec = Vec::new();
        let mut spec_end;
        loop {
            if c.peek() == Some(b'-') && c.peek_at(1) == Some(b'>') {
                c.pos += 2;
                spec.push(SpecPart::Arrow(Span::new(c.pos - 2, c.pos)));
            } else if c.peek() == Some(b'(') {
                let (items, tspan) = c.list()?;
                if items.len() < 2 {
                    return None;
                }
                spec.push(SpecPart::Value(SpecValue::Tuple(items, tspan)));
            } else {
                return None;
            }
            spec_end = c.pos;
            c.ws()?;
            if c.peek() == Some(b';') {
                break;
            }
        }
        // Pest reads `spec_part+` as `spec_part ~ spec_part*`, with the blanks between them
        // taken even when no second part follows: a one-part spec ends at the `;`.
        if spec.len() == 1 {
            spec_end = c.pos;
        }
        c.eat(b';')?;
        let keyword = Ident {
            text: kw_text.to_string(),
            span: kw,
        };
        let decl_span = Span::new(start, c.pos);
        StatementKind::Geom(GeomDecl {
            keyword,
            name,
            spec,
            spec_span: Span::new(spec_start, spec_end),
            fixed,
            span: decl_span,
        })
    } else if fixed.is_none() && !KEYWORDS.contains(&kw_text) {
        let name = Ident {
            text: kw_text.to_string(),
            span: kw,
        };
        c.ws()?;
        if c.peek() != Some(b'(') {
            return None;
        }
        let (args, args_span) = c.list()?;
        c.ws()?;
        let value = if c.peek() == Some(b'=') {
            c.pos += 1;
            let v = c.expr()?;
            c.ws()?;
            Some(v)
        } else {
            None
        };
        c.eat(b';')?;
        StatementKind::Constraint {
            label: None,
            name,
            args,
            args_span,
            value,
        }
    } else {
        return None;
    };
    let stmt_end = c.pos;
    c.ws()?;
    if c.pos != c.end {
        return None;
    }
    Some(Statement {
        kind,
        span: Span::new(start, stmt_end),
        fixed,
    })
}

struct Cursor<'t> {
    b: &'t [u8],
    text: &'t str,
    pos: usize,
    end: usize,
}

impl Cursor<'_> {
    fn peek(&self) -> Option<u8> {
        self.peek_at(0)
    }

    fn peek_at(&self, k: usize) -> Option<u8> {
        (self.pos + k < self.end).then(|| self.b[self.pos + k])
    }

    /// Skips blanks; a comment (or a `/` that might start one) is left to pest.
    fn ws(&mut self) -> Option<()> {
        while let Some(ch) = self.peek() {
            match ch {
                b' ' | b'\t' | b'\r' | b'\n' => self.pos += 1,
                b'/' if matches!(self.peek_at(1), Some(b'/' | b'*')) => return None,
                _ => break,
            }
        }
        Some(())
    }

    fn eat(&mut self, ch: u8) -> Option<()> {
        (self.peek() == Some(ch)).then(|| self.pos += 1)
    }

    /// `word = @{ (ASCII_ALPHA | "_") ~ ident_char* }`
    fn word(&mut self) -> Option<Span> {
        let start = self.pos;
        match self.peek() {
            Some(ch) if ch.is_ascii_alphabetic() || ch == b'_' => self.pos += 1,
            _ => return None,
        }
        while matches!(self.peek(), Some(ch) if ch.is_ascii_alphanumeric() || ch == b'_') {
            self.pos += 1;
        }
        Some(Span::new(start, self.pos))
    }

    /// A declared name: any word but a keyword (those go to pest).
    fn name(&mut self) -> Option<Ident> {
        let span = self.word()?;
        let text = &self.text[span.range()];
        if KEYWORDS.contains(&text) {
            return None;
        }
        Some(Ident {
            text: text.to_string(),
            span,
        })
    }

    /// `( EXPR, ... )` with its span, from `(` to `)`; the cursor is on `(`.
    fn list(&mut self) -> Option<(Vec<Expr>, Span)> {
        let start = self.pos;
        self.eat(b'(')?;
        let mut items = Vec::new();
        self.ws()?;
        if self.peek() != Some(b')') {
            loop {
                items.push(self.expr()?);
                self.ws()?;
                match self.peek() {
                    Some(b',') => self.pos += 1,
                    Some(b')') => break,
                    _ => return None,
                }
            }
        }
        self.eat(b')')?;
        Some((items, Span::new(start, self.pos)))
    }

    /// An expression of numbers and references with `+ - * /` and prefix `-`, as pest's Pratt
    /// parser builds it (left associative; `-` binds tighter than `*`). Leaves the cursor after
    /// the last primary.
    fn expr(&mut self) -> Option<Expr> {
        // Operands and operators, reduced by precedence as they come.
        let mut operands: Vec<Expr> = Vec::new();
        let mut ops: Vec<BinaryOp> = Vec::new();
        let mut count = 0usize;
        loop {
            let operand = self.operand(&mut count)?;
            operands.push(operand);
            let after = self.pos;
            self.ws()?;
            let op = match self.peek() {
                Some(b'+') => BinaryOp::Add,
                Some(b'-') if self.peek_at(1) != Some(b'>') => BinaryOp::Sub,
                Some(b'*') => BinaryOp::Mul,
                Some(b'/') => BinaryOp::Div,
                _ => {
                    self.pos = after;
                    break;
                }
            };
            count += 1;
            if count > MAX_FAST_OPERATORS {
                return None;
            }
            self.pos += 1;
            while ops.last().is_some_and(|&top| prec(top) >= prec(op)) {
                reduce(&mut operands, &mut ops);
            }
            ops.push(op);
        }
        while !ops.is_empty() {
            reduce(&mut operands, &mut ops);
        }
        operands.pop()
    }

    /// `-`* then a number or a reference.
    fn operand(&mut self, count: &mut usize) -> Option<Expr> {
        self.ws()?;
        if self.peek() == Some(b'-') {
            let start = self.pos;
            self.pos += 1;
            *count += 1;
            if *count > MAX_FAST_OPERATORS {
                return None;
            }
            let inner = self.operand(count)?;
            let span = Span::new(start, start + 1).to(inner.span);
            return Some(Expr {
                kind: ExprKind::Neg(Box::new(inner)),
                span,
            });
        }
        let e = match self.peek()? {
            b'0'..=b'9' => self.number()?,
            ch if ch.is_ascii_alphabetic() || ch == b'_' => self.path()?,
            _ => return None,
        };
        // A unit, a call, a malformed number or a `^` after it: pest's business.
        self.check_follower()?;
        Some(e)
    }

    /// What may follow a primary on the fast path: blanks, `, ) ; + - * /` or the end.
    fn check_follower(&self) -> Option<()> {
        let mut k = 0;
        while let Some(ch) = self.peek_at(k) {
            match ch {
                b' ' | b'\t' | b'\r' | b'\n' => k += 1,
                b',' | b')' | b';' | b'+' | b'-' | b'*' | b'/' => return Some(()),
                _ => return None,
            }
        }
        Some(())
    }

    /// `DIGITS [. DIGITS]`, not followed by anything that would make it a unit or a bad number.
    fn number(&mut self) -> Option<Expr> {
        let start = self.pos;
        while matches!(self.peek(), Some(b'0'..=b'9')) {
            self.pos += 1;
        }
        if self.peek() == Some(b'.') {
            self.pos += 1;
            while matches!(self.peek(), Some(b'0'..=b'9')) {
                self.pos += 1;
            }
        }
        if matches!(self.peek(), Some(ch) if ch.is_ascii_alphanumeric() || ch == b'.' || ch == b'_')
        {
            return None;
        }
        let span = Span::new(start, self.pos);
        let s = &self.text[span.range()];
        let kind = match s.parse::<f64>() {
            Ok(v) => ExprKind::Number(v),
            Err(_) => return None,
        };
        Some(Expr { kind, span })
    }

    /// `word (. word)*`, the first word not a keyword.
    fn path(&mut self) -> Option<Expr> {
        let start = self.pos;
        let first = self.name()?;
        let mut parts = vec![first];
        while self.peek() == Some(b'.') {
            self.pos += 1;
            let w = self.word()?;
            parts.push(Ident {
                text: self.text[w.range()].to_string(),
                span: w,
            });
        }
        let span = Span::new(start, self.pos);
        Some(Expr {
            kind: ExprKind::Path(Path { parts, span }),
            span,
        })
    }
}

fn prec(op: BinaryOp) -> u8 {
    match op {
        BinaryOp::Add | BinaryOp::Sub => 1,
        _ => 2,
    }
}

fn reduce(operands: &mut Vec<Expr>, ops: &mut Vec<BinaryOp>) {
    let (Some(op), Some(rhs), Some(lhs)) = (ops.pop(), operands.pop(), operands.pop()) else {
        return;
    };
    let span = lhs.span.to(rhs.span);
    operands.push(Expr {
        kind: ExprKind::Binary(op, Box::new(lhs), Box::new(rhs)),
        span,
    });
}

#[cfg(test)]
mod tests {
    use crate::parse::parse_with;

    fn same(text: &str) {
        let fast = parse_with(text, true);
        let slow = parse_with(text, false);
        assert_eq!(format!("{fast:?}"), format!("{slow:?}"), "for {text:?}");
    }

    #[test]
    fn the_fast_path_builds_what_pest_builds_on_every_model_in_the_repository() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let mut stack = vec![root];
        let mut seen = 0;
        while let Some(dir) = stack.pop() {
            let Ok(entries) = std::fs::read_dir(&dir) else {
                continue;
            };
            for e in entries.flatten() {
                let p = e.path();
                let name = e.file_name();
                let name = name.to_string_lossy();
                if p.is_dir() {
                    if !name.starts_with('.') && name != "target" {
                        stack.push(p);
                    }
                } else if name.ends_with(".gcs") {
                    if let Ok(text) = std::fs::read_to_string(&p) {
                        same(&text);
                        seen += 1;
                    }
                }
            }
        }
        assert!(seen > 10, "found only {seen} models");
    }

    #[test]
    fn the_fast_path_takes_the_plain_statements() {
        for text in [
            "point q1 = (1.1, 0.1);",
            "on(q1, axis);",
            "distance(q0, q1) = gap;",
            "param p2 = p1 * 2;",
            "fixed line axis = (0, 0) -> (1, 0);",
        ] {
            let span = crate::source::Span::new(0, text.len());
            assert!(super::statement(text, span).is_some(), "{text}");
        }
    }

    #[test]
    fn the_fast_path_builds_what_pest_builds_on_mutated_statements() {
        // Plain statements, each mutated by up to three random insertions, deletions or
        // replacements of tokens and blanks (a fixed xorshift sequence).
        let templates = [
            "point q1 = (1.1, 0.1);",
            "fixed line axis = (0, 0) -> (1, 0);",
            "on(q1, axis);",
            "distance(q0, q1) = gap;",
            "param p2 = p1 * 2 - -3 / q.r;",
            "segment s = (a, b) -> (c + 1, d);",
        ];
        let tokens = [
            " ", "\n", "\r\n", "\t", "(", ")", ",", ";", "=", "->", "-", "+", "*", "/", "^", ".",
            ":", "1", "2.5", "1e3", "a", "b.c", "deg", "pi", "point", "param", "fixed", "x",
            "//c\n", "/*c*/", "\u{e9}", "_", "0.", ".5", "center",
        ];
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = |n: usize| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % n as u64) as usize
        };
        for _ in 0..8_000 {
            let mut t = templates[next(templates.len())].to_string();
            for _ in 0..next(4) {
                let at = next(t.len() + 1);
                let at = (0..=at).rev().find(|&i| t.is_char_boundary(i)).unwrap_or(0);
                match next(3) {
                    0 => t.insert_str(at, tokens[next(tokens.len())]),
                    1 => {
                        if let Some(c) = t[at..].chars().next() {
                            t.replace_range(at..at + c.len_utf8(), "");
                        }
                    }
                    _ => {
                        if let Some(c) = t[at..].chars().next() {
                            t.replace_range(at..at + c.len_utf8(), tokens[next(tokens.len())]);
                        }
                    }
                }
            }
            same(&t);
        }
    }

    #[test]
    fn the_fast_path_builds_what_pest_builds_on_edge_cases() {
        let cases = [
            "space 2d; point a = (1, 2); point b = (3,4);",
            "param g = 1;\nparam h = -g * 2 + 3 / g - - 4;",
            "param h = a - b - c * d / e + f;",
            "param h = a-b;param k = a->b;",
            "fixed point q0 = (0, 0);\nfixed line l = (0, 0) -> (1, 0);",
            "line l = (0,0)->(1,0) ;  ",
            "segment s = (0, 0) -> (1, 0) (2, 3);",
            "on(a, b); distance(a, b) = gap; distance(a.b, c.d) = 2.5;",
            "f(); g( ); h(1) = 2;",
            "distance(a, b) = 1.;",
            "distance(a, b) = 1.e;",
            "distance(a, b) = 1e3;",
            "distance(a, b) = 30deg;",
            "distance(a, b) = 30 deg;",
            "angle(a, b) = pi / 2;",
            "distance(a, b) = (1 + 2);",
            "distance(a, b) = 2 ^ 3;",
            "distance(a, b) = f(2);",
            "distance(a, b) = f (2);",
            "lbl: distance(a, b) = 1;",
            "fixed distance(a, b) = 1;",
            "point p = (1);",
            "point p = (1, );",
            "point p = (1, 2) * 3;",
            "point p = (1, 2)",
            "point p = (1, 2); // comment\n",
            "point /* c */ p = (1, 2);",
            "point p = (1/2, 3);",
            "point point = (1, 2);",
            "point p = center (1, 2) radius 3;",
            "circle c = center (1, 2) radius 3;",
            "point p = (a., 2);",
            "point p = (a.b.c, _x9);",
            "point p = (1__2, 3);",
            "point p = (x.1, 3);",
            "param p = 1 2;",
            "param p = ;",
            "param = 1;",
            "param p == 1;",
            "output a, b.c;",
            "body B { point m = (0, 0); }",
            "on(q1 axis);",
            "on(q1,, axis);",
            "on(q1, axis)",
            "on q1, axis;",
            "distance(a, b) = 1 point c = (0, 0);",
            "distance(a, b) = gap\npoint c = (0, 0);",
            "point c = (é, 0);",
            "p(x) = -(1);",
            "param p = - - - 1 * - 2;",
            "fixed param p = 1;",
            "fixed on(a, b);",
            "point\tp =\r\n(1,\t2)\r\n;",
            "on (a , b) ;",
            "on(a . b, c);",
            "on(a.b., c);",
            "param p = 1.5.;",
            "param p = 1..2;",
            "param p = 2x;",
            "param p = q1\u{e9};",
            "param p = a +;",
            "param p = 1 - -2 * 3 / 4 - 5;",
            "space 2d;",
            "param p = 1;;",
            "point p = (1, 2)\n;",
            "point p = (1, 2)\r\n;",
            "point p = (1, 2) ;",
            "point p = (1, 2) -> (3, 4) ;",
            "point p = (1, 2) (3, 4) ;",
            "point p = (1, 2)->(3, 4)->(5, 6)\t;",
            "on(a, b) = 1 ;",
            "param p = 1 ;",
        ];
        for c in cases {
            same(c);
        }
        let mut long = String::from("param p = 1");
        for _ in 0..40 {
            long.push_str(" + 1");
        }
        long.push(';');
        same(&long);
    }
}
