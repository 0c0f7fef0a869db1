//! `gcs`: the command line of the gcs compiler. It is the only place that reads files, prints
//! and chooses an exit code.

use clap::{Parser, Subcommand};
use codespan_reporting::term::{self, termcolor};
use gcs_compiler::codegen::Form;
use gcs_compiler::pipeline::{AnalysisError, CompileError, Compiled, Unanalysed};
use gcs_lang::{Diagnostic, SourceFile};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// `print!` to standard output, which stops quietly when its reader has gone (`gcs plan FILE |
/// head`) instead of panicking as `print!` does; the exit status is then a broken pipe's.
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if write!(std::io::stdout().lock(), $($arg)*).is_err() {
            std::process::exit(141);
        }
    }};
}

/// `println!` as [`out!`] is `print!`.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if writeln!(std::io::stdout().lock(), $($arg)*).is_err() {
            std::process::exit(141);
        }
    }};
}

mod generated;
mod serve;
mod shared;

/// A front end that reads a 100,000-statement model makes millions of small strings and nodes;
/// mimalloc's thread-local free lists serve them several times faster than the system's.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Turns transparent huge pages off for this process. `gcs compile` of a large model touches
/// half a gigabyte once; where the system gives huge pages on request (mimalloc asks), a fault
/// may wait for the kernel to compact memory into a 2 MB page: on the 2-core machine the
/// 10,000-stage sketch profile took 2.8 to 4.2 s (0.7 to 1.3 s of it in the kernel) with
/// them, and 2.2 to 2.9 s (0.3 s) without (docs/BENCHMARKS.md). A refusal changes nothing.
fn no_huge_pages() {
    #[cfg(target_os = "linux")]
    let _ = rustix::thread::disable_transparent_huge_pages(true);
}

