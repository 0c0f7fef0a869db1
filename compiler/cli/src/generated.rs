//! The generated solver of a model, built with cargo into a small driver program and run on a
//! bench sweep, for `gcs bench`.
//!
//! The driver crate lives under the workspace's `target/gcs-bench/`, depends on the runtime's
//! sources by path, and shares one target directory between models, so that only the first
//! bench compiles the runtime. Without cargo or the runtime's sources (an installed `gcs`), the
//! caller falls back to the interpreter.

use gcs_bench::bench::Sweep;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// What the driver reports for one sample: nanoseconds per solve, and the solution's values
/// by name, or the error's text.
pub struct Sample {
    /// Nanoseconds per solve.
    pub ns: f64,
    /// Points, vectors and scalars by dotted name; or the solve's error.
    pub values: Result<Values, String>,
    /// Whether the warm solve found no assembly near the last answer's defaults (the one it
    /// followed ended at a fold) and this answer is the sketch's, solved cold.
    pub restarted: bool,
}

/// A generated solution's values by dotted name.
#[derive(Default)]
pub struct Values {
    /// Points.
    pub points: Vec<(String, Vec<f64>)>,
    /// Unit vectors.
    pub vectors: Vec<(String, Vec<f64>)>,
    /// Dimensions.
    pub scalars: Vec<(String, f64)>,
    /// The defaults the solve converged to, by name (a solver with defaults).
    pub defaults: Vec<(String, f64)>,
}

/// The workspace this binary was built in, if its sources are still there.
fn workspace() -> Option<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = dir.canonicalize().ok()?;
    dir.join("runtime/Cargo.toml").is_file().then_some(dir)
}

/// The driver's main (its `time_per_call` repeats `gcs_bench::bench::time_per_call`: the
/// driver depends on the runtime alone, as generated code does): reads param names, then one line of values per sample, on stdin; prints
/// one line per sample: `ok NS` (`ok NS restart` when a warm sweep went on with the assembly
/// nearest its last answer, the one it followed having ended at a fold), then `d` and the
/// answer's defaults (a solver with defaults), `p NAME X Y`, `v NAME X Y`, `s NAME X` lines
/// and `end`; or `err NS TEXT`.
const DRIVER: &str = r#"
use std::io::BufRead as _;
use std::io::Write as _;

fn time_per_call(budget_ns: f64, mut solve: impl FnMut()) -> f64 {
    let start = std::time::Instant::now();
    solve();
    let once = start.elapsed().as_nanos() as f64;
    let reps = ((budget_ns / once.max(1.0)) as usize).clamp(1, 1_000_000);
    let start = std::time::Instant::now();
    for _ in 0..reps {
        solve();
    }
    start.elapsed().as_nanos() as f64 / reps as f64
}

fn main() {
    let stdin = std::io::stdin();
    let mut lines = stdin.lock().lines().map_while(Result::ok);
    let names: Vec<String> = lines
        .next()
        .unwrap_or_default()
        .split_whitespace()
        .map(String::from)
        .collect();
    let mut branches = solver::Branches::default();
    for arg in std::env::args().skip(1) {
        if let Some((name, index)) = arg.split_once('=') {
            let index: u8 = index.parse().unwrap_or(0);
            branches.set(name, index);
        }
    }
    // `gcs bench` passes its per-sample budget; without one, each sample is solved once.
    let budget: f64 = std::env::var("GCS_BENCH_BUDGET_NS")
        .ok()
        .and_then(|b| b.parse().ok())
        .unwrap_or(0.0);
    let out = std::io::stdout();
    let mut out = out.lock();
    for line in lines {
        let mut params = solver::Params::default();
        for (name, value) in names.iter().zip(line.split_whitespace()) {
            params.set(name, value.parse().unwrap_or(f64::NAN));
        }
        let defaults = solver::Defaults::default();
        SOLVE_TIMED
        let answer = solver::solve(&params, &branches, &defaults);
        RESTART
        match answer {
            Ok(s) => {
                let _ = writeln!(out, "ok {ns}{}", if restarted { " restart" } else { "" });
                DEFAULTS_LINE
                // Every coordinate, in either space.
                for (n, p) in s.points() {
                    let _ = write!(out, "p {n}");
                    for c in p.iter() {
                        let _ = write!(out, " {c:e}");
                    }
                    let _ = writeln!(out);
                }
                for (n, v) in s.vectors() {
                    let _ = write!(out, "v {n}");
                    for c in v.iter() {
                        let _ = write!(out, " {c:e}");
                    }
                    let _ = writeln!(out);
                }
                for (n, x) in s.scalars() {
                    let _ = writeln!(out, "s {n} {x:e}");
                }
                let _ = writeln!(out, "end");
            }
            Err(e) => {
                let _ = writeln!(out, "err {ns} {e}");
            }
        }
    }
}
"#;

