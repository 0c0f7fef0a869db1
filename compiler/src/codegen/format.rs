//! rustfmt at the edge: the one place codegen runs a program, so that the library's other code
//! stays free of I/O.

/// The line after which a generated module holds data tables only, one entry a line: `format`
/// leaves them as written (rustfmt would keep them so too, at a cost that grows with the
/// tables of a large model).
pub const DATA: &str = "// The tables the code above reads: data, written one entry a line.";

/// The module formatted by `rustfmt`, when a `rustfmt` is on the path (as it is wherever cargo
/// is installed with its usual components); otherwise the module as generated. What follows
/// a [`DATA`] line is left as written.
pub fn format(code: &str) -> String {
    match code.find(DATA) {
        Some(at) => {
            let mut out = format_all(&code[..at]);
            out.push_str(&code[at..]);
            out
        }
        None => format_all(code),
    }
}

/// The whole of `code` formatted by `rustfmt`.
fn format_all(code: &str) -> String {
    use std::io::Write as _;
    use std::process::{Command, Stdio};
    let child = Command::new("rustfmt")
        .args(["--edition", "2021", "--emit", "stdout", "--quiet"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn();
    let Ok(mut child) = child else {
        return code.to_string();
    };
    if let Some(mut stdin) = child.stdin.take() {
        if stdin.write_all(code.as_bytes()).is_err() {
            return code.to_string();
        }
    }
    match child.wait_with_output() {
        Ok(out) if out.status.success() && !out.stdout.is_empty() => {
            String::from_utf8(out.stdout).unwrap_or_else(|_| code.to_string())
        }
        _ => code.to_string(),
    }
}
