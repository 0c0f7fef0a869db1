//! How analysis, code generation and solving scale with the size of a model (issue 7).
//!
//! For each generated family ([`gcs_bench::families::Family`]) and N in 10, 30, 100, 300,
//! 1000, 3000, 10000, times parse + resolve (`gcs_lang::load`), analysis
//! (`gcs_compiler::analyse`), pruning + code generation (`prune::prune` and `codegen::generate`,
//! without rustfmt) and one solve of the pruned plan by the interpreter (`interp::run` with the
//! default branches, median of several runs), and checks the solve's max residual once per N
//! with `solve_plan`. Fits the exponent b of t = a·N^b by least squares on log-log for each
//! column, prints a Markdown table and writes it to `target/scaling.md`.
//!
//! `cargo bench -p gcs-examples --bench scaling`; `GCS_SCALING_MAX=1000` (or a first argument
//! that is a number) limits the sizes for a quick run.

use gcs_bench::families::Family;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

const SIZES: [usize; 7] = [10, 30, 100, 300, 1000, 3000, 10000];

/// One measured row.
struct Row {
    n: usize,
    parse: Duration,
    analyse: Duration,
    codegen: Duration,
    solve: Duration,
    steps: usize,
    residual: f64,
}

/// The median of `runs` timings of `f` (at least one).
fn median(runs: usize, mut f: impl FnMut()) -> Duration {
    let mut ts: Vec<Duration> = (0..runs.max(1))
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed()
        })
        .collect();
    ts.sort();
    ts[ts.len() / 2]
}

/// Repeats for a step of size `n`: more for small models, so that the medians are stable.
fn runs_for(n: usize) -> usize {
    match n {
        0..=100 => 9,
        101..=1000 => 5,
        _ => 3,
    }
}

fn measure(family: Family, n: usize) -> Row {
    let text = family.model(n);
    let name = format!("{}_{n}.gcs", family.name());
    let runs = runs_for(n);
    let parse = median(runs, || {
        black_box(gcs_lang::load(&name, text.as_bytes()));
    });
    let (_, model, diags) = gcs_lang::load(&name, text.as_bytes());
    let model = model.unwrap_or_else(|| panic!("{name} does not load: {diags:?}"));
    let analyse = median(runs, || {
        black_box(gcs_compiler::analyse(&model).ok());
    });
    let analysis =
        gcs_compiler::analyse(&model).unwrap_or_else(|e| panic!("{name} is not analysed: {e}"));
    let codegen = median(runs, || {
        let (plan, scope) = gcs_compiler::prune::prune(&model, &analysis.plan);
        black_box((&plan, &scope));
        black_box(gcs_compiler::codegen::generate(&model, &analysis.plan));
    });
    let (plan, scope) = gcs_compiler::prune::prune(&model, &analysis.plan);
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let params = model.default_params();
    let choice = gcs_compiler::interp::Choice::Given(branches.clone());
    let solve = median(runs * 3, || {
        black_box(gcs_compiler::interp::run(&model, &plan, &params, &choice).is_ok());
    });
    let residual = match gcs_compiler::solve_plan(&model, &plan, &scope, &params, &branches) {
        Ok(s) => s.max_residual,
        Err(e) => panic!("{name} does not solve: {e}"),
    };
    Row {
        n,
        parse,
        analyse,
        codegen,
        solve,
        steps: plan.steps.len(),
        residual,
    }
}

/// The exponent b of t = a·N^b, by least squares on (ln N, ln t).
fn exponent(points: &[(usize, Duration)]) -> f64 {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .map(|&(n, t)| ((n as f64).ln(), t.as_secs_f64().max(1e-9).ln()))
        .collect();
    let k = xy.len() as f64;
    if xy.len() < 2 {
        return f64::NAN;
    }
    let (mx, my) = (
        xy.iter().map(|p| p.0).sum::<f64>() / k,
        xy.iter().map(|p| p.1).sum::<f64>() / k,
    );
    let sxy: f64 = xy.iter().map(|&(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xy.iter().map(|&(x, _)| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// A duration in the unit that suits it.
fn show(t: Duration) -> String {
    let us = t.as_secs_f64() * 1e6;
    if us < 1000.0 {
        format!("{us:.1} µs")
    } else if us < 1e6 {
        format!("{:.2} ms", us / 1e3)
    } else {
        format!("{:.3} s", us / 1e6)
    }
}

fn main() {
    // `cargo bench` passes `--bench`; a numeric argument or GCS_SCALING_MAX limits N.
    let max = std::env::args()
        .skip(1)
        .find_map(|a| a.parse::<usize>().ok())
        .or_else(|| {
            std::env::var("GCS_SCALING_MAX")
                .ok()
                .and_then(|v| v.parse().ok())
        })
        .unwrap_or(usize::MAX);
    let sizes: Vec<usize> = SIZES.into_iter().filter(|&n| n <= max).collect();
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Scaling of analysis, code generation and solving (issue 7)\n\n\
         Times are medians; codegen is prune + generate without rustfmt; solve is one run of \
         the pruned plan by the interpreter with the default branches. b is the exponent of \
         t = a·N^b fitted by least squares on log-log.\n"
    );
    for family in Family::ALL {
        let _ = writeln!(md, "## {}\n", family.name());
        let _ = writeln!(
            md,
            "| N | steps | parse + resolve | analyse | prune + codegen | solve | max residual |"
        );
        let _ = writeln!(md, "|---:|---:|---:|---:|---:|---:|---:|");
        let mut rows = Vec::new();
        for &n in &sizes {
            let r = measure(family, n);
            let line = format!(
                "| {} | {} | {} | {} | {} | {} | {:.1e} |",
                r.n,
                r.steps,
                show(r.parse),
                show(r.analyse),
                show(r.codegen),
                show(r.solve),
                r.residual
            );
            eprintln!("{} {line}", family.name());
            let _ = writeln!(md, "{line}");
            rows.push(r);
        }
        let fit = |f: fn(&Row) -> Duration| {
            exponent(&rows.iter().map(|r| (r.n, f(r))).collect::<Vec<_>>())
        };
        let _ = writeln!(
            md,
            "\nExponents b: parse + resolve {:.2}, analyse {:.2}, prune + codegen {:.2}, \
             solve {:.2}; worst residual {:.1e}.\n",
            fit(|r| r.parse),
            fit(|r| r.analyse),
            fit(|r| r.codegen),
            fit(|r| r.solve),
            rows.iter().map(|r| r.residual).fold(0.0, f64::max)
        );
    }
    print!("{md}");
    // target/ of the workspace: the bench runs with the package's directory as cwd.
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| {
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("..")
                .join("target")
        });
    let file = target.join("scaling.md");
    match std::fs::write(&file, &md) {
        Ok(()) => eprintln!("wrote {}", file.display()),
        Err(e) => eprintln!("cannot write {}: {e}", file.display()),
    }
}
