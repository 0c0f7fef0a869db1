//! The one maker of the generated module's identifiers, so that every name is derived from the
//! model's names the same way: snake case, keyword-safe, unique, never an index.

use std::collections::{HashMap, HashSet};

/// Makes every identifier of the generated module: snake case, keyword-safe, unique within its
/// scope, derived from the model's names (repeats get `_2`, `_3`, ... in order of first use).
#[derive(Debug, Default)]
pub struct Namer {
    used: HashSet<String>,
    /// For a base, the suffix its last fresh name took: names are never released, so the
    /// next search for that base starts there instead of at `_2`.
    last: HashMap<String, usize>,
}

const KEYWORDS: &[&str] = &[
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for",
    "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
    "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where",
    "while", "async", "await", "dyn", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen",
];

impl Namer {
    /// `text` as a snake-case identifier (not yet unique).
    pub fn snake(text: &str) -> String {
        let mut out = String::new();
        for c in text.chars() {
            if c.is_ascii_alphanumeric() {
                out.push(c.to_ascii_lowercase());
            } else if !out.ends_with('_') {
                out.push('_');
            }
        }
        let mut out = out.trim_matches('_').to_string();
        if out.is_empty() {
            out = "value".into();
        }
        if out.starts_with(|c: char| c.is_ascii_digit()) {
            out.insert_str(0, "v_");
        }
        if KEYWORDS.contains(&out.as_str()) {
            out.push('_');
        }
        out
    }

    /// A fresh identifier from `text`.
    pub fn fresh(&mut self, text: &str) -> String {
        let base = Self::snake(text);
        let mut n = self.last.get(&base).copied().unwrap_or(1);
        let mut name = if n == 1 {
            base.clone()
        } else {
            format!("{base}_{n}")
        };
        while self.used.contains(&name) {
            n += 1;
            name = format!("{base}_{n}");
        }
        self.used.insert(name.clone());
        self.last.insert(base, n);
        name
    }

    /// Marks a name as taken.
    pub fn reserve(&mut self, name: &str) {
        self.used.insert(name.to_string());
    }
}
