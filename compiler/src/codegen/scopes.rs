//! Keeps the lexical scopes of a long solve shallow, and the comparisons of large structs flat.
//!
//! Every `let` opens a scope nested in the one before it, to the end of its block. A debug build
//! describes that nesting to LLVM, whose DWARF writer recurses once per level, so a solve of
//! some thousands of `let`s in a row overflows rustc's stack (a chain of 1,024 four-bars has
//! about 8,000). A long solve is therefore written in blocks, each handing on the values later
//! code reads, and a long list of declarations as tuple `let`s: the nesting then grows as the
//! square root of the number of `let`s. Code short enough to nest safely is written as it is.
//!
//! A derived `PartialEq` compares all of a struct's fields in one `&&` chain, which rustc
//! recurses through: the `Branches` and `Solution` of a chain of 10,000 four-bars (10,000 and
//! 20,001 fields) overflow its stack. Past [`FLAT_LETS`] fields, it is written field by field.

use super::writer::Writer;
use rustc_hash::FxHashSet as HashSet;

/// Code with at most this many `let`s in a row is written flat: deep enough for any model a
/// person writes by hand, and far from the depth that overflows (thousands).
pub(super) const FLAT_LETS: usize = 512;

/// The fewest `let`s a block, or bindings a tuple `let`, holds once code is split.
const MIN_BLOCK: usize = 64;

/// How many `let`s go in one block (or one tuple) when `total` are split: about the square
/// root, so that the number of blocks and the depth inside each stay about equal.
fn block_size(total: usize) -> usize {
    MIN_BLOCK.max((total as f64).sqrt().ceil() as usize)
}

/// One binding of the solve's declarations: `let [mut] name = value;`.
pub(super) struct Binding {
    pub mutable: bool,
    pub name: String,
    pub value: String,
}

impl Binding {
    fn pattern(&self) -> String {
        match self.mutable {
            true => format!("mut {}", self.name),
            false => self.name.clone(),
        }
    }
}

/// Writes `bindings` in order: a `let` each, or, past [`FLAT_LETS`], tuple `let`s of
/// [`block_size`] bindings. No binding's value may read another binding of the list.
pub(super) fn declare(w: &mut Writer, bindings: &[Binding]) {
    if bindings.len() <= FLAT_LETS {
        for b in bindings {
            w.line(&format!("let {} = {};", b.pattern(), b.value));
        }
        return;
    }
    w.line(&format!(
        "// {} declarations, {} to a `let`: a `let` each would nest their scopes too deep for",
        bindings.len(),
        block_size(bindings.len())
    ));
    w.line("// a debug build.");
    for chunk in bindings.chunks(block_size(bindings.len())) {
        if let [b] = chunk {
            w.line(&format!("let {} = {};", b.pattern(), b.value));
            continue;
        }
        let patterns: Vec<String> = chunk.iter().map(Binding::pattern).collect();
        w.open(&format!("let ({}) = (", patterns.join(", ")));
        for b in chunk {
            w.line(&format!("{},", b.value));
        }
        w.close(");");
    }
}

/// The `derive` attribute of a generated struct of `fields` fields: `Clone, Copy, Debug`, and
/// `PartialEq` (with `Eq` when `eq`) unless the struct is too large to derive it (see
/// [`field_by_field_eq`]).
pub(super) fn derives(fields: usize, eq: bool) -> String {
    let mut traits = vec!["Clone", "Copy", "Debug"];
    if fields <= FLAT_LETS {
        traits.push("PartialEq");
        if eq {
            traits.push("Eq");
        }
    }
    format!("#[derive({})]", traits.join(", "))
}

/// For a struct too large for [`derives`] to derive `PartialEq`, the impl written field by
/// field: a statement each, where the derive nests one `&&` per field. Nothing otherwise.
pub(super) fn field_by_field_eq(w: &mut Writer, name: &str, fields: &[String], eq: bool) {
    if fields.len() <= FLAT_LETS {
        return;
    }
    w.line(&format!(
        "// Compared field by field: a derive's one `&&` chain over {} fields is too deep for rustc.",
        fields.len()
    ));
    w.open(&format!("impl PartialEq for {name} {{"));
    w.open("fn eq(&self, other: &Self) -> bool {");
    for f in fields {
        w.open(&format!("if self.{f} != other.{f} {{"));
        w.line("return false;");
        w.close("}");
    }
    w.line("true");
    w.close("}");
    w.close("}");
    if eq {
        w.line("");
        w.line(&format!("impl Eq for {name} {{}}"));
    }
    w.line("");
}

