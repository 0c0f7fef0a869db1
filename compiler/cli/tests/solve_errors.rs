//! `gcs solve` on an impossible assembly exits non-zero, and its stderr names the constraint
//! (`elbow`) and the gap by which the loop misses, equal to the true gap computed here; params
//! that break two redundant constraints get both named, each with its size.

mod support;

use std::path::Path;

/// The four-bar of examples/fourbar.gcs with its coupler's and rocker's `c` members replaced.
fn fourbar(coupler_c: &str, rocker_c: &str) -> String {
    format!(
        "space 2d;
param theta = 30 deg;
param crank_len = 1.5;
fixed point A = (0, 0);
fixed point D = (4, 0);
fixed vector X = (1, 0);
body crank   at (0, 0)   {{ point a = (0, 0); point b = (crank_len, 0); vector u = (1, 0); }}
body coupler at (1.5, 0) {{ point b = (0, 0); point c = {coupler_c}; }}
body rocker  at (4, 0)   {{ point d = (0, 0); point c = {rocker_c}; }}
coincident(crank.a, A);
drive: angle(X, crank.u) = theta;
coincident(crank.b, coupler.b);
elbow: coincident(coupler.c, rocker.c);
coincident(rocker.d, D);
output coupler.c;
"
    )
}

/// The gap between the circle about crank.b (crank of length `crank` at `theta_deg`) with
/// radius `r1` and the circle about D = (4, 0) with radius `r2`.
fn gap(crank: f64, theta_deg: f64, r1: f64, r2: f64) -> f64 {
    let t = theta_deg.to_radians();
    let d = (4.0 - crank * t.cos()).hypot(crank * t.sin());
    if d > r1 + r2 {
        d - (r1 + r2)
    } else {
        (r1 - r2).abs() - d
    }
}

/// Runs `gcs solve` with `args` after the file and returns exit code, stdout and stderr.
fn gcs_solve(path: &Path, args: &[&str]) -> (i32, String, String) {
    let mut all = vec![std::ffi::OsStr::new("solve"), path.as_os_str()];
    all.extend(args.iter().map(std::ffi::OsStr::new));
    support::gcs(&all)
}

/// Every number that follows "miss by " in `text`.
fn gaps_in(text: &str) -> Vec<f64> {
    text.match_indices("miss by ")
        .filter_map(|(i, m)| {
            let rest = &text[i + m.len()..];
            let end = rest
                .find(|c: char| !(c.is_ascii_digit() || matches!(c, '.' | 'e' | 'E' | '-' | '+')))
                .unwrap_or(rest.len());
            rest[..end].parse::<f64>().ok()
        })
        .collect()
}

