// The driver of a generated `solve_all`, included by the cases of models that have one (see
// `driver.rs`): at the model's params, and each param moved a little, the generated list of
// assemblies equals the interpreter's (`gcs_compiler::all::solve_all`): as many, each one of
// the interpreter's within 1e-9 of the model's size, the same completeness; every assembly
// re-checked by `verify`; and listing them allocates nothing.

fn all_assemblies(
    model: &gcs_lang::Model,
    plan: &gcs_compiler::plan::Plan,
    scope: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
    names: &[String],
) -> usize {
    let base = model.default_params();
    let mut cases = vec![base.clone()];
    for i in 0..base.len() {
        for k in [0.97, 1.03] {
            let mut p = base.clone();
            p[i] = if p[i] == 0.0 { 0.1 * k } else { p[i] * k };
            cases.push(p);
        }
    }
    let sketch_defaults = plan.sketch_defaults();
    let mut listed = 0;
    for params in &cases {
        let mut gp = solver::Params::default();
        for (n, v) in names.iter().zip(params) {
            assert!(gp.set(n, *v), "no param {n}");
        }
        let gd = solver::Defaults::default();
        let interpreted = gcs_compiler::all::solve_all(model, plan, scope, params, &sketch_defaults);
        let region = stats_alloc::Region::new(crate::ALLOCATOR);
        let generated = solver::solve_all(&gp, &gd);
        let change = region.change();
        assert_eq!(
            (change.allocations, change.reallocations),
            (0, 0),
            "{NAME}: the generated solve_all allocated"
        );
        // The generated list holds at most `MAX_ASSEMBLIES`, and then says it is not complete.
        let expected = interpreted.solutions.len().min(solver::MAX_ASSEMBLIES);
        assert_eq!(
            generated.len(),
            expected,
            "{NAME}: generated {} assemblies, interpreter {} at {params:?}",
            generated.len(),
            interpreted.solutions.len()
        );
        let overflow = interpreted.solutions.len() > solver::MAX_ASSEMBLIES;
        assert_eq!(
            generated.is_complete(),
            interpreted.complete && !overflow,
            "{NAME}: completeness"
        );
        for g in generated.iter() {
            let mut size: f64 = 1.0;
            let mut solution = gcs_compiler::solution::Solution::default();
            for (name, p) in g.points() {
                size = size.max(p.coords.amax());
                solution.points.push((name.to_string(), p.iter().copied().collect()));
            }
            for (name, v) in g.vectors() {
                solution.vectors.push((name.to_string(), v.iter().copied().collect()));
            }
            for (name, x) in g.scalars() {
                size = size.max(x.abs());
                solution.scalars.push((name.to_string(), x));
            }
            let matched = interpreted.solutions.iter().any(|s| {
                let s = s.by_name();
                g.points().iter().all(|(name, p)| {
                    s.point(name).is_some_and(|q| {
                        p.iter().zip(q).all(|(a, b)| (a - b).abs() <= 1e-9 * size)
                    })
                })
            });
            assert!(matched, "{NAME}: a generated assembly the interpreter does not list: {g:?}");
            for r in gcs_compiler::verify::residuals(model, &solution, params) {
                let c = &model.constraints[r.constraint];
                if c.args.iter().all(|a| scope.contains(&model.top_level_of(*a))) {
                    assert!(
                        r.value <= 1e-12 * size,
                        "{NAME}: an assembly of solve_all violates `{}` by {:e}",
                        c.text,
                        r.value
                    );
                }
            }
            listed += 1;
        }
    }
    listed
}
