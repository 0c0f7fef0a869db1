//! The one maker of the generated module's identifiers, so that every name is derived from the
//! model's names the same way: snake case, keyword-safe, unique, never an index.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

/// Makes every identifier of the generated module: snake case, keyword-safe, unique within its
/// scope, derived from the model's names (repeats get `_2`, `_3`, ... in order of first use).
///
/// Two different names of the model that take the same identifier are a [`Clash`]: the
/// second gets a suffix, and a caller could set one thinking it sets the other. The namers of
/// the public API (params, branches, defaults, accessors) report them as diagnostics.
#[derive(Debug, Default)]
pub struct Namer {
    used: HashSet<String>,
    /// For a base, the suffix its last fresh name took: names are never released, so the
    /// next search for that base starts there instead of at `_2`.
    last: HashMap<String, usize>,
    /// The text each identifier was made from (none for a reserved one).
    owners: HashMap<String, Option<String>>,
    clashes: Vec<Clash>,
    /// Names are `v0`, `v1`, ... in order, whatever they are made from: a piece's canonical
    /// form (see `lift`) does not depend on the model's names.
    numbered: bool,
}

/// Two names of the model that become one identifier.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Clash {
    /// The identifier both become.
    pub identifier: String,
    /// The name that took it first, or none when the generated API reserves it.
    pub first: Option<String>,
    /// The name that had to take another.
    pub second: String,
}

const KEYWORDS: &[&str] = &[
    "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn", "for",
    "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref", "return",
    "self", "Self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use", "where",
    "while", "async", "await", "dyn", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen",
];

impl Namer {
    /// A namer whose names are numbers in order (see [`Namer::numbered`]'s field).
    pub(crate) fn numbered() -> Namer {
        Namer {
            numbered: true,
            ..Namer::default()
        }
    }

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

    /// A fresh identifier from `text`. A repeat takes `_2`, `_3`, ...: never a double
    /// underscore, which is not snake case.
    pub fn fresh(&mut self, text: &str) -> String {
        if self.numbered {
            let name = format!("v{}", self.used.len());
            self.used.insert(name.clone());
            return name;
        }
        let base = Self::snake(text);
        if let Some(first) = self.owners.get(&base) {
            if first.as_deref() != Some(text) {
                self.clashes.push(Clash {
                    identifier: base.clone(),
                    first: first.clone(),
                    second: text.to_string(),
                });
            }
        }
        let stem = base.trim_end_matches('_');
        let mut n = self.last.get(&base).copied().unwrap_or(1);
        let mut name = if n == 1 {
            base.clone()
        } else {
            format!("{stem}_{n}")
        };
        while self.used.contains(&name) {
            n += 1;
            name = format!("{stem}_{n}");
        }
        self.used.insert(name.clone());
        self.owners.insert(name.clone(), Some(text.to_string()));
        self.last.insert(base, n);
        name
    }

    /// Marks a name as taken by the generated API itself.
    pub fn reserve(&mut self, name: &str) {
        self.used.insert(name.to_string());
        self.owners.insert(name.to_string(), None);
    }

    /// The clashes met so far.
    pub fn clashes(&self) -> &[Clash] {
        &self.clashes
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keywords_and_repeats_stay_snake_case() {
        let mut n = Namer::default();
        assert_eq!(n.fresh("Self"), "self_");
        assert_eq!(n.fresh("self"), "self_2");
        assert_eq!(n.fresh("crank.b"), "crank_b");
        assert_eq!(n.fresh("crank_b"), "crank_b_2");
        assert_eq!(n.fresh("2d"), "v_2d");
        assert!(n.clashes().iter().all(|c| !c.identifier.contains("__")));
    }

    #[test]
    fn different_names_for_one_identifier_are_clashes() {
        let mut n = Namer::default();
        n.reserve("points");
        n.fresh("k");
        n.fresh("K");
        n.fresh("points");
        n.fresh("k");
        assert_eq!(
            n.clashes(),
            [
                Clash {
                    identifier: "k".into(),
                    first: Some("k".into()),
                    second: "K".into()
                },
                Clash {
                    identifier: "points".into(),
                    first: None,
                    second: "points".into()
                },
            ]
        );
    }
}
