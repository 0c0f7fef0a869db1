//! Generated solvers at build time, in the spirit of prost-build: a crate's `build.rs` compiles
//! its `.gcs` models into `OUT_DIR`, and the crate brings each one in with
//! `gcs_runtime::include_solver!`.
//!
//! ```no_run
//! // build.rs
//! fn main() -> Result<(), gcs_compiler::build::BuildError> {
//!     gcs_compiler::build::compile_models(&["models/fourbar.gcs"])
//! }
//! ```
//!
//! ```ignore
//! // src/lib.rs
//! pub mod fourbar {
//!     gcs_runtime::include_solver!("fourbar");
//! }
//! ```
//!
//! For each model, [`Builder::compile`] prints `cargo:rerun-if-changed=PATH`, loads and
//! analyses the model, and writes `OUT_DIR/<file stem>.rs`, only when its content changed (so
//! that an unchanged model does not rebuild the crate that includes it). A model with errors
//! fails the build: its diagnostics are rendered to stderr, as `gcs check` would print them, and
//! warnings become `cargo:warning` lines.
//!
//! This module is the one exception to "library crates do no I/O": a build script's interface
//! to cargo *is* its files, stdout and stderr.

use crate::codegen;
use crate::pipeline::{self, CompileError};
use std::fmt;
use std::path::{Path, PathBuf};

/// Compiles every model in `paths` into `OUT_DIR/<file stem>.rs`, with the default
/// [`Builder`]. Call it from a build script.
pub fn compile_models(paths: &[impl AsRef<Path>]) -> Result<(), BuildError> {
    Builder::new().compile(paths).map(|_| ())
}

/// Options of a build-script compilation; [`compile_models`] uses the defaults.
#[derive(Debug, Clone)]
pub struct Builder {
    out_dir: Option<PathBuf>,
    quiet: bool,
    form: codegen::Form,
}

impl Default for Builder {
    fn default() -> Builder {
        Builder {
            out_dir: None,
            quiet: false,
            form: codegen::Form::Auto,
        }
    }
}

/// What [`Builder::compile`] did with one model.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Generated {
    /// The model, as given.
    pub model: PathBuf,
    /// The generated module.
    pub file: PathBuf,
    /// Whether the file was written (false: it already held this content).
    pub written: bool,
}

impl Builder {
    /// A builder that writes into `OUT_DIR` and talks to cargo.
    pub fn new() -> Builder {
        Builder::default()
    }

    /// Writes into `dir` instead of the `OUT_DIR` environment variable.
    pub fn out_dir(mut self, dir: impl Into<PathBuf>) -> Builder {
        self.out_dir = Some(dir.into());
        self
    }

    /// Prints nothing on stdout (no `cargo:` lines) and no diagnostics on stderr; a failure's
    /// diagnostics are still in the returned [`BuildError`]. For use outside a build script.
    pub fn quiet(mut self, quiet: bool) -> Builder {
        self.quiet = quiet;
        self
    }

    /// Lays `solve` out in `form` ([`codegen::Form::Auto`] unless set: flat for a small plan,
    /// tabled for a large one).
    pub fn form(mut self, form: codegen::Form) -> Builder {
        self.form = form;
        self
    }

    /// Compiles every model in `paths`, in order. Every model is tried, so that one build
    /// reports the errors of all of them; nothing is written for a model with errors.
    pub fn compile(&self, paths: &[impl AsRef<Path>]) -> Result<Vec<Generated>, BuildError> {
        let out_dir = match &self.out_dir {
            Some(d) => d.clone(),
            None => std::env::var_os("OUT_DIR")
                .map(PathBuf::from)
                .ok_or(BuildError::NoOutDir)?,
        };
        // Two models with one stem would overwrite each other's module.
        let mut stems: Vec<(String, &Path)> = Vec::new();
        for p in paths {
            let p = p.as_ref();
            let stem = module_stem(p)?;
            if let Some((_, first)) = stems.iter().find(|(s, _)| *s == stem) {
                return Err(BuildError::DuplicateStem {
                    stem,
                    first: first.to_path_buf(),
                    second: p.to_path_buf(),
                });
            }
            stems.push((stem, p));
        }
        let mut generated = Vec::new();
        let mut failures = Vec::new();
        for (stem, path) in stems {
            if !self.quiet {
                // Before reading: a model that fails now is retried once it is edited.
                println!("cargo:rerun-if-changed={}", path.display());
            }
            match self.generate(path) {
                Ok(source) => {
                    let file = out_dir.join(format!("{stem}.rs"));
                    let written = write_if_changed(&file, &source)?;
                    generated.push(Generated {
                        model: path.to_path_buf(),
                        file,
                        written,
                    });
                }
                Err(failure) => {
                    if !self.quiet {
                        eprint!("{}", failure.diagnostics);
                    }
                    failures.push(failure);
                }
            }
        }
        if failures.is_empty() {
            Ok(generated)
        } else {
            Err(BuildError::Models(failures))
        }
    }

