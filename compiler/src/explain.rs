//! `gcs explain`: the plan as a construction a person can follow, in the words of the papers'
//! plan fragments, with the model's names bound.

use crate::analysis::Analysis;
use crate::plan::Op;
use gcs_lang::Model;
use std::fmt::Write as _;

/// The explanation of an analysed model's plan.
pub fn explain(model: &Model, a: &Analysis) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "Assembly plan for {}", model.source.name());
    if let Some(g) = a.plan.grounded {
        let _ = writeln!(
            out,
            "\nNothing is fixed: {} is held at its sketch placement.",
            model.geoms[g].name
        );
    }
    if let Some((x, y)) = a.plan.grounded_direction {
        let _ = writeln!(
            out,
            "The direction from {} to {} is held as sketched: {} keeps to that line.",
            model.geoms[x].name, model.geoms[y].name, model.geoms[y].name
        );
    }
    let mut n = 0;
    for step in &a.plan.steps {
        if step.explain.is_empty() {
            continue;
        }
        n += 1;
        let _ = writeln!(out, "\n{n}. {}", step.explain);
        if let Op::Intersect { .. } = step.op {
            continue;
        }
    }
    let branches: Vec<_> = a.plan.branches.iter().filter(|b| b.count > 1).collect();
    if !branches.is_empty() {
        let _ = writeln!(out, "\nBranch variables:");
        for b in branches {
            let _ = writeln!(out, "- {} (default {}, the sketch's):", b.name, b.default);
            for (i, m) in b.meanings.iter().enumerate() {
                let _ = writeln!(out, "    {i}: {m}");
            }
        }
    }
    out
}
