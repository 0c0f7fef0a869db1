//! `solve_all` as one tree of the plan. Solving each combination of branch variables from the
//! start repeats, for every combination, the steps before its first intersection (a robot's
//! tool frame and wrist centre, eight times for a six-joint arm) and every intersection taken
//! before the last. Written as a tree instead, the steps before a branch variable's root is
//! taken run once, and a loop over that variable's roots opens there: each root's steps in a
//! closure, so that a failure in them (`?`, `return Err`) ends that root's assemblies only,
//! and each root working on copies of the frames its steps move. The leaves are the
//! combinations `solve` would solve one at a time, in another order; the list keeps each
//! assembly once by the same rule (`keep`).

use super::api::Layout;
use super::context::Context;
use super::names::Namer;
use super::solve::Solve;
use super::writer::Writer;
use crate::plan::BranchId;
use gcs_lang::model::GeomId;
use rustc_hash::FxHashSet as HashSet;

/// The state of writing `solve_all` as one tree of the plan.
#[derive(Default)]
pub(super) struct Forking {
    /// The branch variables whose every root is taken (more than one root, not symmetric).
    varied: HashSet<BranchId>,
    /// Those whose loop is open.
    forked: HashSet<BranchId>,
    /// Where each fork's copies of the frames it moves go: the byte in the steps' text (a
    /// line start) and the indent there.
    copies_at: Vec<(usize, usize)>,
    /// The frames moved before the first fork (entry 0), and after each fork up to the next.
    moved: Vec<HashSet<GeomId>>,
}

/// The body of `solve_all`'s outer closure, at `indent`, written as one tree of the plan
/// with a loop over the roots of each of `varied`; none when the plan is too long to write
/// flat (see `Solve::write_tree`), where `solve_all` solves each combination instead.
pub(super) fn tree(
    cx: &Context<'_>,
    layout: &Layout,
    varied: HashSet<BranchId>,
    indent: usize,
) -> Option<Writer> {
    let mut names = Namer::default();
    for reserved in [
        "params", "branches", "defaults", "tol", "solution", "found", "kept", "root",
    ] {
        names.reserve(reserved);
    }
    let mut s = Solve::new(cx, names);
    s.forking = Some(Forking {
        varied,
        ..Forking::default()
    });
    s.write_tree(indent, layout)
}

impl Solve<'_> {
    /// Before the root of `branch` is taken: in `solve_all`'s tree, the loop over its roots
    /// opens here, once per variable (a later step may read the same root again).
    pub(super) fn fork(&mut self, w: &mut Writer, branch: BranchId) {
        let Some(f) = self.forking.as_mut() else {
            return;
        };
        if !f.varied.contains(&branch) || !f.forked.insert(branch) {
            return;
        }
        let (cx, k) = (self.cx, branch.0 as usize);
        let var = &cx.plan.branches[k];
        let field = &cx.branches[k];
        let text = &cx.model.constraints[var.constraint].text;
        w.line("");
        w.comment(&format!(
            "Each root of `{text}` in turn (`{field}`), the steps above shared by all."
        ));
        w.open(&format!("for root in 0..{}u8 {{", var.count));
        // Every field given: a struct update would be clippy's `needless_update`.
        let rest = if cx.branches.len() > 1 {
            ", ..*branches"
        } else {
            ""
        };
        w.line(&format!(
            "let branches = &Branches {{ {field}: root{rest} }};"
        ));
        f.moved.push(std::mem::take(&mut self.frame_writes));
        f.copies_at.push((w.out.len(), w.indent));
        w.comment("A failure ends this root's assemblies only.");
        w.open("let _ = (|| -> Result<(), SolveError> {");
    }

    /// Whether `solve_all`'s tree takes every root of `branch`: an op whose roots cost apiece
    /// (a quartic's polished) works out all of them, not only the branch's.
    pub(super) fn varies(&self, branch: BranchId) -> bool {
        (self.forking.as_ref()).is_some_and(|f| f.varied.contains(&branch))
    }

    /// Whether a fork is open: a dimension set here is bound anew, as each root's own.
    pub(super) fn in_fork(&self) -> bool {
        (self.forking.as_ref()).is_some_and(|f| !f.forked.is_empty())
    }

    /// Closes `solve_all`'s tree after its leaf, each fork's closure and loop, and writes in
    /// each fork its copies of the frames moved after it (before the next fork, which copies
    /// its own): only the frames moved before the first fork are `mut` where declared.
    pub(super) fn close_forks(&mut self, w: &mut Writer) {
        let Some(mut f) = self.forking.take() else {
            return;
        };
        for _ in &f.copies_at {
            w.line("Ok(())");
            w.close("})();");
            w.close("}");
        }
        f.moved.push(std::mem::take(&mut self.frame_writes));
        self.frame_writes = f.moved.first().cloned().unwrap_or_default();
        for (k, &(at, indent)) in f.copies_at.iter().enumerate().rev() {
            let mut moved: Vec<GeomId> = f.moved[k + 1].iter().copied().collect();
            moved.sort();
            let mut copies = Writer::at(indent);
            for g in moved {
                let frame = self.frame(g);
                copies.line(&format!("let mut {frame} = {frame};"));
            }
            w.insert(at, &copies);
        }
        self.forking = Some(f);
    }
}
