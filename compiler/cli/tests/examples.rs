//! Golden outputs of every example model the analysis covers, for every view: `check`,
//! `explain`, `plan` and `solve --json` (`tests/goldens/<example>.<view>`). Regenerate them, or
//! create a new example's, with `UPDATE_EXPECT=1 cargo test -p gcs-cli --test examples`.

use expect_test::expect_file;
use std::path::Path;

use support::gcs;

mod support;

mod discover {
    include!("../../../examples/discover.rs");
}

/// Numbers at fixed precision (10 decimals, no negative zero), so that goldens do not depend
/// on the last bits of a platform's libm.
fn fixed_precision(text: &str) -> String {
    let mut out = String::new();
    let mut number = String::new();
    let flush = |number: &mut String, out: &mut String| {
        if number.is_empty() {
            return;
        }
        match number.parse::<f64>() {
            Ok(v) if number.contains('.') || number.contains('e') => {
                let s = format!("{v:.10}");
                out.push_str(
                    if s.trim_start_matches('-')
                        .chars()
                        .all(|c| c == '0' || c == '.')
                    {
                        "0.0000000000"
                    } else {
                        &s
                    },
                );
            }
            _ => out.push_str(number),
        }
        number.clear();
    };
    for c in text.chars() {
        // Digits and dots inside a name (`wrist_1.z`) are the name's, not a number.
        let in_name = number.is_empty()
            && (out.chars().last()).is_some_and(|p| p.is_alphanumeric() || p == '_');
        if in_name && (c.is_ascii_digit() || c == '.') {
            out.push(c);
            continue;
        }
        let continues = c.is_ascii_digit()
            || c == '.'
            || ((c == 'e' || c == '-') && !number.is_empty())
            || (c == '-' && number.is_empty());
        if continues && (c != '-' || number.is_empty() || number.ends_with('e')) {
            number.push(c);
        } else {
            flush(&mut number, &mut out);
            out.push(c);
        }
    }
    flush(&mut number, &mut out);
    out
}

/// Every view of an example: all succeed, print nothing on stderr but golden warnings, and
/// match their goldens.
fn views(name: &str, file: &str) {
    let file = file.to_string();
    for (view, args) in [
        ("check", vec!["check", file.as_str()]),
        ("explain", vec!["explain", file.as_str()]),
        ("plan", vec!["plan", file.as_str()]),
        (
            "solve.json",
            vec!["solve", "--json", "--all", file.as_str()],
        ),
    ] {
        let (code, stdout, stderr) = gcs(&args);
        assert_eq!(code, 0, "{view} of {name} failed: {stderr}");
        // Only warnings (an under-constrained example's free motions), and golden too.
        let warnings = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join(format!("tests/goldens/{name}.{view}.stderr"));
        if stderr.is_empty() {
            assert!(
                !warnings.exists(),
                "{view} of {name} no longer warns: remove {warnings:?}"
            );
        } else {
            assert!(!stderr.contains("error"), "{view} of {name}: {stderr}");
            expect_file![warnings].assert_eq(&stderr);
        }
        let golden =
            Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/goldens/{name}.{view}"));
        let text = if view == "solve.json" {
            fixed_precision(&stdout)
        } else {
            stdout
        };
        expect_file![golden].assert_eq(&text);
    }
}

/// Every view of every example the analysis covers, one thread an example; every example is
/// checked, and the failures are reported together, each naming its example.
#[test]
fn every_example_matches_its_goldens_in_every_view() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let examples = discover::analysed(&root, discover::Folder::Examples);
    let failures: Vec<String> = std::thread::scope(|s| {
        let runs: Vec<_> = examples
            .iter()
            .map(|m| (m, s.spawn(move || views(&m.stem, &m.relative()))))
            .collect();
        runs.into_iter()
            .filter_map(|(m, run)| {
                run.join().err().map(|e| {
                    let why = e
                        .downcast_ref::<String>()
                        .cloned()
                        .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                        // expect-test prints its diff, naming the golden, and panics
                        // without a message.
                        .unwrap_or_else(|| "differs from a golden (the diff is above)".into());
                    format!("{}: {why}", m.relative())
                })
            })
            .collect()
    });
    assert!(
        failures.is_empty(),
        "{} of {} examples differ from their goldens:\n{}",
        failures.len(),
        examples.len(),
        failures.join("\n\n")
    );
}

/// A golden whose example is gone (or no longer analysed) is stale: remove it with its example.
/// Subfolders hold other tests' goldens (`draw/`, checked by `tests/draw.rs`).
#[test]
fn every_golden_belongs_to_an_example() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let examples = discover::analysed(&root, discover::Folder::Examples);
    let goldens = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/goldens");
    for entry in std::fs::read_dir(&goldens).expect("the goldens' folder") {
        let entry = entry.expect("a golden");
        if entry.file_type().expect("a file type").is_dir() {
            continue;
        }
        let name = entry.file_name();
        let name = name.to_string_lossy();
        let stem = name.split('.').next().unwrap_or_default();
        assert!(
            examples.iter().any(|m| m.stem == stem),
            "tests/goldens/{name} has no example examples/{stem}.gcs the analysis covers"
        );
    }
}

#[test]
fn solve_prunes_to_outputs() {
    // Two independent cranks; the output needs only the first.
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("two.gcs");
    std::fs::write(
        &file,
        "space 2d;\nparam a = 30 deg;\nfixed point A = (0, 0);\nfixed point B = (5, 0);\nfixed vector X = (1, 0);\n\
         body one { point o = (0, 0); point t = (1, 0); vector u = (1, 0); }\n\
         body two { point o = (5, 0); point t = (6, 0); vector u = (1, 0); }\n\
         coincident(one.o, A);\nangle(X, one.u) = a;\ncoincident(two.o, B);\nangle(X, two.u) = 2 * a;\noutput one.t;\n",
    )
    .expect("write");
    let path = file.to_str().expect("utf-8 path");
    let (code, pruned, _) = gcs(&["solve", "--json", path]);
    assert_eq!(code, 0);
    assert!(
        pruned.contains("\"one.t\"") && !pruned.contains("\"two.t\""),
        "{pruned}"
    );
    let (code, all, _) = gcs(&["solve", "--json", "--all", path]);
    assert_eq!(code, 0);
    assert!(
        all.contains("\"one.t\"") && all.contains("\"two.t\""),
        "{all}"
    );
}
