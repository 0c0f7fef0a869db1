//! The sketch's assembly is a promise, or gcs says it broke it, on the command line: the folded
//! strip (`compiler/tests/models/folded_strip.gcs`, a strip of unit triangles sketched straight
//! whose `closing` needs it folded) solves on another branch with a warning naming it (the
//! sketch's index, the one used, its meaning, how far the points it places lie from their
//! sketch), in `gcs check` and `gcs solve`, with `"branches_changed"` in the JSON; `--deny
//! sketch-branch` makes that an error (exit 1); a branch given by `--branch` is never changed;
//! a model solvable on the sketch's branches says nothing and lists none. The library's side,
//! with the verifier, is `compiler/tests/sketch_branches.rs`.

mod support;

use expect_test::expect;
use serde_json::Value;
use support::gcs;

const FOLDED: &str = "compiler/tests/models/folded_strip.gcs";

/// The folded strip's branches as the sketch has them (`gcs check` lists them): the strip
/// runs straight; the sketch does not reach `distance_p5_p7`, whose default is 0.
const SKETCH: &[&str] = &[
    "distance_p1_p2=1",
    "distance_p2_p3=0",
    "distance_p3_p4=1",
    "distance_p4_p5=0",
    "distance_p5_p6=1",
    "distance_p5_p7=0",
];

/// `gcs solve --json` of the folded strip with `args`: exit code, JSON and stderr.
fn solve_json(args: &[&str]) -> (i32, Value, String) {
    let mut all = vec!["solve", "--json", FOLDED];
    all.extend(args);
    let (code, stdout, stderr) = gcs(&all);
    let json = serde_json::from_str(&stdout).unwrap_or(Value::Null);
    (code, json, stderr)
}

/// Every constraint of the folded strip (each a unit distance between two points) on the
/// JSON's points, measured here.
fn assert_unit_distances(json: &Value) {
    let point = |n: &str| -> (f64, f64) {
        let p = &json["points"][n];
        (p[0].as_f64().expect("x"), p[1].as_f64().expect("y"))
    };
    let text = std::fs::read_to_string(support::root().join(FOLDED)).expect("the model");
    let mut n = 0;
    for line in text.lines().filter(|l| l.contains("distance(")) {
        let args = line.split_once("distance(").expect("a distance").1;
        let (a, rest) = args.split_once(", ").expect("two points");
        let b = rest.split_once(')').expect("closed").0;
        let (p, q) = (point(a), point(b));
        let d = (p.0 - q.0).hypot(p.1 - q.1);
        assert!((d - 1.0).abs() <= 1e-12, "{line}: {d}");
        n += 1;
    }
    assert_eq!(n, 14);
}

