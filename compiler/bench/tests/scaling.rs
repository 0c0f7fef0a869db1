//! Analysis stays linear in the size of a model (issue 7), checked without timing anything:
//! every stage of a long four-bar chain costs the same number of plan steps, whatever its
//! place in the chain, and the long chain solves to the verifier's tolerance. A quadratic
//! analysis would take minutes here in a debug build (it used to scan every pending relation
//! after each step); this test takes seconds.

use gcs_bench::families::Family;

/// The model of `n` stages, analysed: (plan steps, branch variables, max residual of a solve
/// with the sketch's branches).
fn analysed(n: usize) -> (usize, usize, f64) {
    let text = Family::FourBarChain.model(n);
    let (_, model, diags) = gcs_lang::load(&format!("fourbar_chain_{n}.gcs"), text.as_bytes());
    let model = model.unwrap_or_else(|| panic!("the chain of {n} does not load: {diags:?}"));
    let a = gcs_compiler::analyse(&model).expect("a 2d model is analysed");
    assert!(
        a.unsolved.is_empty(),
        "the chain of {n} has unsolved constraints"
    );
    assert!(
        a.free_geoms().is_empty(),
        "the chain of {n} is under-constrained"
    );
    let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let s = gcs_compiler::solve(&model, &a, &model.default_params(), &branches)
        .unwrap_or_else(|e| panic!("the chain of {n} does not solve: {e}"));
    (a.plan.steps.len(), a.plan.branches.len(), s.max_residual)
}

#[test]
fn a_long_chain_costs_the_same_per_stage() {
    let (s1, b1, _) = analysed(1);
    let (s2, b2, _) = analysed(2);
    let per_stage = s2 - s1;
    assert!(per_stage > 0);
    assert_eq!(b2 - b1, 1, "one branch variable a stage");
    for n in [10, 100] {
        let (s, b, r) = analysed(n);
        assert_eq!(s, s1 + (n - 1) * per_stage, "steps of the chain of {n}");
        assert_eq!(b, n, "branch variables of the chain of {n}");
        assert!(r <= 1e-9, "the chain of {n} solves with residual {r:e}");
    }
    let (s1000, b1000, r1000) = analysed(1000);
    let (s2000, b2000, r2000) = analysed(2000);
    assert_eq!(s1000, s1 + 999 * per_stage);
    assert_eq!(
        s2000,
        2 * s1000 - (s1 - per_stage),
        "steps(2000) = 2·steps(1000) - steps(0)"
    );
    assert_eq!((b1000, b2000), (1000, 2000));
    assert!(r1000 <= 1e-9, "residual {r1000:e}");
    assert!(r2000 <= 1e-9, "residual {r2000:e}");
}
