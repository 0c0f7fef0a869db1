//! `gcs solve` of a model whose outputs name joint values (`J.angle`, `J.travel`): they are
//! printed as scalars, in text and under `"scalars"` in `--json`, for every assembly of
//! `--all-solutions`; a joint value the model cannot have is an error with its span.

mod support;

use expect_test::expect;
use support::gcs_in;

/// Two slider-cranks on one crank: the crank's angle by its revolute and by its drive, a point
/// slider's travel (`in_line`) and a slider body's on a rail pointing the other way.
const SLIDERS: &str = "space 2d;
param phi = 30 deg;
param r = 1.5;
param l = 4;
fixed body ground {
    marker o = (0, 0) x (1, 0);
    marker rail = (0, 0) x (1, 0);
    marker back = (0, -1) x (-1, 0);
}
body crank { marker o = (0, 0) x (1, 0); marker tip = (r, 0) x (1, 0); }
point P = (5.2, 0);
body slider at (-3, -1) { marker s = (0, 0) x (-1, 0); }
pivot: revolute(crank.o, ground.o);
drive: offset_x(ground.o, crank.o) = phi;
in_line(P, ground.rail);
distance(crank.tip, P) = l;
slide: prismatic(slider.s, ground.back);
distance(crank.tip, slider.s) = l;
output pivot.angle, drive.angle, in_line_P_ground_rail.travel, slide.travel;
";

/// Runs `gcs ARGS MODEL` on `text` written to a temporary `sliders.gcs`.
fn solve(text: &str, args: &[&str]) -> (i32, String, String) {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("sliders.gcs"), text).expect("write the model");
    let all: Vec<&str> = args.iter().copied().chain(["sliders.gcs"]).collect();
    gcs_in(dir.path(), &all)
}

/// The `"scalars"` object of a JSON solution, as printed.
fn scalars(json: &str) -> &str {
    let start = json.find("\"scalars\"").expect("a scalars section");
    let end = start + json[start..].find('}').expect("its end");
    &json[start..=end]
}

#[test]
fn solve_json_reports_joint_values_among_the_scalars() {
    let (code, out, err) = solve(SLIDERS, &["solve", "--json", "--set", "phi=45deg"]);
    assert_eq!(code, 0, "{err}");
    expect![[r#"
        "scalars": {
            "pivot.angle": -0.7853981633974483,
            "drive.angle": 0.7853981633974483,
            "in_line_P_ground_rail.travel": 4.917472326915199,
            "slide.travel": 2.3677038194615343
          }"#]]
    .assert_eq(scalars(&out));
    // phi = 45 deg: the crank's tip at r (cos, sin) phi; the point slider r cos phi +
    // sqrt(l^2 - (r sin phi)^2) along the rail; the slider body on the rail one below, at
    // r cos phi - sqrt(l^2 - (r sin phi + 1)^2), its travel measured along -x.
    let (c, s) = (1.5 * 0.5f64.sqrt(), 1.5 * 0.5f64.sqrt());
    let point = c + (16.0 - s * s).sqrt();
    let body = -(c - (16.0 - (s + 1.0) * (s + 1.0)).sqrt());
    for (name, want) in [
        ("in_line_P_ground_rail.travel", point),
        ("slide.travel", body),
    ] {
        let line = (out.lines())
            .find(|l| l.contains(&format!("\"{name}\"")))
            .expect("reported");
        let got: f64 = (line.rsplit(": ").next().expect("a value"))
            .trim_end_matches(',')
            .parse()
            .expect("a number");
        assert!((got - want).abs() < 1e-12, "{name}: {got} vs {want}");
    }
}

#[test]
fn solve_prints_joint_values_and_lists_them_for_every_assembly() {
    let (code, out, err) = solve(SLIDERS, &["solve"]);
    assert_eq!(code, 0, "{err}");
    let joints: Vec<&str> = out.lines().filter(|l| l.starts_with("scalar")).collect();
    expect![[r#"
        [
            "scalar pivot.angle = -0.523598775598",
            "scalar drive.angle = 0.523598775598",
            "scalar in_line_P_ground_rail.travel = 5.228096517052",
            "scalar slide.travel = 2.297835536808",
        ]
    "#]]
    .assert_debug_eq(&joints);
    // Four assemblies (each slider on either side of the crank's tip), each with its values.
    let (code, out, err) = solve(SLIDERS, &["solve", "--all-solutions", "--json"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out.matches("\"scalars\"").count(), 4, "{out}");
    assert_eq!(out.matches("\"slide.travel\"").count(), 4, "{out}");
}

#[test]
fn a_joint_value_the_constraint_has_not_is_an_error_at_its_span() {
    let text = SLIDERS.replace("output pivot.angle,", "output slide.angle,");
    let (code, out, err) = solve(&text, &["solve", "--json"]);
    assert_ne!(code, 0);
    assert!(out.is_empty(), "{out}");
    expect![[r#"
        error: `slide` is a `prismatic` constraint, which has no angle
           ┌─ sliders.gcs:19:8
           │
        17 │ slide: prismatic(slider.s, ground.back);
           │ ---------------------------------------- `slide` is this `prismatic` constraint
        18 │ distance(crank.tip, slider.s) = l;
        19 │ output slide.angle, drive.angle, in_line_P_ground_rail.travel, slide.travel;
           │        ^^^^^^^^^^^ `.angle` is the value of a `revolute`, `cylindrical` or `offset_x` joint
           │
           = its joint has `slide.travel`

        error: could not load `sliders.gcs` due to 1 previous error
    "#]].assert_eq(&err);
}