/// Compiles geometric constraint models (.gcs) into specialised solvers.
#[derive(Debug, Parser)]
#[command(name = "gcs", version, about)]
struct Cli {
    /// When to colour diagnostics: auto, always or never.
    #[arg(long, global = true, default_value = "auto")]
    color: String,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Parse and analyse a model; print its diagnostics and DOF summary. Exits 0 only without
    /// errors.
    Check {
        /// The .gcs file.
        file: PathBuf,
        /// Make a warning an error: `under-constrained` (a motion the constraints leave free,
        /// held by a default) or `sketch-branch` (the constraints cannot be met on the sketch's
        /// branches with the default params, and the solve takes others).
        #[arg(long, value_name = "WARNING")]
        deny: Vec<String>,
    },
    /// Solve a model with the interpreter and print every geom's configuration.
    Solve {
        /// The .gcs file.
        file: PathBuf,
        /// Set a param: `NAME=EXPR`, units allowed (`theta=45deg`); a bare number for an angle
        /// is radians.
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// Choose a branch: `NAME=INDEX` (see `gcs explain` for what each index means).
        #[arg(long = "branch", value_name = "NAME=INDEX")]
        branch: Vec<String>,
        /// Set a default: `NAME=EXPR`, units allowed (`crank_angle=30deg`): the value of a
        /// motion the constraints leave free, or where an outer iteration starts.
        #[arg(long = "default", value_name = "NAME=VALUE")]
        default: Vec<String>,
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
        /// Solve every geom, not only what the `output` statements need.
        #[arg(long)]
        all: bool,
        /// List every real assembly: each branch combination, and each root of an iteration.
        #[arg(long)]
        all_solutions: bool,
        /// Make a warning an error: `sketch-branch` (the constraints cannot be met on the
        /// sketch's branches, and the solve took others).
        #[arg(long, value_name = "WARNING")]
        deny: Vec<String>,
        /// How the motions the constraints leave free are chosen: `step` (each where it moves
        /// nothing at its own step) or `global` (all together, to move the points least in
        /// total from the sketch).
        #[arg(long, value_name = "HOW", default_value = "step", value_parser = ["step", "global"])]
        least_motion: String,
    },
    /// Draw the solved model as an SVG: bodies, points with their names, circles, lines,
    /// segments and planes, fixed geoms as ground; with `--sweep`, traced points' curves or an
    /// animation of the motion.
    Draw {
        /// The .gcs file.
        file: PathBuf,
        /// Where to write the SVG; standard output when absent.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Set a param: `NAME=EXPR`, units allowed (`theta=45deg`); a bare number for an angle
        /// is radians.
        #[arg(long = "set", value_name = "NAME=VALUE")]
        set: Vec<String>,
        /// Choose a branch: `NAME=INDEX` (see `gcs explain` for what each index means); it
        /// holds at every sample of a sweep.
        #[arg(long = "branch", value_name = "NAME=INDEX")]
        branch: Vec<String>,
        /// Set a default: `NAME=EXPR`, units allowed: the value of a motion the constraints
        /// leave free, or where an outer iteration starts (a sweep's first sample; each later
        /// one starts from the one before).
        #[arg(long = "default", value_name = "NAME=VALUE")]
        default: Vec<String>,
        /// Solve at evenly spaced values of a param, both ends included: `NAME=FROM..TO` or
        /// `NAME=FROM..TO:STEPS` (60 steps unless given; `theta=0deg..360deg`). The model is
        /// drawn at the first sample that solves.
        #[arg(long, value_name = "NAME=FROM..TO[:STEPS]")]
        sweep: Option<String>,
        /// Draw a point's curve over the sweep (repeatable): one polyline for each run of
        /// samples that solved.
        #[arg(long = "trace", value_name = "POINT")]
        trace: Vec<String>,
        /// Play the sweep in the SVG itself (SMIL animation, looping).
        #[arg(long)]
        animate: bool,
        /// The view of a 3d model: xy (top), xz (front), yz (side) or iso (isometric, the
        /// default). A 2d model is drawn in its plane.
        #[arg(long, value_parser = ["xy", "xz", "yz", "iso"])]
        view: Option<String>,
    },
    /// Serve a local page where the model is edited, checked, solved and drawn: a slider a
    /// param, a choice a branch, a field a default, traced curves, the generated module. The
    /// first line printed is the page's URL.
    Serve {
        /// The .gcs file (the only file the server reads; it writes none).
        file: PathBuf,
        /// The port to listen on; 0 picks a free one.
        #[arg(long, default_value_t = 8000)]
        port: u16,
        /// The address to listen on. The default answers this machine only.
        #[arg(long, default_value = "127.0.0.1")]
        host: String,
    },
    /// Print the assembly plan as steps a person can follow.
    Explain {
        /// The .gcs file.
        file: PathBuf,
    },
    /// Emit the Rust solver module.
    Compile {
        /// The .gcs file.
        file: PathBuf,
        /// Where to write it; standard output when absent.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// How `solve` is laid out: `auto` (flat below a plan of 2,048 steps, tabled from
        /// there), `flat` (one straight function) or `tabled` (a function per shape of
        /// repeated steps, and tables of their data).
        #[arg(long, default_value = "auto", value_parser = form)]
        form: Form,
    },
    /// Print the plan's stable text dump.
    Plan {
        /// The .gcs file.
        file: PathBuf,
    },
    /// Time the compiled plan against a numeric baseline (Newton on the raw constraint
    /// equations) over a sweep of the model's params: per-solve time, residual, branch flips,
    /// ratio, and the baseline's run time against error.
    Bench {
        /// The .gcs file.
        file: PathBuf,
        /// Points of the sweep (two or more: its two ends at least).
        #[arg(long, default_value_t = 100, value_parser = sweep_samples)]
        samples: usize,
        /// Print one JSON object.
        #[arg(long)]
        json: bool,
        /// Write the run time against error as an SVG plot.
        #[arg(long, value_name = "FILE.svg")]
        plot: Option<PathBuf>,
        /// Time the interpreter, without building the generated solver.
        #[arg(long)]
        interpreted: bool,
        /// Give the baseline dense linear algebra at any size (as numeric solvers with dense
        /// factorisations have), instead of sparse above 120 unknowns.
        #[arg(long)]
        dense: bool,
        /// How the generated solver's `solve` is laid out, as for `gcs compile`.
        #[arg(long, default_value = "auto", value_parser = form)]
        form: Form,
    },
}

/// A `--form` value.
fn form(text: &str) -> Result<Form, String> {
    match text {
        "auto" => Ok(Form::Auto),
        "flat" => Ok(Form::Flat),
        "tabled" => Ok(Form::Tabled),
        _ => Err(format!("`{text}` is not a form: auto, flat or tabled")),
    }
}

