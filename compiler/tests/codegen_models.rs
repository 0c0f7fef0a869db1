//! The models of `tests/models/`: the generated solver of each declares only frames its code
//! reads or moves. A frame nothing uses is an unused variable in the caller's crate, which
//! fails a build under `deny(warnings)`; the workspace's trybuild test builds and runs these
//! solvers, this one shows the cause directly.

mod discover {
    include!("../../examples/discover.rs");
}

/// The analysed models of `tests/models/`.
fn models() -> Vec<discover::Found> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    discover::analysed(&root, discover::Folder::TestModels)
}

/// The generated module of a model.
fn generated(m: &discover::Found) -> String {
    let c = gcs_compiler::compile(&m.file_name(), m.text.as_bytes())
        .unwrap_or_else(|e| panic!("{}: {e:?}", m.relative()));
    gcs_compiler::codegen::generate(&c.model, &c.analysis.plan).into()
}

/// The names of the frames a solve declares: `let [mut] NAME = Frame2::...;`.
fn declared_frames(code: &str) -> Vec<&str> {
    code.lines()
        .filter_map(|line| {
            let rest = line.trim_start().strip_prefix("let ")?;
            let rest = rest.strip_prefix("mut ").unwrap_or(rest);
            let (name, value) = rest.split_once(" = ")?;
            value.starts_with("Frame2::").then_some(name)
        })
        .collect()
}

/// The code of `solve`, without comments and string literals (a constraint's text may name a
/// geom).
fn solve_code(code: &str) -> String {
    let start = code.find("pub fn solve(").expect("a solve function");
    let mut out = String::new();
    let mut chars = code[start..].chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' => {
                while let Some(c) = chars.next() {
                    match c {
                        '\\' => {
                            chars.next();
                        }
                        '"' => break,
                        _ => {}
                    }
                }
                out.push_str("\"\"");
            }
            '/' if chars.peek() == Some(&'/') => {
                for c in chars.by_ref() {
                    if c == '\n' {
                        out.push('\n');
                        break;
                    }
                }
            }
            c => out.push(c),
        }
    }
    out
}

/// How many times `name` occurs in `code` as a whole identifier.
fn uses(code: &str, name: &str) -> usize {
    let ident = |c: char| c.is_ascii_alphanumeric() || c == '_';
    code.split(|c: char| !ident(c))
        .filter(|w| *w == name)
        .count()
}

#[test]
fn every_declared_frame_is_used() {
    let models = models();
    assert!(!models.is_empty(), "no models in tests/models");
    for m in models {
        let code = solve_code(&generated(&m));
        for frame in declared_frames(&code) {
            assert!(
                uses(&code, frame) > 1,
                "{}: frame `{frame}` is declared and never used:\n{code}",
                m.relative()
            );
        }
    }
}