/// Builds the generated solver `code` of the model at `path` and runs it on `sweep`, with the
/// given branch indices by name, repeating each sample's solve for `budget_ns` (see
/// `gcs_bench::bench::Settings`). `Err` says why it could not (the caller then interprets).
pub fn run(
    path: &Path,
    code: &str,
    param_names: &[String],
    branches: &[(String, usize)],
    sweep: &Sweep,
    budget_ns: f64,
) -> Result<Vec<Sample>, String> {
    let root = workspace().ok_or("the runtime's sources are not at hand")?;
    let stem = path
        .file_stem()
        .map_or("model".into(), |s| s.to_string_lossy().into_owned())
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect::<String>();
    let dir = root.join("target/gcs-bench").join(&stem);
    std::fs::create_dir_all(dir.join("src")).map_err(|e| e.to_string())?;
    let manifest = format!(
        "[package]\nname = \"gcs-bench-{}\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n\
         [dependencies]\ngcs-runtime = {{ path = {:?} }}\n\n\
         [profile.release]\ncodegen-units = 1\n\n[workspace]\n",
        stem.replace('_', "-"),
        root.join("runtime").display().to_string()
    );
    // A solver with defaults reports those it converged to: each sample starts from the last
    // answer's, as the baseline's Newton does (warm), and as a sweep that follows one assembly.
    // Where that assembly ends (a fold: no assembly near the last answer), the sweep goes on
    // with the assembly nearest the last answer, as a user's would, and says so.
    let driver = if code.contains("pub fn defaults(&self) -> Defaults") {
        DRIVER
            .replace(
                "DEFAULTS_LINE",
                "let _ = writeln!(out, \"d {:?}\", s.defaults());",
            )
            .replace(
                "RESTART",
                "let mut restarted = false;
        // The assembly followed ended (a fold): go on with the assembly nearest the last
        // answer, of every one `solve_all` finds here.
        let answer = match answer {
            Err(e) if e.kind == gcs_runtime::error::ErrorKind::NoAssemblyNear => {
                let all = solver::solve_all(&params, &defaults);
                let far = |s: &solver::Solution| -> f64 {
                    last.as_ref().map_or(0.0, |l: &Vec<f64>| {
                        let here = s.points();
                        let coords = here.iter().flat_map(|(_, p)| p.iter().copied());
                        coords.zip(l).map(|(a, b)| (a - b) * (a - b)).sum()
                    })
                };
                match all.iter().min_by(|a, b| far(a).total_cmp(&far(b))) {
                    Some(nearest) => {
                        restarted = true;
                        Ok(*nearest)
                    }
                    None => Err(e),
                }
            }
            answer => answer,
        };",
            )
            .replace(
                "let defaults = solver::Defaults::default();",
                "let defaults = warm;",
            )
            .replace(
                "Ok(s) => {",
                "Ok(s) => {\n                warm = s.defaults();\n                last = Some(s.points().iter().flat_map(|(_, p)| p.iter().copied()).collect());",
            )
            .replace(
                "let mut branches = solver::Branches::default();",
                "let mut branches = solver::Branches::default();\n    let mut warm = solver::Defaults::default();\n    let mut last: Option<Vec<f64>> = None;",
            )
    } else {
        DRIVER
            .replace("RESTART", "let restarted = false;")
            .replace("DEFAULTS_LINE", "")
    };
    // What is timed: `solve`, or a tabled solver's `solve_into` on a `Solution` made once
    // (its storage allocated before, as a caller that solves again and again keeps it).
    let timed = if code.contains("pub fn solve_into(") {
        "let mut solution = solver::Solution::new();
        let ns = time_per_call(budget, || {
            std::hint::black_box(solver::solve_into(
                std::hint::black_box(&params),
                &branches,
                &defaults,
                &mut solution,
            ).is_ok());
        });"
    } else {
        "let ns = time_per_call(budget, || {
            std::hint::black_box(solver::solve(
                std::hint::black_box(&params),
                &branches,
                &defaults,
            ).is_ok());
        });"
    };
    let driver = driver.replace("SOLVE_TIMED", timed);
    let main = format!("mod solver {{\n{code}\n}}\n{driver}");
    write_if_changed(&dir.join("Cargo.toml"), &manifest)?;
    write_if_changed(&dir.join("src/main.rs"), &main)?;
    if let Ok(lock) = std::fs::read_to_string(root.join("Cargo.lock")) {
        write_if_changed(&dir.join("Cargo.lock"), &lock)?;
    }
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let target = root.join("target/gcs-bench/target");
    let status = Command::new(&cargo)
        .args(["build", "--release", "--quiet", "--offline"])
        .current_dir(&dir)
        .env("CARGO_TARGET_DIR", &target)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .output()
        .map_err(|e| format!("cannot run cargo: {e}"))?;
    if !status.status.success() {
        return Err(format!(
            "cargo could not build the generated solver:\n{}",
            String::from_utf8_lossy(&status.stderr)
        ));
    }
    let exe = target
        .join("release")
        .join(format!("gcs-bench-{}", stem.replace('_', "-")));
    let mut child = Command::new(&exe)
        .args(branches.iter().map(|(n, i)| format!("{n}={i}")))
        .env("GCS_BENCH_BUDGET_NS", budget_ns.to_string())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot run {}: {e}", exe.display()))?;
    let mut input = param_names.join(" ");
    input.push('\n');
    for params in &sweep.params {
        let line: Vec<String> = params.iter().map(|v| format!("{v:e}")).collect();
        input.push_str(&line.join(" "));
        input.push('\n');
    }
    if let Some(mut stdin) = child.stdin.take() {
        stdin
            .write_all(input.as_bytes())
            .map_err(|e| e.to_string())?;
    }
    let output = child.wait_with_output().map_err(|e| e.to_string())?;
    parse(&String::from_utf8_lossy(&output.stdout), sweep.params.len())
}

