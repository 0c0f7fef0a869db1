//! What the command-line tests share: running the `gcs` binary. Each test file that needs it
//! says `mod support;` (not every file uses every function).
#![allow(dead_code)]

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The repository's root, where the examples are.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Runs `gcs ARGS` in `dir`, without colour: exit code, stdout and stderr.
pub fn gcs_in<S: AsRef<OsStr>>(dir: &Path, args: &[S]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_gcs"))
        .current_dir(dir)
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("run gcs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs `gcs ARGS` from the repository's root.
pub fn gcs<S: AsRef<OsStr>>(args: &[S]) -> (i32, String, String) {
    gcs_in(&root(), args)
}
