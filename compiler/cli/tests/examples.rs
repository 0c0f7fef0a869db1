//! Golden outputs of every example model, for every view: `check`, `explain`, `plan` and
//! `solve --json`. Regenerate with `UPDATE_EXPECT=1 cargo test -p gcs-cli --test examples`.

use expect_test::expect_file;
use std::path::Path;
use std::process::Command;

fn gcs(args: &[&str]) -> (i32, String, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = Command::new(env!("CARGO_BIN_EXE_gcs"))
        .current_dir(&root)
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("run gcs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
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

/// Every view of a 2d example: all succeed, print nothing on stderr, and match their goldens.
fn views(name: &str) {
    let file = format!("examples/{name}.gcs");
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
        assert_eq!(stderr, "", "{view} of {name} wrote to stderr");
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

#[test]
fn fourbar() {
    views("fourbar");
}

#[test]
fn circle() {
    views("circle");
}

#[test]
fn tenbar() {
    views("tenbar");
}

#[test]
fn slider_crank_2d() {
    views("slider_crank_2d");
}

#[test]
fn crank_rocker() {
    views("crank_rocker");
}

#[test]
fn sixbar() {
    views("sixbar");
}

#[test]
fn jansen_leg() {
    views("jansen_leg");
}

#[test]
fn sketch_profile() {
    views("sketch_profile");
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