fn assert_fails_with_gap(text: &str, args: &[&str], want: f64) {
    assert!(want > 0.0, "the test model must not close (gap {want})");
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("broken.gcs");
    std::fs::write(&path, text).expect("write model");
    for json in [false, true] {
        let mut args = args.to_vec();
        if json {
            args.push("--json");
        }
        let (code, stdout, stderr) = gcs_solve(&path, &args);
        assert_ne!(
            code, 0,
            "{args:?}: exit 0\nstdout: {stdout}\nstderr: {stderr}"
        );
        assert!(
            !stdout.contains("\"points\"") && !stdout.contains("max residual"),
            "{args:?}: a solution was printed: {stdout}"
        );
        assert!(stderr.contains("`elbow`"), "{args:?}: stderr: {stderr}");
        let gaps = gaps_in(&stderr);
        assert!(
            gaps.iter().any(|g| (g - want).abs() <= 1e-12 * 5.0),
            "{args:?}: no gap {want} in stderr (found {gaps:?}): {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn a_coupler_too_short_to_reach_fails_naming_elbow_and_the_gap() {
    // Coupler 0.5 and rocker 1 cannot span the 2.80 from crank.b to D.
    assert_fails_with_gap(
        &fourbar("(0.5, 0)", "(0, 1)"),
        &[],
        gap(1.5, 30.0, 0.5, 1.0),
    );
}

#[test]
fn a_coupler_too_long_to_fold_fails_naming_elbow_and_the_gap() {
    assert_fails_with_gap(&fourbar("(8, 0)", "(0, 3)"), &[], gap(1.5, 30.0, 8.0, 3.0));
}

#[test]
fn the_example_four_bar_in_a_dead_zone_fails_naming_elbow_and_the_gap() {
    // With a crank of 3.5 at 0 degrees, crank.b is 0.5 from D, but coupler 4 and rocker 3 meet
    // only at distances of at least 1.
    let text = fourbar("(4, 0)", "(0, 3)");
    assert_fails_with_gap(
        &text,
        &["--set", "crank_len=3.5", "--set", "theta=0"],
        gap(3.5, 0.0, 4.0, 3.0),
    );
    // And at its defaults it solves.
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("ok.gcs");
    std::fs::write(&path, &text).expect("write model");
    let (code, stdout, stderr) = gcs_solve(&path, &[]);
    assert_eq!(code, 0, "stderr: {stderr}");
    assert!(stdout.contains("coupler.c"), "{stdout}");
}

#[test]
fn params_that_break_two_redundant_constraints_name_both_with_their_sizes() {
    // At its defaults `x` and `g` hold (as checks); moved, each is off by its own amount,
    // and a failed check does not hide the other.
    let text = "space 2d;
param xv = 2.6535945694153691;
param gv = 11.774591973880774;
fixed point A = (0, 0);
fixed point B = (3, 0);
point C = (1, 2);
fixed point D = (10, 0);
fixed line L = (0, -1) -> (1, -1);
point E = (11, 2);
b: distance(A, C) = 2;
c: distance(B, C) = 2.5;
x: distance(C, L) = xv;
e: distance(D, E) = 2;
f: on(E, L);
g: distance(E, A) = gv;
";
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("two.gcs");
    std::fs::write(&path, text).expect("write model");
    let (code, stdout, stderr) = gcs_solve(&path, &[]);
    assert_eq!(code, 0, "stderr: {stderr}");
    assert!(stdout.contains("point  E"), "{stdout}");
    let (code, stdout, stderr) = gcs_solve(&path, &["--set", "xv=3", "--set", "gv=11.5"]);
    assert_eq!(code, 1, "stdout: {stdout}");
    let cy = (4.0f64 - (6.75f64 / 6.0).powi(2)).sqrt();
    let lines: Vec<&str> = stderr.lines().collect();
    assert_eq!(lines.len(), 2, "{stderr}");
    for (line, (name, off)) in lines
        .iter()
        .zip([("g", 11.774591973880774 - 11.5), ("x", 3.0 - (cy + 1.0))])
    {
        assert!(
            line.starts_with(&format!("error: constraint `{name}` ")),
            "{stderr}"
        );
        let m: f64 = (line.rsplit(' ').next())
            .and_then(|m| m.parse().ok())
            .unwrap_or(f64::NAN);
        assert!((m - off).abs() < 1e-9, "{name}: {m}, not {off}: {stderr}");
    }
}

/// `--all-solutions` where no assembly exists (the 3R arm's target beyond its reach) is an
/// error naming why, exit 1, and its JSON says the empty list is complete.
#[test]
fn all_solutions_with_none_is_an_error_naming_why() {
    let model = "examples/arm_3r.gcs";
    let (code, stdout, stderr) =
        support::gcs(&["solve", "--all-solutions", "--set", "tx=3", model]);
    assert_eq!(code, 1, "{stdout}");
    assert!(stderr.contains("error: no real assembly\n"), "{stderr}");
    assert!(
        stderr.contains("`revolute_forearm_elbow_upper_arm_elbow`")
            && stderr.contains("the loci miss by 2.00166"),
        "{stderr}"
    );
    let (code, stdout, _) =
        support::gcs(&["solve", "--all-solutions", "--json", "--set", "tx=3", model]);
    assert_eq!(code, 1);
    assert_eq!(stdout.trim(), "{\"complete\": true, \"solutions\": []}");
}
