// A tabled solver's errors name the occurrence that failed, not the representative its
// function was written from: the 16-stage chain's stages are one shape, written from stage 1,
// and a branch index that stage 7 does not have is reported as stage 7's constraint. Values
// are read and set by name, and a name the model does not have is refused.
#![deny(warnings)]

mod solver {
    include!("../tabled/fourbar_chain_16.rs");
}

use gcs_runtime::error::ErrorKind;

fn main() {
    let params = solver::Params::default();
    let defaults = solver::Defaults::default();
    let mut solution = solver::Solution::new();

    let mut branches = solver::Branches::default();
    assert!(branches.set("elbow7", 2));
    assert!(!branches.set("elbow17", 0), "no such branch variable");
    let error = solver::solve_into(&params, &branches, &defaults, &mut solution)
        .expect_err("stage 7 has no third assembly");
    assert_eq!(error.label, "elbow7");
    assert_eq!(error.text, "coincident(coupler7.c, rocker7.c)");
    assert_eq!(error.kind, ErrorKind::NoSuchBranch);

    // The same at the last stage, and a solve of the sketch's branches after both.
    branches.set("elbow7", 0);
    branches.set("elbow16", 3);
    let error = solver::solve_into(&params, &branches, &defaults, &mut solution)
        .expect_err("stage 16 has no fourth assembly");
    assert_eq!(error.label, "elbow16");
    assert_eq!(error.text, "coincident(coupler16.c, rocker16.c)");
    branches.set("elbow16", 0);
    solver::solve_into(&params, &branches, &defaults, &mut solution).expect("the sketch's assembly");

    // By name: each value once, in model order, and the same through `point`.
    let points: Vec<(&str, _)> = solution.points().collect();
    assert_eq!(points.len(), solver::Solution::new().points().count());
    for (name, p) in &points {
        assert_eq!(solution.point(name), Some(*p), "{name}");
    }
    assert!(solution.point("rocker17.c").is_none());
    let c7 = solution.point("rocker7.c").expect("rocker7.c");
    let d7 = solution.point("rocker7.d").expect("rocker7.d");
    assert!(((c7 - d7).norm() - 3.0).abs() < 1e-12, "rocker7 keeps its length");
    assert_eq!(solver::Branches::names().count(), 16);
    assert_eq!(
        solver::Branches::meaning("elbow7", 1),
        Some("rocker7.c to the right of the line from rocker6.b to P7")
    );
    assert_eq!(solver::Branches::meaning("elbow7", 2), None);
}