fn main() -> ExitCode {
    no_huge_pages();
    let cli = Cli::parse();
    let color = match cli.color.as_str() {
        "always" => termcolor::ColorChoice::Always,
        "never" => termcolor::ColorChoice::Never,
        _ if std::env::var_os("NO_COLOR").is_some() => termcolor::ColorChoice::Never,
        _ if !std::io::IsTerminal::is_terminal(&std::io::stderr()) => termcolor::ColorChoice::Never,
        _ => termcolor::ColorChoice::Auto,
    };
    match cli.command {
        Command::Check { file, deny } => check(&file, &deny, color),
        Command::Solve {
            file,
            set,
            branch,
            default,
            json,
            all,
            all_solutions,
            deny,
            least_motion,
        } => solve(
            &file,
            (&set, &branch, &default),
            (json, all, all_solutions),
            (&deny, least_motion == "global"),
            color,
        ),
        Command::Compile { file, output, form } => with_analysis(&file, color, |c| {
            let code = match gcs_compiler::codegen::generate_as(&c.model, &c.analysis.plan, form) {
                Ok(code) => gcs_compiler::codegen::format(&code),
                Err(why) => {
                    eprintln!(
                        "error: `{}` cannot be laid out as tables: {why}",
                        file.display()
                    );
                    return ExitCode::from(1);
                }
            };
            match output {
                Some(path) => match std::fs::write(&path, code) {
                    Ok(()) => ExitCode::SUCCESS,
                    Err(e) => {
                        eprintln!("error: cannot write `{}`: {e}", path.display());
                        ExitCode::from(2)
                    }
                },
                None => {
                    out!("{code}");
                    ExitCode::SUCCESS
                }
            }
        }),
        Command::Bench {
            file,
            samples,
            json,
            plot,
            interpreted,
            dense,
            form,
        } => bench(
            &file,
            samples,
            json,
            plot.as_deref(),
            (interpreted, dense, form),
            color,
        ),
        Command::Draw {
            file,
            output,
            set,
            branch,
            default,
            sweep,
            trace,
            animate,
            view,
        } => draw(
            &file,
            output.as_deref(),
            (&set, &branch, &default),
            Drawn {
                sweep: sweep.as_deref(),
                trace: &trace,
                animate,
                view: view.as_deref(),
            },
            color,
        ),
        Command::Serve { file, port, host } => serve::run(&file, &host, port),
        Command::Explain { file } => with_analysis(&file, color, |c| {
            out!(
                "{}",
                gcs_compiler::explain::explain(&c.model, &c.analysis.plan)
            );
            ExitCode::SUCCESS
        }),
        Command::Plan { file } => match compile(&file, color) {
            // The dump is printed even when the plan is incomplete: it shows how far the
            // analysis got.
            Ok(c) => {
                out!("{}", c.analysis.plan.dump(&c.model));
                if c.has_errors() {
                    ExitCode::FAILURE
                } else {
                    ExitCode::SUCCESS
                }
            }
            Err(stop) => stop.exit(),
        },
    }
}

/// Why a command stops before the model has a plan.
enum Stop {
    /// The model did not load (its diagnostics are printed), or could not be read.
    Exit(ExitCode),
    /// The model loaded but has no plan (its warnings are printed).
    Unanalysed(Box<Unanalysed>),
}

impl Stop {
    /// The exit code, saying why there is no plan.
    fn exit(self) -> ExitCode {
        match self {
            Stop::Exit(code) => code,
            Stop::Unanalysed(u) => {
                eprintln!("error: {}", u.error);
                ExitCode::FAILURE
            }
        }
    }
}

/// Reads a model and takes it through the pipeline (load, analyse, validate, report),
/// printing its diagnostics.
fn compile(path: &Path, color: termcolor::ColorChoice) -> Result<Compiled, Stop> {
    compile_hiding(path, color, |_| false)
}

/// [`compile`], printing the diagnostics but those `hide` says a command says itself.
fn compile_hiding(
    path: &Path,
    color: termcolor::ColorChoice,
    hide: fn(&Diagnostic) -> bool,
) -> Result<Compiled, Stop> {
    let name = path.display().to_string();
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("error: cannot read `{name}`: {e}");
            return Err(Stop::Exit(ExitCode::from(2)));
        }
    };
    match gcs_compiler::compile(&name, &bytes) {
        Ok(c) => {
            if c.diagnostics.iter().any(hide) {
                let shown: Vec<Diagnostic> = (c.diagnostics.iter())
                    .filter(|d| !hide(d))
                    .cloned()
                    .collect();
                emit(&c.source, &shown, color);
            } else {
                emit(&c.source, &c.diagnostics, color);
            }
            Ok(c)
        }
        Err(CompileError::Load(r)) => {
            emit(&r.source, &r.diagnostics, color);
            eprintln!("error: {}", shared::not_loaded(&name, &r.diagnostics));
            Err(Stop::Exit(ExitCode::FAILURE))
        }
        Err(CompileError::Analysis(u)) => {
            emit(&u.source, &u.diagnostics, color);
            Err(Stop::Unanalysed(u))
        }
    }
}

