//! The text of the generated module: an indenting writer that keeps comments (which a token
//! printer would drop), and the spelling of Rust literals, so that every value is written one way.

/// An indenting writer over a `String`: infallible, so no `unwrap` on every line.
#[derive(Debug, Default)]
pub(super) struct Writer {
    pub(super) out: String,
    pub(super) indent: usize,
    /// Comments are left out: a piece's canonical form (see `lift`) is its code alone.
    pub(super) no_comments: bool,
    /// Where each line starts in `out`, and whether it is blank: the text's lines are counted
    /// and indented again (put in a block) without reading it.
    pub(super) starts: Vec<(usize, bool)>,
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
        // The words' own spaces at the end of the text are not written.
        match line.trim_end() {
            "" => self.line("///"),
            line => self.line(&format!("/// {line}")),
        }
    }

    pub(super) fn line(&mut self, text: &str) {
        self.starts.push((self.out.len(), text.is_empty()));
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

    /// The number of lines written.
    pub(super) fn lines(&self) -> usize {
        self.starts.len()
    }

    /// The text from byte `from` to `to` (a stretch of whole lines), with its lines.
    pub(super) fn slice(&self, from: usize, to: usize) -> Writer {
        let (first, last) = (
            self.starts.partition_point(|&(s, _)| s < from),
            self.starts.partition_point(|&(s, _)| s < to),
        );
        Writer {
            out: self.out[from..to].to_string(),
            indent: self.indent,
            no_comments: self.no_comments,
            starts: (self.starts[first..last].iter())
                .map(|&(s, blank)| (s - from, blank))
                .collect(),
        }
    }

    /// Puts the lines of `other` in at byte `at`, a line start.
    pub(super) fn insert(&mut self, at: usize, other: &Writer) {
        let k = self.starts.partition_point(|&(s, _)| s < at);
        let n = other.out.len();
        for (s, _) in &mut self.starts[k..] {
            *s += n;
        }
        let inserted = other.starts.iter().map(|&(s, blank)| (s + at, blank));
        self.starts.splice(k..k, inserted);
        self.out.insert_str(at, &other.out);
    }

    /// Appends the lines of `other`, each but a blank one level deeper (in a block).
    pub(super) fn push_deeper(&mut self, other: &Writer) {
        let mut from = 0;
        for &(s, blank) in &other.starts {
            self.out.push_str(&other.out[from..s]);
            self.starts.push((self.out.len(), blank));
            if !blank {
                self.out.push_str("    ");
            }
            from = s;
        }
        self.out.push_str(&other.out[from..]);
    }

    /// Appends the lines of `other` as they are.
    pub(super) fn push(&mut self, other: &Writer) {
        let at = self.out.len();
        (self.starts).extend(other.starts.iter().map(|&(s, blank)| (s + at, blank)));
        self.out.push_str(&other.out);
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

/// A float literal typed `f64`, as the receiver of a method must be: `2.0_f64.sqrt()`; and
/// whether it is written as a negative literal (not as a row's datum), which as a receiver
/// needs parentheses.
pub(super) fn typed_float(v: f64) -> (String, bool) {
    let written = std::cell::Cell::new(false);
    let literal = || {
        written.set(true);
        named_float(v).unwrap_or_else(|| format!("{}_f64", numeric_float(v)))
    };
    let code = super::lift::float(v, literal).unwrap_or_else(literal);
    (code, written.get() && v.is_finite() && v.is_sign_negative())
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
    // `Debug` spells every finite float with a decimal point or an exponent.
    format!("{v:?}")
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_are_kept_through_inserts_and_blocks() {
        let mut w = Writer::at(1);
        w.line("let a = 1.0;");
        w.line("");
        w.line("let c = a;");
        let mut b = Writer::at(1);
        b.line("let b = a;");
        w.insert(w.starts[1].0, &b);
        assert_eq!(
            w.out,
            "    let a = 1.0;\n    let b = a;\n\n    let c = a;\n"
        );
        assert_eq!(w.lines(), 4);
        let mut block = Writer::at(1);
        block.push_deeper(&w.slice(w.starts[1].0, w.out.len()));
        assert_eq!(block.out, "        let b = a;\n\n        let c = a;\n");
        assert_eq!(block.lines(), 3);
    }
}
