//! Generated solvers against the interpreter on every example, and the four-bar against a
//! closed-form solve written by hand, in one run. `cargo bench -p gcs-examples --bench solvers`.

use criterion::{criterion_group, criterion_main, Criterion};
use gcs_examples as ex;
use std::hint::black_box;

/// A four-bar solved by hand, in closed form: the crank's end, then the coupler's far joint as
/// the intersection of two circles, on the side the model's `elbow` = 0 means (left of the line
/// from the crank's end to the rocker's pivot). Same geometry as examples/fourbar.gcs, and the
/// same answer as its output `coupler.c`.
fn four_bar_by_hand(theta: f64) -> Option<(f64, f64)> {
    let (crank, coupler, rocker) = (1.5, 4.0, 3.0);
    let (dx, dy) = (4.0, 0.0);
    let (s, c) = theta.sin_cos();
    let (bx, by) = (crank * c, crank * s);
    let (ux, uy) = (dx - bx, dy - by);
    let d2 = ux * ux + uy * uy;
    let d = d2.sqrt();
    let a = (coupler * coupler - rocker * rocker + d2) / (2.0 * d);
    let h2 = coupler * coupler - a * a;
    if h2 < 0.0 {
        return None;
    }
    let h = h2.sqrt();
    let (ex_, ey) = (ux / d, uy / d);
    Some((bx + a * ex_ - h * ey, by + a * ey + h * ex_))
}

fn interpreted(name: &str) -> (gcs_lang::Model, gcs_compiler::analysis::Analysis) {
    let path = format!("{}/{name}.gcs", env!("CARGO_MANIFEST_DIR"));
    let bytes = std::fs::read(&path).expect("example");
    let (_, model, _) = gcs_lang::load(&path, &bytes);
    let model = model.expect("model");
    let analysis = gcs_compiler::analysis::analyse(&model).expect("analysis");
    (model, analysis)
}

fn bench_four_bar(c: &mut Criterion) {
    let mut g = c.benchmark_group("fourbar");
    let thetas: Vec<f64> = (0..64).map(|i| i as f64 * 0.098).collect();
    g.bench_function("by_hand", |b| {
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 63;
            black_box(four_bar_by_hand(black_box(thetas[i])))
        })
    });
    g.bench_function("generated", |b| {
        let branches = ex::fourbar::Branches::default();
        let defaults = ex::fourbar::Defaults::default();
        let mut params = ex::fourbar::Params::default();
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 63;
            params.theta = black_box(thetas[i]);
            // The same work and the same answer as by hand: the coupler point, or none.
            let solution = ex::fourbar::solve(&params, &branches, &defaults);
            black_box(solution.ok().map(|s| {
                let c = s.coupler_c();
                (c.x, c.y)
            }))
        })
    });
    let (model, analysis) = interpreted("fourbar");
    let (plan, scope) = gcs_compiler::prune::prune(&model, &analysis.plan);
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let theta = model
        .param_named("theta")
        .map_or(0, |p| p.into_raw().into_u32() as usize);
    g.bench_function("interpreted", |b| {
        let mut params = model.default_params();
        let mut i = 0;
        b.iter(|| {
            i = (i + 1) & 63;
            params[theta] = black_box(thetas[i]);
            black_box(
                gcs_compiler::interp::run(
                    &model,
                    &plan,
                    &params,
                    &gcs_compiler::interp::Choice::Given(branches.clone()),
                )
                .is_ok(),
            )
        })
    });
    let _ = scope;
    g.finish();
}

macro_rules! generated_vs_interpreted {
    ($c:expr, $($m:ident),*) => {$(
        {
            let mut g = $c.benchmark_group(stringify!($m));
            g.bench_function("generated", |b| {
                let (p, br, d) = (ex::$m::Params::default(), ex::$m::Branches::default(), ex::$m::Defaults::default());
                b.iter(|| black_box(ex::$m::solve(black_box(&p), &br, &d).is_ok()))
            });
            let (model, analysis) = interpreted(stringify!($m));
            let (plan, _) = gcs_compiler::prune::prune(&model, &analysis.plan);
            let choice = gcs_compiler::interp::Choice::Given(plan.branches.iter().map(|b| b.default).collect());
            let params = model.default_params();
            g.bench_function("interpreted", |b| {
                b.iter(|| black_box(gcs_compiler::interp::run(&model, &plan, black_box(&params), &choice).is_ok()))
            });
            g.finish();
        }
    )*};
}

fn bench_examples(c: &mut Criterion) {
    generated_vs_interpreted!(
        c,
        circle,
        tenbar,
        slider_crank_2d,
        crank_rocker,
        sixbar,
        jansen_leg,
        sketch_profile
    );
}

criterion_group!(benches, bench_four_bar, bench_examples);
criterion_main!(benches);
