//! Canonicity: shuffling the statements of every example and test model the analysis covers
//! gives the same solution and the same plan, up to the numbering of registers.
//!
//! Statements are split at `;` at brace depth 0 and at the `}` closing a body (comments
//! stripped first), the `space` header stays first, and the rest is permuted by a small
//! xorshift generator with fixed seeds, so every run tests the same permutations.

use gcs_compiler::analyse;
use gcs_compiler::solution::Solution;
use gcs_lang::Model;

mod discover {
    include!("../../examples/discover.rs");
}

const PERMUTATIONS: u64 = 20;

fn example_text(name: &str) -> String {
    let path = format!("{}/../examples/{name}.gcs", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("read {path}: {e}"))
}

/// The text without `//` and `/* */` comments (the examples have no comment markers inside
/// strings: the language has no strings).
fn strip_comments(text: &str) -> String {
    let mut out = String::new();
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, chars.peek()) {
            ('/', Some('/')) => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            ('/', Some('*')) => {
                chars.next();
                let mut prev = ' ';
                for c in chars.by_ref() {
                    if prev == '*' && c == '/' {
                        break;
                    }
                    prev = c;
                }
                out.push(' ');
            }
            _ => out.push(c),
        }
    }
    out
}

/// The statements of a file, each with its terminator (`;` or the `}` of a body).
fn statements(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut depth = 0usize;
    for c in strip_comments(text).chars() {
        cur.push(c);
        match c {
            '{' => depth += 1,
            '}' => {
                depth = depth.checked_sub(1).expect("unbalanced braces");
                if depth == 0 {
                    out.push(std::mem::take(&mut cur));
                }
            }
            ';' if depth == 0 => out.push(std::mem::take(&mut cur)),
            _ => {}
        }
    }
    assert!(cur.trim().is_empty(), "trailing text: {cur:?}");
    out.into_iter()
        .map(|s| s.trim().to_string())
        // A `;` after a body's block is a statement of its own: drop it.
        .filter(|s| !s.is_empty() && s != ";")
        .collect()
}

/// xorshift64*.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// The file with its statements after the `space` header in a seeded random order.
fn shuffled(text: &str, seed: u64) -> String {
    let mut stmts = statements(text);
    let space = stmts
        .iter()
        .position(|s| s.starts_with("space"))
        .expect("a space header");
    let header = stmts.remove(space);
    let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
    for i in (1..stmts.len()).rev() {
        let j = rng.below(i + 1);
        stmts.swap(i, j);
    }
    let mut out = header;
    out.push('\n');
    for s in stmts {
        out.push_str(&s);
        out.push('\n');
    }
    out
}

fn load(name: &str, text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load(name, text.as_bytes());
    assert!(
        diags.iter().all(|d| !d.is_error()),
        "{name}: {diags:?}\n{text}"
    );
    model.unwrap_or_else(|| panic!("{name}: no model\n{text}"))
}

/// Analyses and solves with the default params and branches; returns the plan dump (with
/// registers renumbered) and the solution.
fn run(name: &str, text: &str) -> (String, Solution) {
    let model = load(name, text);
    let analysis = analyse(&model).unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
    let branches: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
    let solution = gcs_compiler::solve(&model, &analysis, &model.default_params(), &branches)
        .unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
    (normalise_registers(&analysis.plan.dump(&model)), solution)
}

/// Renames every register `rN` of a dump to `r0`, `r1`, ... in order of first appearance.
fn normalise_registers(dump: &str) -> String {
    let chars: Vec<char> = dump.chars().collect();
    let word = |c: char| c.is_alphanumeric() || c == '_' || c == '.';
    let mut names: Vec<String> = Vec::new();
    let mut out = String::new();
    let mut i = 0;
    while i < chars.len() {
        let starts = chars[i] == 'r' && (i == 0 || !word(chars[i - 1]));
        if starts {
            let mut j = i + 1;
            while j < chars.len() && chars[j].is_ascii_digit() {
                j += 1;
            }
            if j > i + 1 && (j == chars.len() || !word(chars[j])) {
                let reg: String = chars[i..j].iter().collect();
                let n = match names.iter().position(|r| *r == reg) {
                    Some(n) => n,
                    None => {
                        names.push(reg);
                        names.len() - 1
                    }
                };
                out.push_str(&format!("r{n}"));
                i = j;
                continue;
            }
        }
        out.push(chars[i]);
        i += 1;
    }
    out
}

