// The driver of a generated solver: included in a module of the case, after `mod solver {
// include!(...) }`, `MODEL` (the model's text), `NAME`, `SPREAD` and `TOL_GROWTH`; the case's
// `main` calls its `run`, and the case's root holds the counting allocator `ALLOCATOR`. It solves
// the model with the interpreter and with the generated solver on the same params, branches and
// defaults, asks for equal results (1e-14 relative; 1e-12 where an outer iteration converges, each
// side to its own rounding) or equal errors (the same constraint, kind and magnitude), re-checks
// every constraint of the generated solution with `verify`, and counts the generated solve's
// allocations (none, errors included; `generated_solve`, written with the case, calls `solve`, or a
// tabled module's `solve_into` on a `Solution` made before). Then `all_assemblies`
// (`driver_all.rs`, or a stand-in where the model has no `solve_all`) compares the lists of every
// assembly.

fn close(what: &str, a: f64, b: f64, tol: f64) {
    let scale = a.abs().max(b.abs()).max(1.0);
    assert!((a - b).abs() <= tol * scale, "{NAME}: {what}: generated {a} vs interpreter {b}");
}

/// The indices moved of `n` params, branch variables or defaults: all of them, or `SPREAD`
/// spread evenly from the first to the last where there are more (a large family's thousands).
fn spread(n: usize) -> Vec<usize> {
    if n <= SPREAD {
        return (0..n).collect();
    }
    let mut at: Vec<usize> = (0..SPREAD).map(|k| k * (n - 1) / (SPREAD - 1)).collect();
    at.dedup();
    at
}

