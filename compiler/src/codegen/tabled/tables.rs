//! The static tables of a large model's module: a row of a piece's or a value's data a line, a
//! list of numbers several to a line, and every string once in one literal.

use crate::codegen::writer::lit;
use crate::codegen::writer::Writer;
use rustc_hash::FxHashMap as HashMap;
use std::fmt::Write as _;

/// A static table, left as it is by rustfmt.
pub(super) struct Table {
    name: String,
    /// The type of the array but its length and closing bracket (`[u32; `).
    head: String,
    entries: Vec<String>,
    /// Each entry is a row: one to a line.
    rows: bool,
    /// The entries of the array a row holds (1 but for a flat table of rows).
    width: usize,
}

impl Table {
    /// A table of numbers (or pairs) of type `ty`, written several to a line.
    pub(super) fn packed(name: &str, ty: &str, entries: Vec<String>) -> Table {
        Table {
            name: name.to_string(),
            head: format!("[{ty}; "),
            entries,
            rows: false,
            width: 1,
        }
    }

    /// A flat table of `ty` whose rows are `width` entries each, a row to a line (with its
    /// comment): rustc reads a flat array of numbers several times faster than one of structs
    /// or nested arrays, which counts in a model of 100,000 stages.
    pub(super) fn flat_rows(name: &str, ty: &str, width: usize, rows: Vec<String>) -> Table {
        Table {
            name: name.to_string(),
            head: format!("[{ty}; "),
            entries: rows,
            rows: true,
            width,
        }
    }

    /// Appends the table to `out`, `per_line` entries to a line for a packed one.
    pub(super) fn write(&self, out: &mut String, per_line: usize) {
        let n = self.entries.len() * self.width;
        let _ = writeln!(out, "#[rustfmt::skip]");
        let _ = writeln!(out, "static {}: {}{n}] = [", self.name, self.head);
        if self.rows {
            for e in &self.entries {
                let _ = writeln!(out, "    {e}");
            }
        } else {
            for line in self.entries.chunks(per_line.max(1)) {
                let _ = writeln!(out, "    {},", line.join(", "));
            }
        }
        let _ = writeln!(out, "];\n");
    }
}

/// Every string the tables hold, once: one literal (`STRINGS`) and the byte offset where each
/// starts (`STRING_AT`), read by `text(id)`. rustc's time grows with the number of string
/// literals it is given; one literal of a million names costs little.
#[derive(Default)]
pub(super) struct Strings {
    text: String,
    at: Vec<u32>,
    ids: HashMap<String, u32>,
}

impl Strings {
    /// The id of string `s`.
    pub(super) fn id(&mut self, s: &str) -> u32 {
        if let Some(&id) = self.ids.get(s) {
            return id;
        }
        if self.at.is_empty() {
            self.at.push(0);
        }
        self.text.push_str(s);
        self.at.push(self.text.len() as u32);
        let id = self.ids.len() as u32;
        self.ids.insert(s.to_string(), id);
        id
    }

    /// The entries `[name's string id, index in model order]` sorted by name, for `find`.
    pub(super) fn by_name<'n>(&mut self, names: impl Iterator<Item = &'n str>) -> Vec<String> {
        let mut sorted: Vec<(&str, usize)> = names.enumerate().map(|(k, n)| (n, k)).collect();
        sorted.sort();
        sorted
            .iter()
            .map(|(n, k)| format!("[{}, {k}]", self.id(n)))
            .collect()
    }

    /// The tables and `text`.
    pub(super) fn write(&self, w: &mut Writer, tables: &mut String) {
        w.line("/// String `id` of the tables (`STRINGS`, `STRING_AT`).");
        w.open("fn text(id: u32) -> &'static str {");
        w.line("let i = id as usize;");
        w.open("match (STRING_AT.get(i), STRING_AT.get(i + 1)) {");
        w.line(
            "(Some(&from), Some(&to)) => STRINGS.get(from as usize..to as usize).unwrap_or(\"\"),",
        );
        w.line("_ => \"\",");
        w.close("}");
        w.close("}");
        w.line("");
        let _ = writeln!(tables, "#[rustfmt::skip]");
        let _ = writeln!(tables, "static STRINGS: &str = {};\n", lit(&self.text));
        let at: Vec<String> = self.at.iter().map(u32::to_string).collect();
        Table::packed("STRING_AT", "u32", at).write(tables, 16);
    }
}