/// Takes a model through the pipeline; runs `then` on a model that can be solved.
fn with_analysis(
    path: &Path,
    color: termcolor::ColorChoice,
    then: impl FnOnce(&Compiled) -> ExitCode,
) -> ExitCode {
    with_analysis_hiding(path, color, |_| false, then)
}

/// [`with_analysis`], not printing the diagnostics `hide` says the command says itself.
fn with_analysis_hiding(
    path: &Path,
    color: termcolor::ColorChoice,
    hide: fn(&Diagnostic) -> bool,
    then: impl FnOnce(&Compiled) -> ExitCode,
) -> ExitCode {
    match compile_hiding(path, color, hide) {
        Ok(c) if c.has_errors() => {
            eprintln!("error: could not solve `{}`", path.display());
            ExitCode::FAILURE
        }
        Ok(c) => {
            let code = then(&c);
            exit_without_freeing(c);
            code
        }
        Err(stop) => stop.exit(),
    }
}

/// Ends a compiled model's life without freeing it, as the process exits next: freeing a large
/// model's arenas and plan an allocation at a time is measurable (0.1 s at 100,000 points).
fn exit_without_freeing(c: Compiled) {
    std::mem::forget(c);
}

/// The warnings `--deny` makes errors, each for the commands that take it.
const DENIABLE: [(&str, &str); 2] = [
    ("under-constrained", "check"),
    ("sketch-branch", "check and solve"),
];

/// The first of `deny` that `command` cannot make an error, said as an error.
fn not_deniable(deny: &[String], command: &str) -> Option<String> {
    let other = deny.iter().find(|d| {
        !DENIABLE
            .iter()
            .any(|(w, by)| w == d && by.contains(command))
    })?;
    let names: Vec<&str> = (DENIABLE.iter())
        .filter(|(_, by)| by.contains(command))
        .map(|(w, _)| *w)
        .collect();
    Some(format!(
        "`--deny {other}`: the warnings that can be denied are: {}",
        names.join(", ")
    ))
}

/// Prints the warning of a solve that could not keep the sketch's branches, if it changed
/// one; with `deny`, then an error: whether that stops the command.
fn changed_branches(
    c: &Compiled,
    plan: &gcs_compiler::plan::Plan,
    kept: &gcs_compiler::solve::Kept,
    (set, branch): (&[String], &[String]),
    deny: bool,
    color: termcolor::ColorChoice,
) -> bool {
    if let Some(ended) = gcs_compiler::report::sketch_assembly_ended(&c.model, plan, &kept.solution)
    {
        emit(&c.source, &[ended], color);
        if deny {
            eprintln!(
                "error: `{}` cannot be solved on the sketch's assembly, and `--deny sketch-branch` makes that an error",
                c.source.name()
            );
            return true;
        }
    }
    if !kept.changed() {
        return false;
    }
    let given = if branch.is_empty() {
        ""
    } else {
        "(and those given)"
    };
    let params = match (c.model.params.is_empty(), set.is_empty()) {
        (true, _) => "",
        (false, true) => "with the default params",
        (false, false) => "with the params given",
    };
    let at = [given, params]
        .iter()
        .filter(|w| !w.is_empty())
        .copied()
        .collect::<Vec<_>>()
        .join(" ");
    let warning = gcs_compiler::report::sketch_branches(&c.model, plan, kept, &at);
    emit(&c.source, &[warning], color);
    if deny {
        eprintln!(
            "error: `{}` cannot be solved on the sketch's branches, and `--deny sketch-branch` makes that an error",
            c.source.name()
        );
    }
    deny
}

