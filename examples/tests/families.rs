//! The generated solvers of the model families (`families/`) against the interpreter, as the
//! trybuild driver checks the examples: equal answers or equal errors, and every constraint
//! re-measured by `verify`. The chain of 128 four-bars is long enough that
//! codegen writes its solve in blocks (`codegen/scopes.rs`); this is where that code runs.

use gcs_compiler::solution::Solution;

/// What a generated solver gives for one case, by dotted name.
type Answer = Result<Solution, (String, String)>;

fn close(model: &str, what: &str, a: f64, b: f64, at: &[f64], rel: f64) {
    let scale = a.abs().max(b.abs()).max(1.0);
    assert!(
        (a - b).abs() <= rel * scale,
        "{model}: {what}: generated {a} vs interpreter {b} at {at:?}"
    );
}

/// Solves `file` with the interpreter and with `generated` on the default params and others
/// spread over each param's range, on the sketch's branches and with every seventh branch
/// variable flipped in turn; asks for answers equal to `rel` relative; returns how many cases
/// solved.
fn agree(
    file: &str,
    rel: f64,
    generated: impl Fn(&[(String, f64)], &[(String, u8)]) -> Answer,
) -> usize {
    let path = format!("{}/families/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read(&path).expect("family file");
    let (_, model, diags) = gcs_lang::load(file, &text);
    let model = model.unwrap_or_else(|| panic!("{file}: {diags:?}"));
    let analysis = gcs_compiler::analyse(&model).expect("analysis");
    let (plan, scope) = gcs_compiler::prune::prune(&model, &analysis.plan);
    let names: Vec<String> = model.params.iter().map(|(_, p)| p.name.clone()).collect();
    let base = model.default_params();
    let mut cases = vec![base.clone()];
    for i in 0..base.len() {
        for k in [0.5, 0.97, 1.03, 2.0, -1.0] {
            let mut p = base.clone();
            p[i] = if p[i] == 0.0 { 0.1 * k } else { p[i] * k };
            cases.push(p);
        }
    }
    let defaults: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let mut branch_sets = vec![defaults.clone()];
    for (i, b) in plan.branches.iter().enumerate().step_by(7) {
        let mut set = defaults.clone();
        set[i] = (b.default + 1) % b.count;
        branch_sets.push(set);
    }
    let mut solved = 0;
    for params in &cases {
        for branches in &branch_sets {
            let named_params: Vec<(String, f64)> =
                names.iter().cloned().zip(params.iter().copied()).collect();
            let named_branches: Vec<(String, u8)> = plan
                .branches
                .iter()
                .zip(branches)
                .map(|(b, &i)| (b.name.clone(), i as u8))
                .collect();
            let interpreted = gcs_compiler::solve_plan(&model, &plan, &scope, params, branches);
            match (interpreted, generated(&named_params, &named_branches)) {
                (Ok(s), Ok(g)) => {
                    let s = s.by_name();
                    let mut size: f64 = 1.0;
                    for (name, p) in &g.points {
                        let q = s.point(name).unwrap_or_else(|| panic!("{file}: no {name}"));
                        close(file, name, p[0], q[0], params, rel);
                        close(file, name, p[1], q[1], params, rel);
                        size = size.max(p[0].abs()).max(p[1].abs());
                    }
                    for (name, v) in &g.vectors {
                        let q = s
                            .vector(name)
                            .unwrap_or_else(|| panic!("{file}: no {name}"));
                        close(file, name, v[0], q[0], params, rel);
                        close(file, name, v[1], q[1], params, rel);
                    }
                    for (name, x) in &g.scalars {
                        let q = s
                            .scalar(name)
                            .unwrap_or_else(|| panic!("{file}: no {name}"));
                        close(file, name, *x, q, params, rel);
                        size = size.max(x.abs());
                    }
                    for r in gcs_compiler::verify::residuals(&model, &g, params) {
                        let c = &model.constraints[r.constraint];
                        if c.args
                            .iter()
                            .all(|a| scope.contains(&model.top_level_of(*a)))
                        {
                            assert!(
                                r.value <= 1e-12 * size,
                                "{file}: `{}` off by {:e} at {params:?}",
                                c.text,
                                r.value
                            );
                        }
                    }
                    solved += 1;
                }
                (Err(a), Err((label, kind))) => {
                    assert_eq!(
                        (a.label.to_string(), format!("{:?}", a.kind)),
                        (label, kind),
                        "{file}"
                    );
                }
                (a, b) => panic!("{file}: interpreter {a:?} but generated {b:?}"),
            }
        }
    }
    solved
}

/// A closure solving with the generated module `$m`, its answer by dotted name.
macro_rules! generated {
    ($m:path) => {{
        use $m as m;
        |params: &[(String, f64)], branches: &[(String, u8)]| -> Answer {
            let mut p = m::Params::default();
            for (n, v) in params {
                assert!(p.set(n, *v), "no param {n}");
            }
            let mut b = m::Branches::default();
            for (n, i) in branches {
                assert!(b.set(n, *i), "no branch {n}");
            }
            match m::solve(&p, &b, &m::Defaults::default()) {
                Ok(g) => Ok(Solution {
                    points: g
                        .points()
                        .into_iter()
                        .map(|(n, p)| (n.to_string(), vec![p.x, p.y]))
                        .collect(),
                    vectors: g
                        .vectors()
                        .into_iter()
                        .map(|(n, v)| (n.to_string(), vec![v.x, v.y]))
                        .collect(),
                    scalars: g
                        .scalars()
                        .into_iter()
                        .map(|(n, x)| (n.to_string(), x))
                        .collect(),
                    ..Solution::default()
                }),
                Err(e) => Err((e.label.to_string(), format!("{:?}", e.kind))),
            }
        }
    }};
}

/// The generated module of a family file, as `build.rs` writes it (before rustfmt).
fn code_of(file: &str) -> String {
    let path = format!("{}/families/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read(&path).expect("family file");
    let model = gcs_lang::load(file, &text).1.expect("loads");
    let analysis = gcs_compiler::analyse(&model).expect("analysis");
    gcs_compiler::codegen::generate(&model, &analysis.plan).into()
}

#[test]
fn the_chain_of_128_is_solved_in_blocks() {
    assert!(code_of("fourbar_chain_128.gcs").contains("// A block of steps"));
    assert!(!code_of("fourbar_chain_16.gcs").contains("// A block of steps"));
    // The interpreter rounds some steps differently (the generated code folds constants), and
    // 128 stages in series carry a rounding on: 1e-14 at 16 stages, 1e-13 here.
    let solved = agree(
        "fourbar_chain_128.gcs",
        1e-13,
        generated!(gcs_examples::fourbar_chain_128),
    );
    assert!(solved > 0);
}

#[test]
fn the_other_families_agree_with_the_interpreter() {
    let chain = generated!(gcs_examples::fourbar_chain_16);
    assert!(agree("fourbar_chain_16.gcs", 1e-14, chain) > 0);
    assert!(agree("truss_16.gcs", 1e-14, generated!(gcs_examples::truss_16)) > 0);
    // Each segment's end is where it touches its fillet (`tangent` and `on`): a double root,
    // which a rounding of 1e-16 moves by its square root. Both sides meet every constraint to
    // 1e-12 (checked by `verify`), and agree to 1e-7 relative.
    let sketch = generated!(gcs_examples::sketch_profile_16);
    assert!(agree("sketch_profile_16.gcs", 1e-7, sketch) > 0);
}
