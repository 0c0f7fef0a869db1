//! How analysis, code generation and solving scale with the size of a model (issue 7), and what
//! `gcs check` and `gcs solve --json` do with many params and many points (issue 17, item 7).
//!
//! For each generated family ([`gcs_bench::families::Family`]) and N in 10, 30, 100, 300,
//! 1000, 3000, 10000, times parse + resolve (`gcs_lang::load`), analysis
//! (`gcs_compiler::analyse`), pruning + code generation (`prune::prune` and `codegen::generate`,
//! without rustfmt) and one solve of the pruned plan by the interpreter (`interp::run` with the
//! default branches, median of several runs), and checks the solve's max residual once per N
//! with `solve_plan`.
//!
//! Then the commands' own paths, N from 2,500 to 100,000: for the `params` family what
//! `gcs check` does (the pipeline, `gcs_compiler::compile`; the report; the diagnostics
//! rendered as the CLI renders them, repeated warnings counted), and for the `points` family
//! what `gcs solve --json` does (the pipeline; prune, solve, verify; the JSON).
//!
//! Fits the exponent b of t = a·N^b by least squares on log-log for each column, prints
//! Markdown tables and writes them to `target/scaling.md`.
//!
//! `cargo bench -p gcs-examples --bench scaling`; `GCS_SCALING_MAX=1000` (or an argument that
//! is a number) limits the sizes for a quick run, and a word keeps the families whose name holds
//! it (`-- points`).

use gcs_bench::families::Family;
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::{Duration, Instant};

const SIZES: [usize; 7] = [10, 30, 100, 300, 1000, 3000, 10000];

/// The sizes of the commands' paths: the (2,500 to 20,000), and up to 100,000.
const COMMAND_SIZES: [usize; 7] = [2500, 5000, 10000, 20000, 40000, 70000, 100000];

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

/// One measured row of a command's path.
struct CommandRow {
    n: usize,
    /// `gcs_lang::load` alone: parse and resolve.
    load: Duration,
    /// `gcs_compiler::compile`: load, analyse, report the problems.
    compile: Duration,
    /// What the command does next: the report and the diagnostics, or the solve and the JSON.
    command: Duration,
    /// What it prints, in lines (stdout and diagnostics).
    lines: usize,
}

impl CommandRow {
    fn total(&self) -> Duration {
        self.compile + self.command
    }
}

/// `gcs check` on the params family, as the CLI runs it: the pipeline, then the DOF report and
/// the diagnostics rendered (without colour), or `gcs solve --json` on the points family: the
/// pipeline, then the plan pruned to the outputs, solved with the default branches and
/// verified, and the JSON.
fn measure_command(family: Family, n: usize) -> CommandRow {
    let text = family.model(n);
    let name = format!("{}_{n}.gcs", family.name());
    let runs = if n <= 10000 { 3 } else { 1 };
    let load = median(runs, || {
        black_box(gcs_lang::load(&name, text.as_bytes()));
    });
    let compile = median(runs, || {
        black_box(gcs_compiler::compile(&name, text.as_bytes()).is_ok());
    });
    let c = gcs_compiler::compile(&name, text.as_bytes())
        .unwrap_or_else(|_| panic!("{name} does not compile"));
    assert!(!c.has_errors(), "{name} has errors");
    let mut lines = 0;
    let command = match family {
        Family::Points => median(runs, || {
            let (plan, scope) = gcs_compiler::prune::prune(&c.model, &c.analysis.plan);
            let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
            let params = c.model.default_params();
            let s = gcs_compiler::solve_plan(&c.model, &plan, &scope, &params, &branches)
                .unwrap_or_else(|e| panic!("{name} does not solve: {e}"));
            assert!(
                s.max_residual <= 1e-9,
                "{name}: residual {}",
                s.max_residual
            );
            let json = s.to_json();
            lines = json.lines().count();
            black_box(json);
        }),
        _ => median(runs, || {
            let diagnostics = gcs_lang::diagnostic::render_plain(&c.source, &c.diagnostics);
            let report = gcs_compiler::report::check_report(&c.model, &c.analysis);
            lines = diagnostics.lines().count() + report.lines().count();
            black_box((diagnostics, report));
        }),
    };
    CommandRow {
        n,
        load,
        compile,
        command,
        lines,
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
    // `cargo bench` passes `--bench`; a numeric argument or GCS_SCALING_MAX limits N, a word
    // picks families.
    let words: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-') && a.parse::<usize>().is_err())
        .collect();
    let picked = |f: Family| words.is_empty() || words.iter().any(|w| f.name().contains(w));
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
    for family in Family::ALL.into_iter().filter(|&f| picked(f)) {
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
    let commands = [
        (Family::Params, "gcs check"),
        (Family::Points, "gcs solve --json"),
    ];
    for (family, command) in commands.into_iter().filter(|&(f, _)| picked(f)) {
        let sizes: Vec<usize> = COMMAND_SIZES.into_iter().filter(|&n| n <= max).collect();
        let _ = writeln!(md, "## {command}: {} (issue 17, item 7)\n", family.name());
        let _ = writeln!(
            md,
            "| N | lines printed | parse + resolve | pipeline (compile) | {} | total |",
            if family == Family::Points {
                "prune + solve + verify + JSON"
            } else {
                "report + diagnostics"
            }
        );
        let _ = writeln!(md, "|---:|---:|---:|---:|---:|---:|");
        let mut rows = Vec::new();
        for &n in &sizes {
            let r = measure_command(family, n);
            let line = format!(
                "| {} | {} | {} | {} | {} | {} |",
                r.n,
                r.lines,
                show(r.load),
                show(r.compile),
                show(r.command),
                show(r.total())
            );
            eprintln!("{} {line}", family.name());
            let _ = writeln!(md, "{line}");
            rows.push(r);
        }
        let fit = |f: fn(&CommandRow) -> Duration| {
            exponent(&rows.iter().map(|r| (r.n, f(r))).collect::<Vec<_>>())
        };
        let _ = writeln!(
            md,
            "\nExponents b: parse + resolve {:.2}, pipeline {:.2}, the command's own {:.2}, \
             total {:.2}.\n",
            fit(|r| r.load),
            fit(|r| r.compile),
            fit(|r| r.command),
            fit(|r| r.total())
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
