//! `gcs explain`: the plan as a construction a person can follow, in the words of the papers'
//! plan fragments, with the model's names bound.

use crate::plan::{Op, Plan};
use gcs_lang::Model;
use std::collections::HashMap;
use std::fmt::Write as _;

/// The explanation of a model's plan.
pub fn explain(model: &Model, plan: &Plan) -> String {
    let mut out = String::new();
    let _ = writeln!(out, "Assembly plan for {}", model.source.name());
    if let Some(g) = plan.grounded {
        let _ = writeln!(
            out,
            "\nNothing is fixed: {} is held at its sketch placement.",
            model.geoms[g].name
        );
    }
    if let Some((x, y)) = plan.grounded_direction {
        let _ = writeln!(
            out,
            "The direction from {} to {} is held as sketched: {} keeps to that line.",
            model.geoms[x].name, model.geoms[y].name, model.geoms[y].name
        );
        if let Some(z) = plan.grounded_plane {
            let _ = writeln!(
                out,
                "The plane through {}, {} and {} is held as sketched: {} keeps to that plane.",
                model.geoms[x].name, model.geoms[y].name, model.geoms[z].name, model.geoms[z].name
            );
        }
    }
    // A run-time check says what implies it: the constraints (and fixed geoms) its step
    // rests on, traced through the plan.
    let checks: Vec<usize> = (plan.steps.iter().enumerate())
        .filter(|(_, s)| matches!(s.op, Op::Check { .. }))
        .map(|(i, _)| i)
        .collect();
    let implied_by: HashMap<usize, String> = (checks.iter().copied())
        .zip(plan.supports(model, &checks))
        .filter_map(|(i, s)| {
            let near = (plan.steps[i].op.constraint())
                .map_or_else(Default::default, |c| model.constraints[c].span);
            Some((i, crate::plan::support_words(model, &s, near)?))
        })
        .collect();
    let mut n = 0;
    for (i, step) in plan.steps.iter().enumerate() {
        if step.explain.is_empty() {
            continue;
        }
        n += 1;
        let text = match implied_by.get(&i) {
            Some(by) => step
                .explain
                .replace("implied by the steps before", &format!("implied by {by}")),
            None => step.explain.clone(),
        };
        let _ = writeln!(out, "\n{n}. {text}");
    }
    let branches: Vec<_> = plan.branches.iter().filter(|b| b.count > 1).collect();
    if !branches.is_empty() {
        let _ = writeln!(out, "\nBranch variables:");
        for b in branches {
            // Only a default the sketch reaches is the sketch's.
            let whose = if b.from_sketch {
                "the sketch's"
            } else {
                "the sketch does not reach it"
            };
            let _ = writeln!(out, "- {} (default {}, {whose}):", b.name, b.default);
            for (i, m) in b.meanings.iter().enumerate() {
                let _ = writeln!(out, "    {i}: {m}");
            }
        }
    }
    if !plan.defaults.is_empty() {
        let _ = writeln!(out, "\nDefaults:");
        for d in &plan.defaults {
            let _ = writeln!(
                out,
                "- {} (the sketch's {}): {}",
                d.name,
                crate::plan::fmt_f64(d.sketch),
                d.meaning
            );
        }
    }
    for it in &plan.iterations {
        let closes: Vec<&str> = (plan.closes(it).into_iter())
            .map(|c| model.constraints[c].name.as_str())
            .collect();
        let _ = writeln!(
            out,
            "Vary {} until {} close{}.",
            plan.varied(it).join(", "),
            closes.join(", "),
            if closes.len() == 1 { "s" } else { "" }
        );
        if let Some(words) = it.mode_words() {
            let _ = writeln!(
                out,
                "  From the sketch's defaults and branches it keeps the sketch's assembly mode ({words}), or says that mode has no assembly here; from other defaults it takes the root nearest them."
            );
        }
    }
    out
}
