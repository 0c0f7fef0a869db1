//! Fuzz target: what `gcs check` does (load, analyse, the DOF report or the nominal summary,
//! the diagnostics rendered) must never panic or hang on any bytes.

#![no_main]

use gcs_compiler::pipeline::{compile, CompileError};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    match compile("fuzz.gcs", data) {
        Ok(c) => {
            let _ = gcs_compiler::report::check_report(&c.model, &c.analysis);
            let _ = gcs_lang::diagnostic::render_plain(&c.source, &c.diagnostics);
        }
        Err(CompileError::Load(r)) => {
            let _ = gcs_lang::diagnostic::render_plain(&r.source, &r.diagnostics);
        }
        Err(CompileError::Analysis(u)) => {
            let _ = gcs_compiler::nominal::report(&u.model);
        }
    }
});