/// A group of the solve's steps: its code, and what the ledger holds of it (see `ledger`).
pub(super) struct Group {
    pub code: Writer,
    /// The locals its top-level `let`s declare, in order.
    pub lets: Vec<String>,
    /// The locals its code reads.
    pub reads: Vec<String>,
}

/// The solve's step groups, in order, at `indent`: the groups themselves, or, past
/// [`FLAT_LETS`] `let`s at the top level, runs of groups each in a block of its own that ends
/// with the locals it defines and code after it reads (a later block, or `later`, the locals
/// the code after the groups reads).
pub(super) fn in_blocks(groups: &[Group], later: &[&str], indent: usize) -> Writer {
    let mut w = Writer::at(indent);
    let total: usize = groups.iter().map(|g| g.lets.len()).sum();
    if total <= FLAT_LETS {
        groups.iter().for_each(|g| w.push(&g.code));
        return w;
    }
    // Runs of whole groups, each closed once it holds `size` lets.
    let size = block_size(total);
    let mut runs = Vec::new();
    let (mut start, mut lets) = (0, 0);
    for (i, g) in groups.iter().enumerate() {
        lets += g.lets.len();
        if lets >= size || i + 1 == groups.len() {
            runs.push(start..i + 1);
            start = i + 1;
            lets = 0;
        }
    }
    // What each run hands on: its locals that code after it reads, found from the end back.
    let mut read_after: HashSet<&str> = later.iter().copied().collect();
    let mut handed_on = vec![Vec::new(); runs.len()];
    for (k, run) in runs.iter().enumerate().rev() {
        handed_on[k] = groups[run.clone()]
            .iter()
            .flat_map(|g| &g.lets)
            .map(String::as_str)
            .filter(|name| read_after.contains(name))
            .collect::<Vec<_>>();
        for g in &groups[run.clone()] {
            read_after.extend(g.reads.iter().map(String::as_str));
        }
    }
    for (run, out) in runs.iter().zip(&handed_on) {
        w.line("");
        w.line(match out.len() {
            0 => "// A block of steps, so that a debug build's scopes stay shallow.",
            _ => "// A block of steps, so that a debug build's scopes stay shallow; it hands on what later steps read.",
        });
        // The block's value: the one local it hands on, or a tuple of them.
        let value = match out.as_slice() {
            [] => None,
            [one] => Some(one.to_string()),
            many => Some(format!("({})", many.join(", "))),
        };
        match &value {
            None => w.open("{"),
            Some(v) => w.open(&format!("let {v} = {{")),
        }
        for g in &groups[run.clone()] {
            w.push_deeper(&g.code);
        }
        match &value {
            None => w.close("}"),
            Some(v) => {
                w.line(v);
                w.close("};");
            }
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A group of `n` lets at indent 1: `let {prefix}_i = {prefix}_{i-1} + 1.0;`, the first
    /// reading `input`, with what the ledger would hold of it.
    fn group(prefix: &str, n: usize, input: &str) -> Group {
        let mut code = Writer::at(1);
        code.line("");
        code.line(&format!("// {prefix}"));
        let (mut lets, mut reads) = (Vec::new(), Vec::new());
        for i in 0..n {
            let from = match i {
                0 => input.to_string(),
                _ => format!("{prefix}_{}", i - 1),
            };
            code.line(&format!("let {prefix}_{i} = {from} + 1.0;"));
            lets.push(format!("{prefix}_{i}"));
            reads.push(from);
        }
        Group { code, lets, reads }
    }

    fn text(groups: &[Group]) -> String {
        groups.iter().map(|g| g.code.out.as_str()).collect()
    }

    #[test]
    fn short_code_is_written_as_it_is() {
        let groups = vec![group("a", 10, "x"), group("b", 10, "a_9")];
        assert_eq!(in_blocks(&groups, &["b_9"], 1).out, text(&groups));
        let mut w = Writer::at(1);
        let bindings = [Binding {
            mutable: true,
            name: "crank".into(),
            value: "Frame2::at(Point2::origin())".into(),
        }];
        declare(&mut w, &bindings);
        assert_eq!(w.out, "    let mut crank = Frame2::at(Point2::origin());\n");
    }

    #[test]
    fn long_code_hands_on_exactly_what_later_code_reads() {
        // 40 groups of 20 lets: 800 in all, so blocks of about 64 lets (4 groups), each reading
        // the last local of the group before; the tail reads the very last one.
        let groups: Vec<Group> = (0..40)
            .map(|k| {
                let input = match k {
                    0 => "x".to_string(),
                    _ => format!("g{}_19", k - 1),
                };
                group(&format!("g{k}"), 20, &input)
            })
            .collect();
        let text = in_blocks(&groups, &["g39_19"], 1).out;
        // Ten blocks, each at the top level of the function.
        assert_eq!(text.matches("\n    let g").count(), 10, "{text}");
        assert_eq!(text.matches("\n    {\n").count(), 0);
        // Each block hands on the one local the next block (or the tail) reads.
        for k in 0..10 {
            let last = 4 * k + 3;
            assert!(
                text.contains(&format!("    let g{last}_19 = {{\n")),
                "block {k} hands on g{last}_19:\n{text}"
            );
            assert!(text.contains(&format!("        g{last}_19\n    }};\n")));
        }
        // Every original line is kept, one level deeper.
        for g in &groups {
            for line in g.code.out.split('\n').filter(|l| !l.is_empty()) {
                assert!(text.contains(&format!("    {line}\n")), "{line}");
            }
        }
    }

    #[test]
    fn a_block_nothing_later_reads_from_hands_on_nothing() {
        let groups: Vec<Group> = (0..40).map(|k| group(&format!("g{k}"), 20, "x")).collect();
        let text = in_blocks(&groups, &[], 1).out;
        assert_eq!(text.matches("\n    {\n").count(), 10, "{text}");
        assert!(!text.contains("\n    let g"), "{text}");
    }

    #[test]
    fn several_locals_are_handed_on_as_a_tuple() {
        let mut groups: Vec<Group> = (0..40).map(|k| group(&format!("g{k}"), 20, "x")).collect();
        let mut code = Writer::at(1);
        code.line("");
        code.line("let y = g0_3 * g1_7;");
        groups.push(Group {
            code,
            lets: vec!["y".into()],
            reads: vec!["g0_3".into(), "g1_7".into()],
        });
        let text = in_blocks(&groups, &["y"], 1).out;
        assert!(text.contains("    let (g0_3, g1_7) = {\n"), "{text}");
        assert!(text.contains("        (g0_3, g1_7)\n    };\n"));
    }

    #[test]
    fn large_structs_are_compared_field_by_field() {
        assert_eq!(
            derives(3, true),
            "#[derive(Clone, Copy, Debug, PartialEq, Eq)]"
        );
        assert_eq!(derives(600, true), "#[derive(Clone, Copy, Debug)]");
        let fields: Vec<String> = (0..600).map(|i| format!("elbow{i}")).collect();
        let mut w = Writer::default();
        field_by_field_eq(&mut w, "Branches", &fields[..3], true);
        assert_eq!(w.out, "");
        field_by_field_eq(&mut w, "Branches", &fields, true);
        assert!(w.out.contains("impl PartialEq for Branches {\n"));
        assert!(w
            .out
            .contains("        if self.elbow599 != other.elbow599 {\n"));
        assert_eq!(w.out.matches("return false;").count(), 600);
        assert!(w.out.contains("impl Eq for Branches {}\n"));
    }

    #[test]
    fn long_declarations_are_tuple_lets() {
        let bindings: Vec<Binding> = (0..600)
            .map(|i| Binding {
                mutable: i % 2 == 0,
                name: format!("f{i}"),
                value: format!("Frame2::at(Point2::new({i}.0, 0.0))"),
            })
            .collect();
        let mut w = Writer::at(1);
        declare(&mut w, &bindings);
        // sqrt(600) rounds up to 25, below the least block: 64 a tuple, ten tuples.
        assert_eq!(w.out.matches("let (").count(), 10, "{}", w.out);
        assert!(w.out.contains("    let (mut f0, f1, mut f2,"));
        assert!(w
            .out
            .contains("        Frame2::at(Point2::new(599.0, 0.0)),\n    );\n"));
    }
}
