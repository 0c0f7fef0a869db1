//! Large models through the command line (issue 17, item 7): `gcs check` of 20,000 params and
//! `gcs solve --json` of 20,000 points give the right answers, and repeated warnings are
//! counted in one line instead of printed each. Their speed is measured by the scaling bench
//! (`examples/benches/scaling.rs`), never here.

mod support;

use expect_test::expect;
use gcs_bench::families;

/// Runs `gcs` with `args` on a model written to a temporary file; returns exit code, stdout and
/// stderr. The file is called `model.gcs`, and run from its directory so that diagnostics name it
/// the same on every machine.
fn gcs(args: &[&str], model: &str) -> (i32, String, String) {
    let dir = tempfile::tempdir().expect("temporary directory");
    std::fs::write(dir.path().join("model.gcs"), model).expect("write the model");
    let mut all = args.to_vec();
    all.push("model.gcs");
    support::gcs_in(dir.path(), &all)
}

#[test]
fn repeated_warnings_show_the_first_ten_and_count_the_rest() {
    // 24 params, 12 of them unused: ten warnings in full, then one line for the other two.
    let (code, _, stderr) = gcs(&["check"], &families::params(24));
    assert_eq!(code, 0, "{stderr}");
    let warnings = stderr.matches("warning: param `").count();
    assert_eq!(warnings, 10, "{stderr}");
    let last = stderr.rfind("warning: param `").unwrap_or(0);
    expect![[r#"
        warning: param `p19` is never used
           ┌─ model.gcs:42:7
           │
        42 │ param p19 = 3;
           │       ^^^ unused
           │
           = it still becomes a field of the solver's params

        warning: 2 more warnings like "param `…` is never used" not shown

    "#]]
    .assert_eq(&stderr[last..]);
}

#[test]
fn twenty_thousand_params_check_with_a_bounded_report_of_their_warnings() {
    let (code, stdout, stderr) = gcs(&["check"], &families::params(20_000));
    assert_eq!(code, 0, "{stderr}");
    // 10,000 unused params: ten warnings of seven lines and a blank, and one line for the rest.
    assert_eq!(stderr.matches("warning: param `").count(), 10, "{stderr}");
    assert!(stderr.lines().count() < 100, "{stderr}");
    assert!(
        stderr.contains("warning: 9,990 more warnings like \"param `…` is never used\" not shown"),
        "{stderr}"
    );
    // The first ten unused params, in source order: p2, p3, p6, p7, ...
    let named: Vec<&str> = stderr
        .lines()
        .filter_map(|l| l.strip_prefix("warning: param `"))
        .filter_map(|l| l.split('`').next())
        .collect();
    assert_eq!(
        named,
        ["p2", "p3", "p6", "p7", "p10", "p11", "p14", "p15", "p18", "p19"]
    );
    let first = stdout.lines().next().unwrap_or_default();
    assert_eq!(
        first,
        "model.gcs: space 2d, 20000 params, 5002 geoms, 10000 constraints"
    );
    assert!(
        stdout.contains("\nnominal DOF: 10000 - 10000 = 0\n"),
        "{stdout}"
    );
    assert!(
        stdout.contains("\nanalysis: well-constrained\n"),
        "{stdout}"
    );
    assert_eq!(stdout.matches("\n  branch ").count(), 5000);
    assert!(stdout.contains(
        "\n  branch distance_q4999_q5000: 2 roots, sketch takes 1: the second crossing, along the line\n"
    ));
}

#[test]
fn errors_are_never_counted_away() {
    // Thirty params defined by a division by zero: thirty errors of one kind, every one shown.
    let mut model = String::from("space 2d;\n");
    for k in 0..30 {
        model.push_str(&format!("param p{k} = 1 / 0;\n"));
    }
    let (code, _, stderr) = gcs(&["check"], &model);
    assert_eq!(code, 1, "{stderr}");
    assert_eq!(
        stderr.matches("error: division by zero").count(),
        30,
        "{stderr}"
    );
    assert!(!stderr.contains("not shown"), "{stderr}");
    assert!(stderr.ends_with("error: could not load `model.gcs` due to 30 previous errors\n"));
}

/// The `[x, y]` of a point line of `gcs solve --json`: `    "q12": [12.0, 0.0],`.
fn point_line(line: &str) -> Option<(&str, f64, f64)> {
    let (name, rest) = line.trim().strip_prefix('"')?.split_once("\": [")?;
    let (x, y) = rest
        .trim_end_matches(',')
        .strip_suffix(']')?
        .split_once(", ")?;
    Some((name, x.parse().ok()?, y.parse().ok()?))
}

#[test]
fn twenty_thousand_points_solve_each_in_its_place() {
    let n = 20_000;
    let (code, stdout, stderr) = gcs(&["solve", "--json"], &families::points(n));
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(stderr, "");
    // The entries of a section of the JSON object, a line each.
    let section = |name: &str| -> Vec<&str> {
        let head = format!("  \"{name}\": {{");
        (stdout.lines())
            .skip_while(|l| *l != head)
            .skip(1)
            .take_while(|l| l.starts_with("    "))
            .collect()
    };
    let points: Vec<(&str, f64, f64)> = section("points")
        .into_iter()
        .map(|l| point_line(l).unwrap_or_else(|| panic!("not a point: {l}")))
        .collect();
    // The line's base point, then q0 to q19999, each 1 further along the x axis.
    assert_eq!(points.len(), n + 1);
    assert_eq!(points[0], ("axis.point", 0.0, 0.0));
    for (k, &(name, x, y)) in points[1..].iter().enumerate() {
        assert_eq!(name, format!("q{k}"));
        assert!((x - k as f64).abs() <= 1e-9 * n as f64, "{name}: {x}");
        assert!(y.abs() <= 1e-12, "{name}: {y}");
    }
    // A branch a point (which crossing of its circle with the line), each the sketch's.
    let branches = section("branches");
    assert_eq!(branches.len(), n - 1);
    assert!(branches
        .iter()
        .all(|b| b.ends_with(": 1,") || b.ends_with(": 1")));
    let residual: f64 = stdout
        .lines()
        .find_map(|l| l.trim().strip_prefix("\"max_residual\": "))
        .and_then(|r| r.parse().ok())
        .expect("a max residual");
    assert!(residual <= 1e-9, "{residual}");
}

/// A reader that stops early (`gcs plan FILE | head`) ends the output quietly: the exit status
/// of a broken pipe, and no panic on standard error.
#[test]
fn a_closed_pipe_stops_the_output_without_a_panic() {
    use std::io::Read as _;
    let dir = tempfile::tempdir().expect("temporary directory");
    std::fs::write(dir.path().join("model.gcs"), families::four_bar_chain(400)).expect("write");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_gcs"))
        .current_dir(dir.path())
        .args(["plan", "model.gcs"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run gcs");
    let mut stdout = child.stdout.take().expect("its output");
    let mut first = [0u8; 16];
    stdout
        .read_exact(&mut first)
        .expect("the plan's first bytes");
    drop(stdout);
    let out = child.wait_with_output().expect("gcs ends");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(141), "{stderr}");
}