    /// Loads, analyses and generates one model; its warnings go to cargo.
    fn generate(&self, path: &Path) -> Result<String, ModelFailure> {
        let failure = |message: String, diagnostics: String| ModelFailure {
            path: path.to_path_buf(),
            message,
            diagnostics,
        };
        let name = path.display().to_string();
        let bytes =
            std::fs::read(path).map_err(|e| failure(format!("cannot read: {e}"), "".into()))?;
        let compiled = match pipeline::compile(&name, &bytes) {
            Ok(c) => c,
            Err(CompileError::Load(r)) => {
                return Err(failure(
                    error_count(&r.diagnostics),
                    gcs_lang::diagnostic::render_plain(&r.source, &r.diagnostics),
                ))
            }
            Err(CompileError::Analysis(u)) => {
                return Err(failure(
                    format!("cannot be analysed: {}", u.error),
                    gcs_lang::diagnostic::render_plain(&u.source, &u.diagnostics),
                ))
            }
        };
        let diags = &compiled.diagnostics;
        let rendered = gcs_lang::diagnostic::render_plain(&compiled.source, diags);
        if compiled.has_errors() {
            return Err(failure(error_count(diags), rendered));
        }
        if !self.quiet {
            // As the command line shows them: repeated warnings counted in one line.
            let shown = gcs_lang::diagnostic::shown(diags);
            for d in shown.diagnostics {
                let line = compiled.source.line(d.primary.span.start);
                println!("cargo:warning={name}:{line}: {}", d.message);
            }
            for e in &shown.elided {
                println!("cargo:warning={name}: {}", e.message());
            }
            if !diags.is_empty() {
                eprint!("{rendered}");
            }
        }
        codegen::generate_as(&compiled.model, &compiled.analysis.plan, self.form)
            .map(String::from)
            .map_err(|why| failure(format!("cannot be laid out as tables: {why}"), "".into()))
    }
}

/// "N errors", for a failure's one-line message.
fn error_count(diags: &[gcs_lang::Diagnostic]) -> String {
    match diags.iter().filter(|d| d.is_error()).count() {
        1 => "1 error".to_string(),
        n => format!("{n} errors"),
    }
}

/// The name of the module file a model compiles to: its file stem.
fn module_stem(path: &Path) -> Result<String, BuildError> {
    match path.file_stem().and_then(|s| s.to_str()) {
        Some(stem) if !stem.is_empty() => Ok(stem.to_string()),
        _ => Err(BuildError::BadStem {
            path: path.to_path_buf(),
        }),
    }
}

/// Writes `content` to `file` unless it already holds exactly that; returns whether it wrote.
fn write_if_changed(file: &Path, content: &str) -> Result<bool, BuildError> {
    if std::fs::read(file).is_ok_and(|old| old == content.as_bytes()) {
        return Ok(false);
    }
    std::fs::write(file, content).map_err(|source| BuildError::Write {
        path: file.to_path_buf(),
        source,
    })?;
    Ok(true)
}

/// Why a model did not compile.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ModelFailure {
    /// The model, as given.
    pub path: PathBuf,
    /// One line: "2 errors", "cannot read: ...", "cannot be analysed: ...".
    pub message: String,
    /// Its diagnostics, rendered as plain text (empty when there are none).
    pub diagnostics: String,
}

/// A build-script compilation that failed. Its `Debug` form is its `Display` form, so that a
/// build script's `main` returning `Result<(), BuildError>` fails with a readable message.
pub enum BuildError {
    /// No `OUT_DIR` in the environment (not run by cargo) and no [`Builder::out_dir`].
    NoOutDir,
    /// A model's path has no file stem in UTF-8 to name its module file after.
    BadStem {
        /// The model.
        path: PathBuf,
    },
    /// Two models would generate the same module.
    DuplicateStem {
        /// The module name.
        stem: String,
        /// The first model with it.
        first: PathBuf,
        /// The second.
        second: PathBuf,
    },
    /// A generated module could not be written.
    Write {
        /// The module file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Models that could not be compiled; their diagnostics were rendered to stderr.
    Models(Vec<ModelFailure>),
}

impl fmt::Display for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            BuildError::NoOutDir => write!(
                f,
                "OUT_DIR is not set: run from a build script, or give Builder::out_dir"
            ),
            BuildError::BadStem { path } => write!(
                f,
                "`{}`: the generated module is named after the file stem, which must be UTF-8",
                path.display()
            ),
            BuildError::DuplicateStem {
                stem,
                first,
                second,
            } => write!(
                f,
                "`{}` and `{}` would both generate `{stem}.rs`",
                first.display(),
                second.display()
            ),
            BuildError::Write { path, source } => {
                write!(f, "cannot write `{}`: {source}", path.display())
            }
            BuildError::Models(failures) => {
                let n = failures.len();
                let s = if n == 1 { "" } else { "s" };
                write!(f, "could not compile {n} gcs model{s}:")?;
                for m in failures {
                    write!(f, "\n  {}: {}", m.path.display(), m.message)?;
                }
                Ok(())
            }
        }
    }
}