pub fn run() {
    let compiled = gcs_compiler::compile(NAME, MODEL.as_bytes())
        .unwrap_or_else(|e| panic!("{NAME} does not compile: {e:?}"));
    let (model, analysis) = (&compiled.model, &compiled.analysis);
    let (plan, scope) = gcs_compiler::prune::prune(model, &analysis.plan);
    // Each side rounds on its own; through a large family's thousand dependent stages (each
    // stage built on the one before) the last ulps grow: `TOL_GROWTH` allows for that.
    let tol = TOL_GROWTH * if plan.iterations.is_empty() { 1e-14 } else { 1e-12 };
    // Params: the defaults, each one moved a little and a lot, and each one at values no
    // model means (huge, or not a number), where both must give the same error or answer.
    let base = model.default_params();
    let names: Vec<String> = model.params.iter().map(|(_, p)| p.name.clone()).collect();
    let mut cases = vec![base.clone()];
    for i in spread(base.len()) {
        for k in [0.97, 1.03, 1.25, -0.5] {
            let mut p = base.clone();
            p[i] = if p[i] == 0.0 { 0.1 * k } else { p[i] * k };
            cases.push(p);
        }
        // Zero (a sketch or a size that vanishes), the edges of the range a solve takes, past
        // it, and NaN.
        for extreme in [0.0, 1e150, -1e150, 1e300, -1e300, f64::NAN] {
            let mut p = base.clone();
            p[i] = extreme;
            cases.push(p);
        }
    }
    // Branches: the sketch's, and each variable on each of its other indices.
    let defaults: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let mut branch_sets = vec![defaults.clone()];
    for i in spread(plan.branches.len()) {
        let b = &plan.branches[i];
        for k in 0..b.count {
            if k != b.default {
                let mut set = defaults.clone();
                set[i] = k;
                branch_sets.push(set);
            }
        }
    }
    // Defaults: the sketch's for every case above; then, at the default params and branches,
    // each default moved a little and a lot (where a free motion is set, or an iteration
    // starts), and not a number.
    let sketch_defaults = plan.sketch_defaults();
    // Every params case with every branch set; in a large family (a finite `SPREAD`), each
    // params case at the sketch's branches and each branch set at the sketch's params.
    let mut runs: Vec<(&Vec<f64>, &Vec<usize>, Vec<f64>)> = Vec::new();
    for (i, params) in cases.iter().enumerate() {
        for (k, branches) in branch_sets.iter().enumerate() {
            if SPREAD == usize::MAX || i == 0 || k == 0 {
                runs.push((params, branches, sketch_defaults.clone()));
            }
        }
    }
    for i in spread(sketch_defaults.len()) {
        for delta in [0.01, -0.01, 0.3, -0.3, 2.0, f64::NAN] {
            let mut d = sketch_defaults.clone();
            d[i] += delta;
            runs.push((&cases[0], &branch_sets[0], d));
        }
    }
    let (mut equal, mut errors) = (0, 0);
    for (params, branches, given_defaults) in runs {
        {
            let mut gp = solver::Params::default();
            for (n, v) in names.iter().zip(params) {
                assert!(gp.set(n, *v), "no param {n}");
            }
            let mut gb = solver::Branches::default();
            for (b, i) in plan.branches.iter().zip(branches) {
                assert!(gb.set(&b.name, *i as u8), "no branch {}", b.name);
            }
            let mut gd = solver::Defaults::default();
            for (d, v) in plan.defaults.iter().zip(&given_defaults) {
                assert!(gd.set(&d.name, *v), "no default {}", d.name);
            }
            let interpreted = gcs_compiler::solve_plan_with(
                model,
                &plan,
                &scope,
                params,
                branches,
                &given_defaults,
            );
            let (generated, allocations) = generated_solve(&gp, &gb, &gd);
            assert_eq!(allocations, (0, 0), "{NAME}: the generated solve allocated");
            match (interpreted, generated) {
                (Ok(s), Ok(g)) => {
                    let s = s.by_name();
                    let mut solution = gcs_compiler::solution::Solution::default();
                    let mut size: f64 = 1.0;
                    // Points and vectors of either space: their coordinates in order.
                    for (name, p) in g.points() {
                        let q = s.point(name).unwrap_or_else(|| panic!("{NAME}: no point {name}"));
                        let p: Vec<f64> = p.iter().copied().collect();
                        assert_eq!(p.len(), q.len(), "{NAME}: {name} in another space");
                        for (a, b) in p.iter().zip(q) {
                            close(name, *a, *b, tol);
                            size = size.max(a.abs());
                        }
                        solution.points.push((name.to_string(), p));
                    }
                    for (name, v) in g.vectors() {
                        let q = s.vector(name).unwrap_or_else(|| panic!("{NAME}: no vector {name}"));
                        let v: Vec<f64> = v.iter().copied().collect();
                        assert_eq!(v.len(), q.len(), "{NAME}: {name} in another space");
                        for (a, b) in v.iter().zip(q) {
                            close(name, *a, *b, tol);
                        }
                        solution.vectors.push((name.to_string(), v));
                    }
                    for (name, x) in g.scalars() {
                        let q = s.scalar(name).unwrap_or_else(|| panic!("{NAME}: no scalar {name}"));
                        close(name, x, q, tol);
                        size = size.max(x.abs());
                        solution.scalars.push((name.to_string(), x));
                    }
                    // Every constraint among the solved geoms, re-measured independently.
                    for r in gcs_compiler::verify::residuals(model, &solution, params) {
                        let c = &model.constraints[r.constraint];
                        let solved = c.args.iter().all(|a| scope.contains(&model.top_level_of(*a)));
                        if solved {
                            assert!(
                                r.value <= 1e-12 * size,
                                "{NAME}: `{}` violated by {:e} with params {params:?}",
                                c.text,
                                r.value
                            );
                        }
                    }
                    equal += 1;
                }
                // At params so large that the rounding of the geometry (one unit in the last
                // place of a 1e150 radius is 1.8e134) exceeds the checks' tolerance, scaled by
                // the sketch, the first check to find that rounding depends on each side's
                // order of operations: the same kind of error, by a rounding-level amount,
                // may come at a later stage on one side (the sketch profile of 1,000 stages).
                (Err(a), Err(b))
                    if a.label != b.label
                        && a.kind == b.kind
                        && a.kind == gcs_runtime::error::ErrorKind::Inconsistent
                        && a.magnitude.max(b.magnitude)
                            <= 1e-12 * params.iter().fold(1.0f64, |m, p| m.max(p.abs())) =>
                {
                    errors += 1;
                }
                (Err(a), Err(b)) => {
                    assert_eq!(
                        (&a.label, a.kind),
                        (&b.label, b.kind),
                        "{NAME}: different errors ({a} and {b}) with params {params:?}, branches \
                         {branches:?}"
                    );
                    // An iteration that does not converge stops wherever its own rounding
                    // took it: the residual it reached is not reproducible to the bit.
                    let unconverged = a.kind == gcs_runtime::error::ErrorKind::NoConvergence;
                    let same = unconverged
                        || a.magnitude == b.magnitude
                        || (a.magnitude.is_nan() && b.magnitude.is_nan());
                    if !same {
                        close(&format!("{} magnitude", a.label), b.magnitude, a.magnitude, tol);
                    }
                    errors += 1;
                }
                // A size computed as zero to rounding (a segment of no length, a radius at
                // an ill-conditioned extreme of the params) may fall on either side of zero:
                // one side refuses it as negative, the other solves with it. Both are right
                // to rounding, and that is all an extreme param can ask.
                (Ok(_), Err(e)) | (Err(e), Ok(_))
                    if e.kind == gcs_runtime::error::ErrorKind::InvalidValue
                        && e.magnitude.abs()
                            <= 1e-12 * params.iter().fold(1.0f64, |m, p| m.max(p.abs())) =>
                {
                    errors += 1;
                }
                (a, b) => panic!("{NAME}: interpreter {a:?} but generated {b:?}"),
            }
        }
    }
    assert!(equal > 0, "{NAME}: nothing solved");
    let listed = all_assemblies(model, &plan, &scope, &names);
    println!("{NAME}: {equal} equal solutions, {errors} equal errors, {listed} assemblies listed alike");
}