/// Asserts two solutions agree on every point, vector, scalar and branch, by name.
fn assert_same_solution(what: &str, want: &Solution, got: &Solution) {
    let mut want_points: Vec<_> = want
        .points
        .iter()
        .chain(&want.vectors)
        .map(|(n, v)| (n.clone(), v.clone()))
        .collect();
    let mut got_points: Vec<_> = got
        .points
        .iter()
        .chain(&got.vectors)
        .map(|(n, v)| (n.clone(), v.clone()))
        .collect();
    want_points.sort_by(|a, b| a.0.cmp(&b.0));
    got_points.sort_by(|a, b| a.0.cmp(&b.0));
    let names = |v: &[(String, Vec<f64>)]| v.iter().map(|(n, _)| n.clone()).collect::<Vec<_>>();
    assert_eq!(
        names(&want_points),
        names(&got_points),
        "{what}: named features differ"
    );
    let (want_named, got_named) = (want.by_name(), got.by_name());
    for (name, w) in &want_points {
        let g = got_named
            .point(name)
            .or_else(|| got_named.vector(name))
            .expect("same names");
        let w2 = want_named
            .point(name)
            .or_else(|| want_named.vector(name))
            .expect("name");
        assert_eq!(w2, w.as_slice());
        let off = w
            .iter()
            .zip(g)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(off <= 1e-12, "{what}: {name} = {g:?}, original {w:?}");
    }
    let mut ws = want.scalars.clone();
    let mut gs = got.scalars.clone();
    ws.sort_by(|a, b| a.0.cmp(&b.0));
    gs.sort_by(|a, b| a.0.cmp(&b.0));
    assert_eq!(ws.len(), gs.len(), "{what}: scalars {ws:?} vs {gs:?}");
    for ((wn, wv), (gn, gv)) in ws.iter().zip(&gs) {
        assert_eq!(wn, gn, "{what}: scalar names");
        assert!(
            (wv - gv).abs() <= 1e-12,
            "{what}: {wn} = {gv}, original {wv}"
        );
    }
    let mut wb = want.branches.clone();
    let mut gb = got.branches.clone();
    wb.sort();
    gb.sort();
    assert_eq!(wb, gb, "{what}: branches");
    assert_eq!(want.grounded, got.grounded, "{what}: grounded geom");
}

#[test]
fn splitter_and_normaliser_work() {
    let text =
        "// c\nspace 2d; /* x; */ param a = 1;\nbody B { point p = (0, 0); };\npoint q = (1, a);";
    assert_eq!(
        statements(text),
        vec![
            "space 2d;",
            "param a = 1;",
            "body B { point p = (0, 0); }",
            "point q = (1, a);"
        ]
    );
    assert_eq!(
        normalise_registers("r7 : Point = point_of rocker.r1\nr3 = f r7 r12 ;r3"),
        "r0 : Point = point_of rocker.r1\nr1 = f r0 r2 ;r1"
    );
    let mut seen = std::collections::BTreeSet::new();
    for seed in 0..PERMUTATIONS {
        seen.insert(shuffled(&example_text("fourbar"), seed));
    }
    assert!(
        seen.len() as u64 == PERMUTATIONS,
        "seeds give distinct orders"
    );
}

#[test]
fn shuffled_examples_solve_and_plan_the_same() {
    let mut failures = Vec::new();
    let mut checked = 0;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut examples = discover::analysed(&root, discover::Folder::Examples);
    examples.extend(discover::analysed(&root, discover::Folder::TestModels));
    for example in &examples {
        let name = &example.stem;
        let text = example.text.clone();
        let (dump, solution) = run(name, &text);
        let stmts = statements(&text).len();
        for seed in 0..PERMUTATIONS {
            let text2 = shuffled(&text, seed);
            let what = format!("{name} (seed {seed})");
            let outcome = std::panic::catch_unwind(|| {
                let (dump2, solution2) = run(&what, &text2);
                assert_same_solution(&what, &solution, &solution2);
                assert_eq!(
                    dump, dump2,
                    "{what}: plan differs (registers renumbered)\n--- original\n{dump}\n--- shuffled\n{dump2}\n--- text\n{text2}"
                );
            });
            checked += 1;
            if let Err(e) = outcome {
                let msg = e
                    .downcast_ref::<String>()
                    .cloned()
                    .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_default();
                failures.push(format!("{what}: {msg}"));
            }
        }
        eprintln!("{name}: {stmts} statements, {PERMUTATIONS} permutations");
    }
    eprintln!(
        "canonicity: {checked} permutations of {} examples, {} failures",
        examples.len(),
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{} of {checked} permutations differ:\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}
