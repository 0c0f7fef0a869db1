//! The nominal degrees-of-freedom count: each geom's DOF, each constraint's nominal share, and
//! their difference. It is what a count of equations and unknowns says, before the real
//! analysis finds which constraints are redundant and which motions stay free.

use gcs_lang::model::{GeomKind, Owner};
use gcs_lang::Model;
use std::fmt::Write as _;

/// One geom's line of the summary.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GeomRow {
    /// Its name.
    pub name: String,
    /// `fixed point`, `body`, ...
    pub kind: String,
    /// Its DOF (0 when fixed).
    pub dof: usize,
    /// Its members, for bodies.
    pub members: Vec<String>,
}

/// One constraint's line of the summary.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConstraintRow {
    /// The label or derived name.
    pub name: String,
    /// The statement as written.
    pub text: String,
    /// The DOF it nominally removes.
    pub removes: usize,
}

/// The nominal count of a model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Nominal {
    /// Every top-level geom.
    pub geoms: Vec<GeomRow>,
    /// Every constraint.
    pub constraints: Vec<ConstraintRow>,
    /// The sum of the geoms' DOF.
    pub total_dof: usize,
    /// The sum of what the constraints nominally remove.
    pub total_removed: usize,
}

impl Nominal {
    /// `total_dof - total_removed`, which may be negative.
    pub fn balance(&self) -> i64 {
        self.total_dof as i64 - self.total_removed as i64
    }
}

/// Counts a model's nominal DOF.
pub fn count(model: &Model) -> Nominal {
    let geoms: Vec<GeomRow> = model
        .top_level()
        .map(|(_, g)| {
            let dof = if g.fixed { 0 } else { g.kind.dof(model.space) };
            let kind = if g.fixed {
                format!("fixed {}", g.kind.keyword())
            } else {
                g.kind.keyword().to_string()
            };
            let members = if g.kind == GeomKind::Body {
                g.parts
                    .iter()
                    .filter(|&&p| matches!(model.geoms[p].owner, Owner::Member(_)))
                    .map(|&p| {
                        model.geoms[p]
                            .name
                            .rsplit('.')
                            .next()
                            .unwrap_or("")
                            .to_string()
                    })
                    .collect()
            } else {
                Vec::new()
            };
            GeomRow {
                name: g.name.clone(),
                kind,
                dof,
                members,
            }
        })
        .collect();
    let constraints: Vec<ConstraintRow> = model
        .constraints
        .iter()
        .map(|(id, c)| ConstraintRow {
            name: c.name.clone(),
            text: c.text.clone(),
            removes: model.nominal_dof_removed(id),
        })
        .collect();
    let total_dof = geoms.iter().map(|g| g.dof).sum();
    let total_removed = constraints.iter().map(|c| c.removes).sum();
    Nominal {
        geoms,
        constraints,
        total_dof,
        total_removed,
    }
}

/// The summary `gcs check` prints.
pub fn report(model: &Model) -> String {
    let n = count(model);
    let mut out = String::new();
    let plural = |k: usize, w: &str| format!("{k} {w}{}", if k == 1 { "" } else { "s" });
    let _ = writeln!(
        out,
        "{}: space {}, {}, {}, {}",
        model.source.name(),
        model.space,
        plural(model.params.len(), "param"),
        plural(n.geoms.len(), "geom"),
        plural(n.constraints.len(), "constraint"),
    );
    let name_w = column_width(&n.geoms, |g| &g.name);
    let kind_w = column_width(&n.geoms, |g| &g.kind);
    let _ = writeln!(out, "\ngeoms{:>w$}", "DOF", w = name_w + kind_w + 4);
    for g in &n.geoms {
        let _ = write!(
            out,
            "  {:name_w$}  {:kind_w$}  {:>3}",
            g.name, g.kind, g.dof
        );
        if !g.members.is_empty() {
            let _ = write!(out, "   members: {}", g.members.join(", "));
        }
        out.push('\n');
    }
    out.push_str(&constraints_table(&n));
    let _ = writeln!(
        out,
        "  (a count of equations against unknowns, not the analysis: it cannot see redundant \
         constraints or which motions stay free)"
    );
    out
}

/// The widest a table column grows. A longer entry (a name of a thousand characters) overflows
/// its column on its own row, and the table stays readable; `format!` could not pad to an
/// unbounded width anyway (widths past 65,535 panic).
pub const MAX_COLUMN_WIDTH: usize = 64;

/// The width of a table column: its widest entry in characters, never under four characters
/// and never over [`MAX_COLUMN_WIDTH`].
pub fn column_width<T>(rows: &[T], text: impl Fn(&T) -> &str) -> usize {
    rows.iter()
        .map(|r| text(r).chars().count())
        .max()
        .unwrap_or(0)
        .clamp(4, MAX_COLUMN_WIDTH)
}

/// The constraints table (each constraint with the DOF it nominally removes) and the nominal
/// total: shared by `check`'s nominal summary and its analysis report.
pub fn constraints_table(n: &Nominal) -> String {
    let mut out = String::new();
    let c_name_w = column_width(&n.constraints, |c| &c.name);
    let c_text_w = column_width(&n.constraints, |c| &c.text);
    let _ = writeln!(
        out,
        "\nconstraints{:>w$}",
        "removes",
        w = c_name_w + c_text_w + 2
    );
    for c in &n.constraints {
        let _ = writeln!(
            out,
            "  {:c_name_w$}  {:c_text_w$}  {:>7}",
            c.name, c.text, c.removes
        );
    }
    let _ = writeln!(
        out,
        "\nnominal DOF: {} - {} = {}",
        n.total_dof,
        n.total_removed,
        n.balance()
    );
    out
}
