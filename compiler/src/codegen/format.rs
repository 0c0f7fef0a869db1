//! rustfmt at the edge: the one place codegen runs a program, so that the library's other code
//! stays free of I/O.

/// The line after which a generated module holds data tables only, one entry a line: `format`
/// leaves them as written (rustfmt would keep them so too, at a cost that grows with the
/// tables of a large model).
pub const DATA: &str = "// The tables the code above reads: data, written one entry a line.";

/// A generated module: its text, and where its data tables start (recorded as they are
/// written, so that formatting never looks for them in the text).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Module {
    text: String,
    tables_at: usize,
}

impl Module {
    /// A module of code alone.
    pub(super) fn code(text: String) -> Module {
        let tables_at = text.len();
        Module { text, tables_at }
    }

    /// A module of `code` followed by its data tables `tables`, from a [`DATA`] line on.
    pub(super) fn with_tables(code: String, tables: &str) -> Module {
        let tables_at = code.len();
        let mut text = code;
        text.push_str(DATA);
        text.push_str("\n\n");
        text.push_str(tables);
        Module { text, tables_at }
    }
}

impl std::ops::Deref for Module {
    type Target = str;
    fn deref(&self) -> &str {
        &self.text
    }
}

impl std::fmt::Display for Module {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.text)
    }
}

impl From<Module> for String {
    fn from(m: Module) -> String {
        m.text
    }
}

/// The module formatted by `rustfmt`, when a `rustfmt` is on the path (as it is wherever cargo
/// is installed with its usual components); otherwise the module as generated. Its data
/// tables are left as written.
pub fn format(module: &Module) -> String {
    let (code, tables) = module.text.split_at(module.tables_at);
    let mut out = format_all(code);
    out.push_str(tables);
    out
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
