//! Values given on the command line are checked as the file checks its own: units, finiteness,
//! the sign of a size; and `gcs bench` refuses a sweep of fewer than two samples.

mod support;

use expect_test::{expect, Expect};

/// A point `B` on a fixed line at distance `d` from `A`, and a segment at angle `a`.
const MODEL: &str = "space 2d;
param d = 5;
param a = 30deg;
fixed point A = (0, 0);
fixed vector X = (1, 0);
fixed line L = (0, 0) -> (1, 0);
point B = (5, 0);
segment S = (0, 0) -> (4, 3);
coincident(S.start, A);
angle(X, S) = a;
length(S) = 5;
reach: distance(A, B) = d;
on(B, L);
";

/// Runs `gcs` with `args`, the model's path after the first argument; exit code, stdout and
/// stderr.
fn gcs(args: &[&str]) -> (i32, String, String) {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = dir.path().join("set.gcs");
    std::fs::write(&path, MODEL).expect("write model");
    let mut all = vec![args[0], "set.gcs"];
    all.extend(&args[1..]);
    support::gcs_in(dir.path(), &all)
}

fn refused(args: &[&str], code: i32, want: Expect) {
    let (got, stdout, stderr) = gcs(args);
    assert_eq!(got, code, "{args:?}: {stderr}");
    assert!(stdout.is_empty(), "{args:?}: {stdout}");
    want.assert_eq(&stderr);
}

#[test]
fn a_value_in_the_wrong_unit_is_refused() {
    refused(
        &["solve", "--set", "d=3deg"],
        2,
        expect![[r#"
            error: `--set d=3deg`: `3deg` is an angle, but `d` holds a length; give a length, without `deg` or `rad`
        "#]],
    );
    refused(
        &["solve", "--set", "a=d"],
        2,
        expect![[r#"
            error: `--set a=d`: `d` is a length, but `a` holds an angle; give an angle, in radians or with `deg`
        "#]],
    );
}

#[test]
fn plain_numbers_fit_lengths_and_angles() {
    for set in ["d=3", "d=d*2", "a=0.5", "a=45deg", "a=a/2", "d=sin(30deg)"] {
        let (code, _, stderr) = gcs(&["solve", "--set", set]);
        assert_eq!(code, 0, "{set}: {stderr}");
    }
}

#[test]
fn a_value_that_is_not_finite_says_so() {
    for word in ["NaN", "nan", "inf", "-inf", "Infinity"] {
        let (code, _, stderr) = gcs(&["solve", "--set", &format!("d={word}")]);
        assert_eq!(code, 2, "{word}");
        assert!(
            stderr.contains("is not a finite number"),
            "{word}: {stderr}"
        );
        assert!(!stderr.contains("unknown param"), "{word}: {stderr}");
    }
    refused(
        &["solve", "--set", "d=1/0"],
        2,
        expect![[r#"
            error: `--set d=1/0`: `1/0` is inf, not a finite number
        "#]],
    );
}

#[test]
fn a_negative_size_says_it_is_negative() {
    refused(
        &["solve", "--set", "d=-5"],
        1,
        expect![[r#"
            error: parameter `d` is invalid: its value, -5, is negative, and `distance(A, B) = d` takes it as a distance, a length or a radius, which is zero or more
        "#]],
    );
    // Zero is a size: B at A.
    let (code, stdout, stderr) = gcs(&["solve", "--set", "d=-0.0", "--json"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stdout.contains(r#""B": [0.0, 0.0]"#) || stdout.contains(r#""B":[0.0,0.0]"#),
        "{stdout}"
    );
}

#[test]
fn a_huge_value_is_written_short() {
    let (code, _, stderr) = gcs(&["solve", "--set", "d=-1e100"]);
    assert_eq!(code, 1);
    assert!(
        stderr.contains("its value, -1e100, is negative"),
        "{stderr}"
    );
}

#[test]
fn a_sweep_has_two_samples_or_more() {
    for n in ["0", "1"] {
        let (code, stdout, stderr) = gcs(&["bench", "--samples", n]);
        assert_eq!(code, 2, "{n}: {stdout}");
        assert!(
            stderr.contains(&format!(
                "a sweep has two samples or more (its two ends), not {n}"
            )),
            "{stderr}"
        );
    }
}

#[test]
fn a_value_past_the_range_says_what_would_overflow() {
    refused(
        &["solve", "--set", "d=1e308"],
        1,
        expect![[r#"
            error: parameter `d` is invalid: 1e308 is past 1e150, the largest magnitude a solve takes (squares of lengths past it overflow)
        "#]],
    );
    // The edge of the range solves.
    let (code, stdout, stderr) = gcs(&["solve", "--set", "d=1e150", "--json"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("1e150"), "{stdout}");
}

/// `--default` sets a free motion's value (units as `--set`), is refused for a name the plan
/// has not and for a length where an angle is meant; `--all-solutions --json` lists each
/// real assembly once.
#[test]
fn defaults_and_all_solutions_on_the_command_line() {
    let run = |args: &[&str]| support::gcs(args);
    let model = "examples/fourbar_free.gcs";
    let (code, stdout, stderr) = run(&["solve", "--json", "--default", "crank_angle=90deg", model]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stdout.contains("\"crank_angle\": 1.5707963267948966"),
        "{stdout}"
    );
    assert!(stdout.contains("\"crank.b\": [9.18"), "{stdout}");
    let (code, _, stderr) = run(&["solve", "--default", "crank=1", model]);
    assert_eq!(code, 2);
    assert!(
        stderr.contains("no default `crank`; the defaults are: crank_angle"),
        "{stderr}"
    );
    let (code, _, stderr) = run(&["solve", "--default", "crank_angle=2 * crank_len", model]);
    assert_eq!(code, 2, "{stderr}");
    let (code, stdout, stderr) = run(&["solve", "--all-solutions", "--json", "examples/rpr3.gcs"]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(stdout.matches("\"max_residual\"").count(), 6, "{stdout}");
    assert!(
        stdout.starts_with("{\"complete\": true,"),
        "one angle: exhaustive"
    );
}

/// A default given a negative size is blamed on the default, with what it fixes; not on the
/// constraint whose step reads it.
#[test]
fn a_negative_default_is_blamed_on_the_default() {
    let dir = tempfile::tempdir().expect("tempdir");
    let model = "space 2d;
fixed point O = (0, 0);
fixed vector X = (1, 0);
fixed vector Y = (0, 1);
segment bottom = (0, 0) -> (4, 0);
segment left = (0, 3) -> (0, 0);
coincident(bottom.start, O);
coincident(left.end, bottom.start);
parallel(bottom, X);
parallel(left, Y);
length(bottom) = 4;
";
    std::fs::write(dir.path().join("free.gcs"), model).expect("write model");
    let (code, stdout, stderr) = support::gcs_in(
        dir.path(),
        &["solve", "free.gcs", "--default", "left_length=-5"],
    );
    assert_eq!(code, 1, "{stdout}{stderr}");
    let last = stderr.lines().last().unwrap_or_default();
    expect![[r#"error: default `left_length` is invalid: its value, -5, is negative, and it fixes the length of left, which is zero or more"#]]
        .assert_eq(last);
}
