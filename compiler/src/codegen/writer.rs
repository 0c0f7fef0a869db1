//! The text of the generated module: an indenting writer that keeps comments (which a token
//! printer would drop), and the spelling of Rust literals, so that every value is written one way.

/// An indenting writer over a `String`: infallible, so no `unwrap` on every line.
#[derive(Debug, Default)]
pub(super) struct Writer {
    pub(super) out: String,
    pub(super) indent: usize,
    /// Comments are left out: a piece's canonical form (see `lift`) is its code alone.
    pub(super) no_comments: bool,
}

impl Writer {
    /// A writer of code at `indent`.
    pub(super) fn at(indent: usize) -> Writer {
        Writer {
            indent,
            ..Writer::default()
        }
    }

    /// A `//` comment line (`text` without its slashes); nothing in a canonical form.
    pub(super) fn comment(&mut self, text: &str) {
        if !self.no_comments {
            self.line(&format!("// {text}"));
        }
    }

    /// A `///` doc comment of `text`, wrapped at the formatter's width as a person would.
    pub(super) fn doc(&mut self, text: &str) {
        let width = 96usize.saturating_sub(4 * self.indent + 4).max(40);
        let mut line = String::new();
        for word in text.split(' ') {
            if !line.is_empty() && line.len() + 1 + word.len() > width {
                self.line(&format!("/// {line}"));
                line.clear();
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
        self.line(&format!("/// {line}").trim_end());
    }

    pub(super) fn line(&mut self, text: &str) {
        if text.is_empty() {
            self.out.push('\n');
            return;
        }
        for _ in 0..self.indent {
            self.out.push_str("    ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }
    pub(super) fn open(&mut self, text: &str) {
        self.line(text);
        self.indent += 1;
    }
    pub(super) fn close(&mut self, text: &str) {
        self.indent = self.indent.saturating_sub(1);
        self.line(text);
    }
    /// Takes back the last blank line, if the text ends with one.
    pub(super) fn unblank(&mut self) {
        if self.out.ends_with("\n\n") {
            self.out.pop();
        }
    }
}

/// A struct field initialiser, in shorthand when the names agree.
pub(super) fn field_init(field: &str, value: &str) -> String {
    if field == value {
        format!("{field},")
    } else {
        format!("{field}: {value},")
    }
}

/// A Rust string literal (in a piece of a large model, what its row holds: see `lift`).
pub(super) fn lit(s: &str) -> String {
    let literal = || format!("{s:?}");
    super::lift::text(s, literal).unwrap_or_else(literal)
}

/// A float literal: shortest round-trip form, always with a decimal point or exponent (in a
/// piece of a large model, what its row holds: see `lift`).
pub(super) fn float(v: f64) -> String {
    let literal = || named_float(v).unwrap_or_else(|| numeric_float(v));
    super::lift::float(v, literal).unwrap_or_else(literal)
}

/// A float literal typed `f64`, as the receiver of a method must be: `2.0_f64.sqrt()`.
pub(super) fn typed_float(v: f64) -> String {
    let literal = || named_float(v).unwrap_or_else(|| format!("{}_f64", numeric_float(v)));
    super::lift::float(v, literal).unwrap_or_else(literal)
}

/// The float as a constant of `f64` or `std::f64::consts`, when it is one.
fn named_float(v: f64) -> Option<String> {
    if v.is_nan() {
        return Some("f64::NAN".into());
    }
    if v.is_infinite() {
        let name = if v > 0.0 {
            "f64::INFINITY"
        } else {
            "f64::NEG_INFINITY"
        };
        return Some(name.into());
    }
    for (c, name) in [
        (std::f64::consts::PI, "std::f64::consts::PI"),
        (std::f64::consts::FRAC_PI_2, "std::f64::consts::FRAC_PI_2"),
        (std::f64::consts::FRAC_PI_3, "std::f64::consts::FRAC_PI_3"),
        (std::f64::consts::FRAC_PI_4, "std::f64::consts::FRAC_PI_4"),
        (std::f64::consts::FRAC_PI_6, "std::f64::consts::FRAC_PI_6"),
        (std::f64::consts::TAU, "std::f64::consts::TAU"),
        // The other constants a literal would be taken for (clippy's `approx_constant`).
        (std::f64::consts::FRAC_PI_8, "std::f64::consts::FRAC_PI_8"),
        (std::f64::consts::FRAC_1_PI, "std::f64::consts::FRAC_1_PI"),
        (std::f64::consts::FRAC_2_PI, "std::f64::consts::FRAC_2_PI"),
        (
            std::f64::consts::FRAC_2_SQRT_PI,
            "std::f64::consts::FRAC_2_SQRT_PI",
        ),
        (std::f64::consts::SQRT_2, "std::f64::consts::SQRT_2"),
        (
            std::f64::consts::FRAC_1_SQRT_2,
            "std::f64::consts::FRAC_1_SQRT_2",
        ),
        (std::f64::consts::E, "std::f64::consts::E"),
        (std::f64::consts::LN_2, "std::f64::consts::LN_2"),
        (std::f64::consts::LN_10, "std::f64::consts::LN_10"),
        (std::f64::consts::LOG2_E, "std::f64::consts::LOG2_E"),
        (std::f64::consts::LOG10_E, "std::f64::consts::LOG10_E"),
        (std::f64::consts::LOG2_10, "std::f64::consts::LOG2_10"),
        (std::f64::consts::LOG10_2, "std::f64::consts::LOG10_2"),
    ] {
        if v == c {
            return Some(name.into());
        }
        if v == -c {
            return Some(format!("-{name}"));
        }
    }
    None
}

/// A finite float in digits.
fn numeric_float(v: f64) -> String {
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') {
        s
    } else {
        format!("{s}.0")
    }
}

/// Code for the sum of `coefficient * value` terms, leaving out the zero coefficients (the
/// compiler may not fold them: a NaN times zero is NaN) and writing a unit one as its sign.
pub(super) fn linear(terms: &[(f64, String)]) -> String {
    let mut code = String::new();
    for (k, v) in terms.iter().filter(|(k, _)| *k != 0.0) {
        let (minus, term) = match *k {
            1.0 => (false, v.clone()),
            -1.0 => (true, v.clone()),
            k => (false, format!("{v} * {}", float(k))),
        };
        code = match (code.is_empty(), minus) {
            (true, false) => term,
            (true, true) => format!("-{term}"),
            (false, false) => format!("{code} + {term}"),
            (false, true) => format!("{code} - {term}"),
        };
    }
    if code.is_empty() {
        "0.0".into()
    } else {
        code
    }
}