fn solve(
    path: &Path,
    (set, branch, default): (&[String], &[String], &[String]),
    (json, all, all_solutions): (bool, bool, bool),
    (deny, global): (&[String], bool),
    color: termcolor::ColorChoice,
) -> ExitCode {
    if let Some(why) = not_deniable(deny, "solve") {
        eprintln!("error: {why}");
        return ExitCode::from(2);
    }
    // The pipeline's warning of the sketch's branches at the default params: a solve says its
    // own, at the params it solves with (every assembly lists its own `branches_changed`).
    let hide = gcs_compiler::report::is_sketch_branches;
    with_analysis_hiding(path, color, hide, |c| {
        let (model, analysis) = (&c.model, &c.analysis);
        let shared::Inputs {
            params,
            branches,
            defaults,
        } = match shared::inputs(model, analysis, set, branch, default) {
            Ok(i) => i,
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        };
        // With `output` statements, only what they need is computed, as in a compiled solver.
        let all_geoms: std::collections::BTreeSet<_> =
            model.top_level().map(|(id, _)| id).collect();
        // Without outputs, pruning keeps everything: the plan is used as it is, not copied.
        let (pruned, scope) = if all || model.outputs.is_empty() {
            (None, all_geoms)
        } else {
            let (plan, scope) = gcs_compiler::prune::prune(model, &analysis.plan);
            (Some(plan), scope)
        };
        let plan = pruned.as_ref().unwrap_or(&analysis.plan);
        // Each branch's index in the whole plan (the first, by name), looked up once a kept
        // branch: a scan each made a solve quadratic in its branches.
        let mut whole: rustc_hash::FxHashMap<&str, usize> = rustc_hash::FxHashMap::default();
        whole.reserve(analysis.plan.branches.len());
        for (i, b) in analysis.plan.branches.iter().enumerate() {
            whole.entry(b.name.as_str()).or_insert(i);
        }
        let mut chosen = Vec::new();
        for b in &plan.branches {
            let i = whole.get(b.name.as_str()).copied().unwrap_or(0);
            chosen.push(branches.get(i).copied().unwrap_or(b.default));
        }
        for (b, i) in analysis.plan.branches.iter().zip(&branches) {
            let given = branch
                .iter()
                .any(|s| s.split_once('=').is_some_and(|(n, _)| n.trim() == b.name));
            if given && !plan.branches.iter().any(|x| x.name == b.name) {
                eprintln!(
                    "note: branch `{}` = {i} does not affect the outputs; pass --all to solve everything",
                    b.name
                );
            }
        }
        // Each kept default's value, by name (pruning renumbers them).
        let kept_defaults: Vec<f64> = (plan.defaults.iter())
            .map(|d| {
                (analysis.plan.defaults.iter())
                    .position(|w| w.name == d.name)
                    .map_or(d.sketch, |i| defaults[i])
            })
            .collect();
        if all_solutions {
            let found = gcs_compiler::all::solve_all(model, plan, &scope, &params, &kept_defaults);
            if found.solutions.is_empty() {
                // No assembly: say why, as a plain solve on the sketch's branches does.
                if json {
                    outln!("{}", found.to_json());
                }
                eprintln!(
                    "error: no real assembly{}",
                    if found.complete {
                        ""
                    } else {
                        " found (the search is not exhaustive)"
                    }
                );
                let solved = shared::solve(
                    model,
                    plan,
                    &scope,
                    (&params, &chosen, &kept_defaults),
                    !default.is_empty(),
                    &shared::held(plan, branch),
                );
                if let Err(e) = solved {
                    for line in shared::failure(model, plan, &params, &kept_defaults, chosen, &e) {
                        eprintln!("error: {line}");
                    }
                }
                return ExitCode::FAILURE;
            }
            if json {
                outln!("{}", found.to_json());
            } else {
                for (k, s) in found.solutions.iter().enumerate() {
                    outln!("solution {}:", k + 1);
                    out!("{}", gcs_compiler::report::solution_text(s));
                }
                outln!(
                    "{} real assembl{}{}",
                    found.solutions.len(),
                    if found.solutions.len() == 1 {
                        "y"
                    } else {
                        "ies"
                    },
                    if found.complete {
                        ""
                    } else {
                        " found (the search is not exhaustive)"
                    }
                );
            }
            return ExitCode::SUCCESS;
        }
        // Given no defaults, an iterated plan returns the assembly that moves least.
        let solved = shared::solve(
            model,
            plan,
            &scope,
            (&params, &chosen, &kept_defaults),
            !default.is_empty(),
            &shared::held(plan, branch),
        );
        match solved {
            Ok(kept) => {
                let denied = deny.iter().any(|d| d == "sketch-branch");
                if changed_branches(c, plan, &kept, (set, branch), denied, color) {
                    return ExitCode::FAILURE;
                }
                let mut solution = kept.solution;
                if global {
                    solution = match least_overall(model, plan, &scope, &params, &solution, default)
                    {
                        Ok(s) => s,
                        Err(e) => {
                            eprintln!("error: {e}");
                            return ExitCode::FAILURE;
                        }
                    };
                }
                if json {
                    outln!("{}", solution.to_json());
                } else {
                    out!("{}", gcs_compiler::report::solution_text(&solution));
                }
                ExitCode::SUCCESS
            }
            Err(e) => {
                for line in shared::failure(model, plan, &params, &kept_defaults, chosen, &e) {
                    eprintln!("error: {line}");
                }
                ExitCode::FAILURE
            }
        }
    })
}

