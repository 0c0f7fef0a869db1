//! Embedding one solver the way the README shows, in a private module of a crate that denies
//! warnings, and using only `solve` and one accessor: the generated API the caller leaves
//! unused (the setters, the other accessors) must not warn. (trybuild cannot show this: it
//! builds its cases with `dead_code` allowed.)
#![deny(warnings)]

mod fourbar {
    gcs_runtime::include_solver!("fourbar");
}

#[test]
fn a_caller_that_reads_one_output_builds_without_warnings() {
    let solution = fourbar::solve(
        &fourbar::Params::default(),
        &fourbar::Branches::default(),
        &fourbar::Defaults::default(),
    )
    .expect("the sketch's four-bar assembles");
    let c = solution.coupler_c();
    // The coupler's far joint is 3 from the rocker's pivot D = (4, 0), and above the ground
    // on the default branch.
    let to_d = ((c.x - 4.0).powi(2) + c.y.powi(2)).sqrt();
    assert!((to_d - 3.0).abs() < 1e-12, "coupler.c = {c}, {to_d} from D");
    assert!(c.y > 0.0, "coupler.c = {c}");
}
