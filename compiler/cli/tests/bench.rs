//! `gcs bench`: the compiled plan against the Newton baseline on a sweep. Tests assert
//! residuals, branch flips and counts; never times (those belong in docs/BENCHMARKS.md).

use std::path::Path;
use std::process::Command;

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// Runs `gcs bench --json --interpreted` (the interpreter runs the same plan as the generated
/// solver; building one here would cost a cargo build per test).
fn bench(file: &Path, samples: usize) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_gcs"))
        .arg("bench")
        .arg(file)
        .args(["--samples", &samples.to_string(), "--json", "--interpreted"])
        .env("GCS_BENCH_BUDGET_NS", "1")
        .output()
        .expect("gcs runs");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{}\n{stdout}",
        String::from_utf8_lossy(&out.stderr)
    );
    stdout
}

/// The number after `"key": ` in the object after `"within": {` (or at the top level).
fn number(json: &str, within: Option<&str>, key: &str) -> f64 {
    let from = within.map_or(0, |w| {
        json.find(&format!("\"{w}\": {{"))
            .unwrap_or_else(|| panic!("no {w} in {json}"))
    });
    let rest = &json[from..];
    let at = rest
        .find(&format!("\"{key}\": "))
        .unwrap_or_else(|| panic!("no {key} in {json}"))
        + key.len()
        + 4;
    let end = rest[at..]
        .find([',', '}', ']'])
        .map_or(rest.len(), |e| at + e);
    rest[at..end].trim().parse().unwrap_or(f64::NAN)
}

#[test]
fn fourbar_bench_reports_exact_answers_and_no_flips() {
    let json = bench(&examples().join("fourbar.gcs"), 36);
    assert_eq!(number(&json, None, "samples"), 36.0);
    assert_eq!(number(&json, None, "branch_flips"), 0.0, "{json}");
    let compiled = number(&json, Some("compiled"), "max_residual");
    assert!(compiled <= 1e-12, "{json}");
    assert_eq!(number(&json, Some("compiled"), "failures"), 0.0);
    // The baseline solves the same sweep, warm, on the same assembly, to its tolerance.
    assert!(
        number(&json, Some("baseline"), "max_residual") <= 1e-10,
        "{json}"
    );
    assert_eq!(number(&json, Some("baseline"), "failures"), 0.0, "{json}");
    assert_eq!(
        number(&json, Some("baseline"), "branch_flips"),
        0.0,
        "{json}"
    );
    assert_eq!(number(&json, Some("baseline"), "unknowns"), 9.0, "{json}");
    assert!(number(&json, None, "ratio").is_finite());
    // Newton reaches 1e-12 from the sketch, at some time.
    assert!(number(&json, Some("cold"), "1e-12") > 0.0, "{json}");
}

#[test]
fn chain_bench_has_no_flips() {
    let json = bench(&examples().join("families/fourbar_chain_16.gcs"), 12);
    assert_eq!(number(&json, None, "branch_flips"), 0.0, "{json}");
    assert!(
        number(&json, Some("compiled"), "max_residual") <= 1e-12,
        "{json}"
    );
    assert!(
        number(&json, Some("baseline"), "max_residual") <= 1e-10,
        "{json}"
    );
}

#[test]
fn bench_writes_a_plot_and_text() {
    let dir = tempfile::tempdir().expect("tempdir");
    let svg = dir.path().join("fourbar.svg");
    let out = Command::new(env!("CARGO_BIN_EXE_gcs"))
        .arg("bench")
        .arg(examples().join("fourbar.gcs"))
        .args(["--samples", "8", "--interpreted", "--plot"])
        .arg(&svg)
        .env("GCS_BENCH_BUDGET_NS", "1")
        .output()
        .expect("gcs runs");
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("ratio (baseline median / compiled median)"),
        "{text}"
    );
    assert!(text.contains("1e-12"), "{text}");
    let plot = std::fs::read_to_string(&svg).expect("plot written");
    assert!(
        plot.starts_with("<svg") && plot.contains("<polyline"),
        "{plot}"
    );
}

/// The generated solver's warm sweep of the Stewart platform: the assembly it follows from
/// the sketch ends at a fold between l1 = 3.119 and 3.125 (no assembly near the last answer:
/// `NoAssemblyNear`, measured in `compiler/bench/tests/stewart_fold.rs`). There the sweep goes
/// on with the assembly nearest its last answer, of those `solve_all` finds, and says so: no
/// sample fails, none flips, and the restarts are counted. This builds the generated solver
/// (one cargo build, shared with `gcs bench`'s other models).
#[test]
fn a_warm_sweep_goes_on_past_a_fold_and_says_so() {
    let out = Command::new(env!("CARGO_BIN_EXE_gcs"))
        .arg("bench")
        .arg(examples().join("stewart.gcs"))
        .args(["--samples", "100", "--json"])
        .env("GCS_BENCH_BUDGET_NS", "1")
        .output()
        .expect("gcs runs");
    let json = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(json.contains("\"kind\": \"generated\""), "{json}");
    assert_eq!(number(&json, Some("compiled"), "failures"), 0.0, "{json}");
    assert_eq!(number(&json, None, "branch_flips"), 0.0, "{json}");
    let restarts = number(&json, Some("compiled"), "restarts");
    assert!((1.0..=3.0).contains(&restarts), "{json}");
}