fn write_if_changed(path: &Path, text: &str) -> Result<(), String> {
    if std::fs::read_to_string(path).is_ok_and(|old| old == text) {
        return Ok(());
    }
    std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display()))
}

/// Reads the driver's output.
fn parse(out: &str, samples: usize) -> Result<Vec<Sample>, String> {
    let mut result = Vec::new();
    let mut current: Option<(f64, Values)> = None;
    let mut restarted = false;
    let num = |s: Option<&str>| s.and_then(|v| v.parse::<f64>().ok()).unwrap_or(f64::NAN);
    for line in out.lines() {
        let mut words = line.split(' ');
        match words.next() {
            Some("ok") => {
                let ns = num(words.next());
                restarted = words.next() == Some("restart");
                current = Some((ns, Values::default()));
            }
            Some("err") => {
                let ns = num(words.next());
                let text: Vec<&str> = words.collect();
                result.push(Sample {
                    ns,
                    values: Err(text.join(" ")),
                    restarted: false,
                });
            }
            // `d Defaults { name: value, ... }`, the `Debug` form of the answer's defaults.
            Some("d") => {
                let Some((_, values)) = current.as_mut() else {
                    return Err(format!("unexpected driver output: {line}"));
                };
                let rest = line.split_once('{').map_or("", |(_, r)| r);
                for pair in rest.trim_end_matches('}').split(',') {
                    if let Some((name, value)) = pair.split_once(':') {
                        values
                            .defaults
                            .push((name.trim().to_string(), num(Some(value.trim()))));
                    }
                }
            }
            Some(kind @ ("p" | "v" | "s")) => {
                let Some((_, values)) = current.as_mut() else {
                    return Err(format!("unexpected driver output: {line}"));
                };
                let name = words.next().unwrap_or_default().to_string();
                let nums: Vec<f64> = words.map(|w| num(Some(w))).collect();
                match kind {
                    "p" => values.points.push((name, nums)),
                    "v" => values.vectors.push((name, nums)),
                    _ => values
                        .scalars
                        .push((name, nums.first().copied().unwrap_or(f64::NAN))),
                }
            }
            Some("end") => {
                if let Some((ns, values)) = current.take() {
                    result.push(Sample {
                        ns,
                        values: Ok(values),
                        restarted,
                    });
                }
            }
            _ => {}
        }
    }
    if result.len() != samples {
        return Err(format!(
            "the generated solver answered {} of {samples} samples",
            result.len()
        ));
    }
    Ok(result)
}