#[test]
fn solve_warns_naming_the_changed_branch_and_lists_it_in_the_json() {
    let (code, json, stderr) = solve_json(&[]);
    assert_eq!(code, 0, "{stderr}");
    assert_unit_distances(&json);
    assert!(json["max_residual"].as_f64().expect("a residual") <= 1e-12);
    expect![[r#"
        [
          {
            "meaning": "p5 to the right of the line from p3 to p4",
            "name": "distance_p4_p5",
            "sketch": 0,
            "used": 1
          }
        ]"#]]
    .assert_eq(&serde_json::to_string_pretty(&json["branches_changed"]).expect("JSON"));
    // The index used is the one `branches` lists.
    assert_eq!(json["branches"]["distance_p4_p5"], 1);
    expect![[r#"
        warning: the constraints cannot be met on the sketch's branches: 1 branch changed
           ┌─ compiler/tests/models/folded_strip.gcs:23:1
           │
        23 │ distance(p4, p5) = 1;
           │ ^^^^^^^^^^^^^^^^^^^^^ `distance_p4_p5` = 1, not the sketch's 0: p5 to the right of the line from p3 to p4; p7 lies 3 from its sketch
           │
           = on those branches, constraint `distance_p5_p7` (distance(p5, p7) = 1) cannot be met: no intersection, the loci miss by 0.6457513110645907
           = solved on the branches nearest the sketch; the points the changed branches place lie from their sketch: p7 3, p5 1.73205, p6 1.73205
           = choose the branches with `--branch NAME=INDEX` (`gcs explain` says what each index means), or move the sketch to the assembly wanted; `--deny sketch-branch` makes this an error

    "#]]
    .assert_eq(&stderr);
    // The text says the same once on stderr, and solves.
    let (code, stdout, text_stderr) = gcs(&["solve", FOLDED]);
    assert_eq!(code, 0);
    assert_eq!(text_stderr, stderr);
    assert!(stdout.contains("branch distance_p4_p5 = 1"), "{stdout}");
}

#[test]
fn deny_sketch_branch_makes_it_an_error() {
    let (code, stdout, stderr) = gcs(&["solve", "--deny", "sketch-branch", FOLDED]);
    assert_eq!(code, 1, "{stderr}");
    assert_eq!(stdout, "", "no solution is printed");
    assert!(stderr.contains("warning: the constraints cannot be met on the sketch's branches"));
    assert!(stderr.ends_with(
        "error: `compiler/tests/models/folded_strip.gcs` cannot be solved on the sketch's branches, and `--deny sketch-branch` makes that an error\n"
    ), "{stderr}");
    let (code, _, stderr) = gcs(&["check", "--deny", "sketch-branch", FOLDED]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("`--deny sketch-branch` makes that an error"),
        "{stderr}"
    );
    // Only the warnings a command has can be denied.
    let (code, _, stderr) = gcs(&["solve", "--deny", "under-constrained", FOLDED]);
    assert_eq!(code, 2);
    expect![[r#"
        error: `--deny under-constrained`: the warnings that can be denied are: sketch-branch
    "#]]
    .assert_eq(&stderr);
    let (code, _, stderr) = gcs(&["check", "--deny", "flips", FOLDED]);
    assert_eq!(code, 2);
    expect![[r#"
        error: `--deny flips`: the warnings that can be denied are: under-constrained, sketch-branch
    "#]]
    .assert_eq(&stderr);
}

#[test]
fn check_warns_and_says_which_branch_the_sketch_does_not_reach() {
    let (code, stdout, stderr) = gcs(&["check", FOLDED]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.starts_with(
            "warning: the constraints cannot be met on the sketch's branches: 1 branch changed"
        ),
        "{stderr}"
    );
    assert!(stderr.contains("`distance_p4_p5` = 1, not the sketch's 0: p5 to the right of the line from p3 to p4; p7 lies 3 from its sketch"), "{stderr}");
    // The plan run on the sketch cannot place p7: that branch's default is not the sketch's.
    let branches: Vec<&str> = (stdout.lines())
        .filter(|l| l.starts_with("  branch "))
        .map(str::trim)
        .collect();
    expect![[r#"
        branch distance_p1_p2: 2 roots, sketch takes 1: p2 to the right of the line from p0 to p1
        branch distance_p2_p3: 2 roots, sketch takes 0: p3 to the left of the line from p1 to p2
        branch distance_p3_p4: 2 roots, sketch takes 1: p4 to the right of the line from p2 to p3
        branch distance_p4_p5: 2 roots, sketch takes 0: p5 to the left of the line from p3 to p4
        branch distance_p5_p6: 2 roots, sketch takes 1: p6 to the right of the line from p4 to p5
        branch distance_p5_p7: 2 roots, the sketch does not reach it, default 0: p7 to the left of the line from p0 to p5"#]]
    .assert_eq(&branches.join("\n"));
    let (code, explained, _) = gcs(&["explain", FOLDED]);
    assert_eq!(code, 0);
    assert!(
        explained.contains("- distance_p5_p7 (default 0, the sketch does not reach it):"),
        "{explained}"
    );
    assert!(
        explained.contains("- distance_p4_p5 (default 0, the sketch's):"),
        "{explained}"
    );
}

#[test]
fn a_branch_given_is_never_changed() {
    let (code, json, stderr) = solve_json(&["--branch", "distance_p4_p5=0"]);
    assert_eq!(code, 0, "{stderr}");
    assert_unit_distances(&json);
    assert_eq!(json["branches"]["distance_p4_p5"], 0);
    let changed = json["branches_changed"].as_array().expect("a list");
    assert!(!changed.is_empty());
    assert!(
        changed.iter().all(|c| c["name"] != "distance_p4_p5"),
        "{changed:?}"
    );
    assert!(
        stderr.starts_with(
            "warning: the constraints cannot be met on the sketch's branches (and those given): "
        ),
        "{stderr}"
    );
    // Every branch given as the sketch has it: none is changed, and the error is the plan's.
    let mut all = vec!["solve", FOLDED];
    for b in SKETCH {
        all.extend(["--branch", *b]);
    }
    let (code, stdout, stderr) = gcs(&all);
    assert_eq!(code, 1);
    assert_eq!(stdout, "");
    assert!(
        stderr.contains("`distance_p5_p7` (distance(p5, p7) = 1) cannot be met: no intersection"),
        "{stderr}"
    );
    assert!(!stderr.contains("warning"), "{stderr}");
}

#[test]
fn a_model_solvable_on_the_sketch_s_branches_says_nothing_and_lists_none() {
    let (code, stdout, stderr) = gcs(&["solve", "--json", "examples/fourbar.gcs"]);
    assert_eq!(code, 0);
    assert_eq!(stderr, "");
    let json: Value = serde_json::from_str(&stdout).expect("JSON");
    assert_eq!(json["branches_changed"], Value::Array(Vec::new()));
    assert!(stdout.contains("  \"branches_changed\": [],\n"), "{stdout}");
    let (code, _, stderr) = gcs(&["check", "--deny", "sketch-branch", "examples/fourbar.gcs"]);
    assert_eq!((code, stderr.as_str()), (0, ""));
    let (code, _, stderr) = gcs(&["solve", "--deny", "sketch-branch", "examples/fourbar.gcs"]);
    assert_eq!((code, stderr.as_str()), (0, ""));
}

#[test]
fn every_assembly_lists_where_it_differs_from_the_sketch() {
    let (code, stdout, stderr) = gcs(&["solve", "--all-solutions", "--json", FOLDED]);
    assert_eq!(code, 0, "{stderr}");
    // Nothing is changed when every assembly is listed: each says where it differs.
    assert_eq!(stderr, "");
    let json: Value = serde_json::from_str(&stdout).expect("JSON");
    let solutions = json["solutions"].as_array().expect("a list");
    assert!(!solutions.is_empty());
    let sketch: Vec<(&str, u64)> = (SKETCH.iter())
        .filter_map(|b| b.split_once('='))
        .map(|(n, i)| (n, i.parse().expect("an index")))
        .collect();
    for s in solutions {
        assert_unit_distances(s);
        let differ: Vec<&str> = (sketch.iter())
            .filter(|(b, i)| s["branches"][*b].as_u64() != Some(*i))
            .map(|(b, _)| *b)
            .collect();
        let listed: Vec<&str> = (s["branches_changed"].as_array().expect("a list").iter())
            .map(|c| c["name"].as_str().expect("a name"))
            .collect();
        assert_eq!(listed, differ);
    }
}
