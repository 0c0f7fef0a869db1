//! The text of the generated module: an indenting writer that keeps comments (which a token
//! printer would drop), and the spelling of Rust literals, so that every value is written one way.

/// An indenting writer over a `String`: infallible, so no `unwrap` on every line.
#[derive(Debug, Default)]
pub(super) struct Writer {
    pub(super) out: String,
    pub(super) indent: usize,
}

impl Writer {
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
}

/// A struct field initialiser, in shorthand when the names agree.
pub(super) fn field_init(field: &str, value: &str) -> String {
    if field == value {
        format!("{field},")
    } else {
        format!("{field}: {value},")
    }
}

/// A Rust string literal.
pub(super) fn lit(s: &str) -> String {
    format!("{s:?}")
}

/// A float literal: shortest round-trip form, always with a decimal point or exponent.
pub(super) fn float(v: f64) -> String {
    if v.is_nan() {
        return "f64::NAN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 {
            "f64::INFINITY".into()
        } else {
            "f64::NEG_INFINITY".into()
        };
    }
    for (c, name) in [
        (std::f64::consts::PI, "std::f64::consts::PI"),
        (std::f64::consts::FRAC_PI_2, "std::f64::consts::FRAC_PI_2"),
        (std::f64::consts::FRAC_PI_3, "std::f64::consts::FRAC_PI_3"),
        (std::f64::consts::FRAC_PI_4, "std::f64::consts::FRAC_PI_4"),
        (std::f64::consts::FRAC_PI_6, "std::f64::consts::FRAC_PI_6"),
        (std::f64::consts::TAU, "std::f64::consts::TAU"),
    ] {
        if v == c {
            return name.into();
        }
        if v == -c {
            return format!("-{name}");
        }
    }
    let s = format!("{v:?}");
    if s.contains('.') || s.contains('e') || s.contains("inf") {
        s
    } else {
        format!("{s}.0")
    }
}

/// Code for the sum of `coefficient * value` terms, leaving out the zero coefficients (the
/// compiler may not fold them: a NaN times zero is NaN) and writing a unit one as the value.
pub(super) fn linear(terms: &[(f64, String)]) -> String {
    let mut code = String::new();
    for (k, v) in terms.iter().filter(|(k, _)| *k != 0.0) {
        let term = match *k {
            1.0 => v.clone(),
            -1.0 => format!("-{v}"),
            k => format!("{v} * {}", float(k)),
        };
        if code.is_empty() {
            code = term;
        } else if let Some(minus) = term.strip_prefix('-') {
            code = format!("{code} - {minus}");
        } else {
            code = format!("{code} + {term}");
        }
    }
    if code.is_empty() {
        "0.0".into()
    } else {
        code
    }
}