/// `--least-motion global`: the free defaults of `solution` (on its branches) chosen together
/// to move the points least from the sketch, those given by `--default` kept.
fn least_overall(
    model: &gcs_lang::Model,
    plan: &gcs_compiler::plan::Plan,
    scope: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
    params: &[f64],
    solution: &gcs_compiler::solution::Solution,
    given: &[String],
) -> Result<gcs_compiler::solution::Solution, gcs_runtime::error::SolveError> {
    let branches: Vec<usize> = (plan.branches.iter())
        .map(|b| {
            (solution.branches.iter())
                .find(|(n, _)| *n == b.name)
                .map_or(b.default, |(_, i)| *i)
        })
        .collect();
    let defaults: Vec<f64> = (plan.defaults.iter())
        .map(|d| {
            (solution.defaults.iter())
                .find(|(n, _)| *n == d.name)
                .map_or(d.sketch, |(_, v)| *v)
        })
        .collect();
    let held: Vec<bool> = (plan.defaults.iter())
        .map(|d| {
            given
                .iter()
                .any(|g| g.split_once('=').is_some_and(|(n, _)| n.trim() == d.name))
        })
        .collect();
    gcs_compiler::motion::globally_least(model, plan, scope, params, &branches, &defaults, &held)
}

/// What `gcs draw` draws beside the model: its sweep, traces, animation and view.
struct Drawn<'a> {
    sweep: Option<&'a str>,
    trace: &'a [String],
    animate: bool,
    view: Option<&'a str>,
}

/// `gcs draw`: solves the model (at every sample of a sweep), draws it, and writes the SVG.
fn draw(
    path: &Path,
    output: Option<&Path>,
    (set, branch, default): (&[String], &[String], &[String]),
    drawn: Drawn<'_>,
    color: termcolor::ColorChoice,
) -> ExitCode {
    use gcs_compiler::draw;
    if drawn.sweep.is_none() {
        let needs = if drawn.trace.is_empty() {
            drawn.animate.then_some("--animate")
        } else {
            Some("--trace")
        };
        if let Some(flag) = needs {
            eprintln!(
                "error: `{flag}` plays a sweep: give one with `--sweep NAME=FROM..TO[:STEPS]`"
            );
            return ExitCode::from(2);
        }
    }
    // Drawn at one position, the model is solved as `gcs solve` solves it, and says so.
    let hide: fn(&Diagnostic) -> bool = if drawn.sweep.is_some() {
        |_| false
    } else {
        gcs_compiler::report::is_sketch_branches
    };
    with_analysis_hiding(path, color, hide, |c| {
        let (model, analysis) = (&c.model, &c.analysis);
        let view = match (model.space, drawn.view) {
            (_, None) => draw::View::default(),
            (gcs_lang::model::Space::D2, Some(v)) if v != "xy" => {
                eprintln!(
                    "error: `--view {v}`: `{}` is a 2d model, drawn in its plane (xy)",
                    path.display()
                );
                return ExitCode::from(2);
            }
            (_, Some(v)) => draw::View::named(v).unwrap_or_default(),
        };
        for t in drawn.trace {
            if let Some(e) = draw::trace_error(model, t) {
                eprintln!("error: `--trace {t}`: {e}");
                return ExitCode::from(2);
            }
        }
        let sweep = match drawn.sweep.map(|s| (s, draw::Sweep::parse(model, s))) {
            None => None,
            Some((_, Ok(s))) => Some(s),
            Some((s, Err(e))) => {
                eprintln!("error: `--sweep {s}`: {e}");
                return ExitCode::from(2);
            }
        };
        let shared::Inputs {
            params,
            branches,
            defaults,
        } = match shared::inputs(model, analysis, set, branch, default) {
            Ok(i) => i,
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        };
        // Everything is drawn: the whole plan, whatever the `output` statements say.
        let plan = &analysis.plan;
        let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        let given = !default.is_empty();
        let (shown, samples) = match &sweep {
            None => {
                let held = shared::held(plan, branch);
                let solved = shared::solve(
                    model,
                    plan,
                    &scope,
                    (&params, &branches, &defaults),
                    given,
                    &held,
                );
                match solved {
                    Ok(kept) => {
                        changed_branches(c, plan, &kept, (set, branch), false, color);
                        (kept.solution, Vec::new())
                    }
                    Err(e) => {
                        for line in shared::failure(model, plan, &params, &defaults, branches, &e) {
                            eprintln!("error: {line}");
                        }
                        return ExitCode::FAILURE;
                    }
                }
            }
            Some(sweep) => {
                let solved = draw::sweep::solve(
                    model, plan, &scope, &params, &branches, &defaults, given, sweep,
                );
                let failed: Vec<(f64, String)> = (sweep.values.iter().zip(&solved))
                    .filter_map(|(v, s)| s.as_ref().err().map(|e| (*v, e.to_string())))
                    .collect();
                let Some(shown) = solved.iter().find_map(|s| s.as_ref().ok()).cloned() else {
                    eprintln!(
                        "error: no sample of `--sweep {}` solves; at {} = {}: {}",
                        drawn.sweep.unwrap_or_default(),
                        sweep.name,
                        sweep.values[0],
                        failed.first().map_or("", |f| f.1.as_str())
                    );
                    return ExitCode::FAILURE;
                };
                if let Some((v, e)) = failed.first() {
                    eprintln!(
                        "note: {} of {} samples did not solve, and leave gaps; the first, at {} = {v}: {e}",
                        failed.len(),
                        solved.len(),
                        sweep.name
                    );
                }
                (shown, solved.into_iter().map(Result::ok).collect())
            }
        };
        let options = draw::Options {
            view,
            traces: drawn.trace.to_vec(),
            animate: drawn.animate,
        };
        let drawing = match draw::draw(model, &shown, &samples, &options) {
            Ok(d) => d,
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        };
        match output {
            Some(out) => match std::fs::write(out, &drawing.svg) {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("error: cannot write `{}`: {e}", out.display());
                    ExitCode::from(2)
                }
            },
            None => {
                out!("{}", drawing.svg);
                ExitCode::SUCCESS
            }
        }
    })
}