impl fmt::Debug for BuildError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl std::error::Error for BuildError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            BuildError::Write { source, .. } => Some(source),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, SystemTime};

    const FOURBAR: &str = include_str!("../../examples/fourbar.gcs");

    /// A model in a fresh directory, and an output directory beside it.
    fn setup(name: &str, text: &str) -> (tempfile::TempDir, PathBuf, PathBuf) {
        let dir = tempfile::tempdir().expect("tempdir");
        let model = dir.path().join(name);
        std::fs::write(&model, text).expect("write model");
        let out = dir.path().join("out");
        std::fs::create_dir(&out).expect("out dir");
        (dir, model, out)
    }

    #[test]
    fn writes_the_module_once_and_leaves_it_alone_when_unchanged() {
        let (_dir, model, out) = setup("fourbar.gcs", FOURBAR);
        let builder = Builder::new().out_dir(&out).quiet(true);
        let first = builder.compile(&[&model]).expect("compiles");
        let file = out.join("fourbar.rs");
        assert_eq!(
            first,
            vec![Generated {
                model: model.clone(),
                file: file.clone(),
                written: true
            }]
        );
        let text = std::fs::read_to_string(&file).expect("generated");
        assert!(text.contains("@generated"), "{text}");
        assert!(text.contains("pub fn solve"), "{text}");

        // Backdate the file: a rewrite would move its mtime forward again.
        let old = SystemTime::now() - Duration::from_secs(3600);
        std::fs::File::options()
            .write(true)
            .open(&file)
            .and_then(|f| f.set_modified(old))
            .expect("set mtime");
        let second = builder.compile(&[&model]).expect("compiles again");
        assert!(!second[0].written);
        let mtime = std::fs::metadata(&file).and_then(|m| m.modified());
        assert_eq!(mtime.expect("mtime"), old);
        assert_eq!(std::fs::read_to_string(&file).expect("generated"), text);
    }

    #[test]
    fn rewrites_a_module_whose_content_differs() {
        let (_dir, model, out) = setup("fourbar.gcs", FOURBAR);
        let file = out.join("fourbar.rs");
        std::fs::write(&file, "// stale\n").expect("stale");
        let builder = Builder::new().out_dir(&out).quiet(true);
        assert!(builder.compile(&[&model]).expect("compiles")[0].written);
        let text = std::fs::read_to_string(&file).expect("generated");
        assert!(text.contains("@generated"));
    }

    #[test]
    fn a_bad_model_fails_with_its_diagnostics_and_writes_nothing() {
        let bad = "space 2d;\nfixed point A = (0, 0);\ncoincident(A, B);\n";
        let (_dir, model, out) = setup("bad.gcs", bad);
        let err = Builder::new()
            .out_dir(&out)
            .quiet(true)
            .compile(&[&model])
            .expect_err("fails");
        let BuildError::Models(failures) = &err else {
            panic!("unexpected error: {err}");
        };
        assert_eq!(failures.len(), 1);
        assert_eq!(failures[0].path, model);
        assert_eq!(failures[0].message, "1 error");
        assert!(failures[0].diagnostics.contains("error"));
        assert!(failures[0].diagnostics.contains("bad.gcs:3:"));
        assert!(failures[0].diagnostics.contains('B'));
        let message = err.to_string();
        assert!(
            message.starts_with("could not compile 1 gcs model:"),
            "{message}"
        );
        assert!(message.contains("bad.gcs: 1 error"), "{message}");
        assert!(!out.join("bad.rs").exists());
    }

    #[test]
    fn every_model_is_tried_before_failing() {
        let (dir, bad, out) = setup("bad.gcs", "space 2d;\npoint P = (0, 0)\n");
        let good = dir.path().join("fourbar.gcs");
        std::fs::write(&good, FOURBAR).expect("write model");
        let missing = dir.path().join("missing.gcs");
        let err = Builder::new()
            .out_dir(&out)
            .quiet(true)
            .compile(&[&bad, &good, &missing])
            .expect_err("fails");
        let BuildError::Models(failures) = &err else {
            panic!("unexpected error: {err}");
        };
        let failed: Vec<&Path> = failures.iter().map(|f| f.path.as_path()).collect();
        assert_eq!(failed, [bad.as_path(), missing.as_path()]);
        assert!(failures[1].message.starts_with("cannot read:"));
        assert!(out.join("fourbar.rs").exists());
    }

    #[test]
    fn needs_an_out_dir_and_distinct_stems() {
        let (dir, model, _out) = setup("fourbar.gcs", FOURBAR);
        if std::env::var_os("OUT_DIR").is_none() {
            let err = Builder::new().quiet(true).compile(&[&model]);
            assert!(matches!(err, Err(BuildError::NoOutDir)));
        }
        let other = dir.path().join("sub").join("fourbar.gcs");
        let err = Builder::new()
            .out_dir(dir.path())
            .quiet(true)
            .compile(&[&model, &other]);
        assert!(matches!(err, Err(BuildError::DuplicateStem { .. })));
        let err = Builder::new()
            .out_dir(dir.path())
            .quiet(true)
            .compile(&[".."]);
        assert!(matches!(err, Err(BuildError::BadStem { .. })));
    }
}