/// `--samples`: a sweep has its two ends at least.
fn sweep_samples(text: &str) -> Result<usize, String> {
    match text.parse::<usize>() {
        Ok(n) if n >= 2 => Ok(n),
        Ok(n) => Err(format!(
            "a sweep has two samples or more (its two ends), not {n}"
        )),
        Err(e) => Err(e.to_string()),
    }
}

fn bench(
    path: &Path,
    samples: usize,
    json: bool,
    plot: Option<&std::path::Path>,
    (interpreted, dense, form): (bool, bool, Form),
    color: termcolor::ColorChoice,
) -> ExitCode {
    use gcs_bench::baseline::Linear;
    use gcs_bench::bench;
    with_analysis(path, color, |c| {
        let (model, analysis) = (&c.model, &c.analysis);
        let (plan, scope) = gcs_compiler::prune::prune(model, &analysis.plan);
        let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
        let sweep = bench::sweep(model, samples);
        // `GCS_BENCH_BUDGET_NS` sets the repeated solves of each sample, on both sides (tests set 1).
        let mut settings = bench::Settings {
            linear: if dense { Linear::Dense } else { Linear::Auto },
            ..bench::Settings::default()
        };
        if let Some(b) = std::env::var("GCS_BENCH_BUDGET_NS")
            .ok()
            .and_then(|b| b.parse().ok())
        {
            settings.budget_ns = b;
        }
        let mut compiled = None;
        if !interpreted {
            let code = match gcs_compiler::codegen::generate_as(model, &analysis.plan, form) {
                Ok(code) => gcs_compiler::codegen::format(&code),
                Err(why) => {
                    eprintln!(
                        "error: `{}` cannot be laid out as tables: {why}",
                        path.display()
                    );
                    return ExitCode::from(1);
                }
            };
            let names: Vec<String> = model.params.iter().map(|(_, p)| p.name.clone()).collect();
            let named: Vec<(String, usize)> = plan
                .branches
                .iter()
                .map(|b| (b.name.clone(), b.default))
                .collect();
            match generated::run(path, &code, &names, &named, &sweep, settings.budget_ns) {
                Ok(answers) => {
                    let mut run = bench::CompiledRun {
                        kind: "generated",
                        ns: Vec::new(),
                        solutions: Vec::new(),
                        restarts: 0,
                    };
                    for (answer, params) in answers.into_iter().zip(&sweep.params) {
                        run.ns.push(answer.ns);
                        run.restarts += usize::from(answer.restarted);
                        run.solutions.push(answer.values.map(|v| {
                            let mut s = gcs_compiler::solution::Solution {
                                points: v.points,
                                vectors: v.vectors,
                                scalars: v.scalars,
                                defaults: v.defaults,
                                ..Default::default()
                            };
                            s.max_residual =
                                gcs_compiler::verify::max_residual_in(model, &s, params, &scope);
                            s
                        }));
                    }
                    compiled = Some(run);
                }
                Err(why) => eprintln!("note: timing the interpreter instead: {why}"),
            }
        }
        let compiled = compiled.unwrap_or_else(|| {
            bench::interpreted(model, &plan, &scope, &branches, &sweep, settings.budget_ns)
        });
        // Each whole-plan branch at its kept branch's index (the first, by name), else at its
        // default: through a map, as in `solve`.
        let mut kept: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
        for (i, b) in plan.branches.iter().enumerate() {
            kept.entry(b.name.as_str()).or_insert(i);
        }
        let whole: Vec<usize> = analysis
            .plan
            .branches
            .iter()
            .map(|b| {
                kept.get(b.name.as_str())
                    .map_or(b.default, |&i| branches[i])
            })
            .collect();
        let report = match bench::run(model, &analysis.plan, &whole, sweep, compiled, &settings) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("error: cannot bench `{}`: {e}", path.display());
                return ExitCode::FAILURE;
            }
        };
        if let Some(plot) = plot {
            if let Err(e) = std::fs::write(plot, report.to_svg()) {
                eprintln!("error: cannot write `{}`: {e}", plot.display());
                return ExitCode::from(2);
            }
        }
        if json {
            outln!("{}", report.to_json());
        } else {
            out!("{}", report.to_text());
        }
        ExitCode::SUCCESS
    })
}

fn check(path: &Path, deny: &[String], color: termcolor::ColorChoice) -> ExitCode {
    if let Some(why) = not_deniable(deny, "check") {
        eprintln!("error: {why}");
        return ExitCode::from(2);
    }
    let denied = |w: &str| deny.iter().any(|d| d == w);
    match compile(path, color) {
        Ok(c) if c.has_errors() => {
            let name = path.display().to_string();
            eprintln!("error: {}", shared::analysis_errors(&name, &c.diagnostics));
            ExitCode::FAILURE
        }
        Ok(c) => {
            out!(
                "{}",
                gcs_compiler::report::check_report(&c.model, &c.analysis)
            );
            let mobility = c.analysis.free_defaults().len();
            if mobility > 0 && denied("under-constrained") {
                eprintln!(
                    "error: `{}` is under-constrained (mobility {mobility}), and `--deny under-constrained` makes that an error",
                    path.display()
                );
                return ExitCode::FAILURE;
            }
            let changed = (c.diagnostics.iter()).any(gcs_compiler::report::is_sketch_branches);
            if changed && denied("sketch-branch") {
                eprintln!(
                    "error: `{}` cannot be solved on the sketch's branches, and `--deny sketch-branch` makes that an error",
                    path.display()
                );
                return ExitCode::FAILURE;
            }
            exit_without_freeing(c);
            ExitCode::SUCCESS
        }
        // A model the analysis does not cover yet still gets its nominal count.
        Err(Stop::Unanalysed(u)) if matches!(u.error, AnalysisError::Uncovered(_)) => {
            out!("{}", gcs_compiler::nominal::report(&u.model));
            outln!("analysis: not run: {}", u.error);
            ExitCode::SUCCESS
        }
        Err(stop) => stop.exit(),
    }
}

/// Renders diagnostics to stderr, with colour when the terminal has it, as
/// [`gcs_lang::diagnostic::render_plain`] does in plain text: every error, the first warnings of
/// each kind, and a line counting the warnings left out. Buffered, as codespan writes a
/// diagnostic in many small pieces.
fn emit(source: &SourceFile, diags: &[Diagnostic], color: termcolor::ColorChoice) {
    use std::io::Write as _;
    let file = gcs_lang::diagnostic::codespan_file(source);
    let mut out = termcolor::BufferedStandardStream::stderr(color);
    let config = term::Config::default();
    let shown = gcs_lang::diagnostic::shown(diags);
    for d in shown.diagnostics {
        if term::emit_to_write_style(&mut out, &config, &file, &d.to_codespan()).is_err() {
            let _ = writeln!(out, "error: {}", d.message);
        }
    }
    for e in &shown.elided {
        if term::emit_to_write_style(&mut out, &config, &file, &e.to_codespan()).is_err() {
            let _ = writeln!(out, "warning: {}", e.message());
        }
    }
    let _ = out.flush();
}
