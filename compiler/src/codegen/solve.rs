//! The skeleton of `solve`: the entry checks, the sketch's declarations, the tolerance of the
//! run-time checks, the plan's steps in groups each opened by a comment quoting the constraint
//! it satisfies, put in blocks when long (see `scopes`), and the `Ok(Solution { .. })`. What
//! each step writes is in `steps`.
//!
//! A frame is declared only if written code reads or moves it, and only a moved one is `mut`.
//! An iterated region is a closure that assembles it on copies of the frames it moves for a
//! trial of its defaults and writes its closes' errors, passed to `outer.iterate`; the region
//! is then written again, straight, at the converged defaults. A plan with iterations is
//! written once, as `fn assemble<O: Outer>`, which `solve` calls with the runtime's
//! `outer::Newton` (the plain iteration) and `solve_all` with `outer::Scan`. `solve` is
//! `#[inline]`, so that a caller in another crate can inline a small one; the runtime's
//! per-step intersections are always inlined, their cold cases out of line.

use super::api::{Holds, Layout};
use super::context::Context;
use super::facts::{Facts, Value};
use super::fork::Forking;
use super::ledger::Ledger;
use super::names::Namer;
use super::scopes::{self, Binding, Group};
use super::sketch::dimension_name;
use super::writer::{field_init, lit, Writer};
use crate::plan::{DefaultId, Iteration, Op, Reg, Step};
use gcs_lang::model::GeomId;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::cell::RefCell;

/// A binding of the solve's sketch: a frame's, declared (and `mut`) once the steps show
/// whether the frame is read or moved, or any other, with its Rust type.
enum Decl {
    Frame(GeomId, Binding),
    Dim(GeomId, Binding),
    Value(Binding, &'static str),
}

/// The state of writing `solve`: the locals declared so far and what is known at the current
/// step.
pub(super) struct Solve<'a> {
    pub(super) cx: &'a Context<'a>,
    pub(super) names: Namer,
    /// Locals of frames and dimensions by top-level geom.
    pub(super) frames: HashMap<GeomId, String>,
    pub(super) dims: HashMap<GeomId, String>,
    /// Locals of members' local coordinates that params set.
    pub(super) locals: HashMap<GeomId, String>,
    /// Dimensions declared where the plan sets them (nothing reads their sketch value).
    pub(super) deferred: HashSet<GeomId>,
    /// What is known of frames and registers at the step being written.
    pub(super) facts: Facts,
    /// Frames the solve's code reads, and frames it moves: one that is neither is not
    /// declared, and only a moved one is `mut`.
    pub(super) frame_reads: RefCell<HashSet<GeomId>>,
    pub(super) frame_writes: HashSet<GeomId>,
    /// Each `let` and each read of a local written so far.
    pub(super) ledger: RefCell<Ledger>,
    /// Where the ledger was, and how many errors' code had been made, when the current step
    /// began.
    pub(super) step_start: (usize, usize),
    /// The entry of the trial's array (the array's local and the index) each default an
    /// iteration varies is, while its region is written.
    pub(super) iterated: HashMap<DefaultId, (String, usize)>,
    /// Inside an iteration's trial: the array its closes write, and the next entry.
    pub(super) closing: Option<(String, usize)>,
    /// Writing an iterated region after it converged: its error functions are not written.
    pub(super) converged: bool,
    /// Registers only error functions read: not written once the iteration converged.
    pub(super) error_only: HashSet<Reg>,
    /// The trial's entry each default an iteration converged on is, for
    /// `Solution::defaults`.
    pub(super) converged_defaults: HashMap<DefaultId, (String, usize)>,
    /// The names of each linear system's unknowns, by the register of its answers.
    pub(super) unknown_names: HashMap<Reg, Vec<String>>,
    /// The directions near an iteration's start (`DirectionsNear`) of each angle it varies,
    /// by the angle's trial entry: declared before the iteration once a trial turns the x
    /// axis by that angle, and used again where the region is written at the angle converged
    /// to.
    pub(super) trial_directions: HashMap<(String, usize), TrialDirections>,
    /// In space, frames declared with a value other than their sketch's: a frame whose
    /// moves were all computed here (see `FrameFacts::literal3`) starts where they left it.
    pub(super) declared_at: HashMap<GeomId, String>,
    /// The terms of the tolerance's scale, a list for each geom, when it is not a literal.
    pub(super) tol_terms: RefCell<Vec<Vec<String>>>,
    /// Writing `solve_all` as one tree of the plan, not `solve`.
    pub(super) forking: Option<Forking>,
    /// Dimensions the steps assign (`d = v;`), not bind anew: their declaration is `mut`.
    pub(super) dims_assigned: HashSet<GeomId>,
}

/// The local of an angle's [`gcs_runtime::frame::DirectionsNear`] in an iteration.
pub(super) struct TrialDirections {
    pub(super) name: String,
    /// Whether the trial read it (and so it is declared).
    pub(super) used: bool,
}

/// Writes `solve`.
pub(super) fn solve(w: &mut Writer, cx: &Context<'_>, layout: &Layout) {
    let mut names = Namer::default();
    for reserved in ["params", "branches", "defaults", "outer", "tol", "solution"] {
        names.reserve(reserved);
    }
    let mut s = Solve::new(cx, names);
    s.write(w, layout);
}

impl<'a> Solve<'a> {
    /// Nothing written yet, with `names` taken.
    pub(super) fn new(cx: &'a Context<'a>, names: Namer) -> Solve<'a> {
        Solve {
            cx,
            names,
            frames: HashMap::default(),
            dims: HashMap::default(),
            locals: HashMap::default(),
            deferred: HashSet::default(),
            facts: Facts::default(),
            frame_reads: RefCell::new(HashSet::default()),
            frame_writes: HashSet::default(),
            ledger: RefCell::default(),
            step_start: (0, 0),
            iterated: HashMap::default(),
            closing: None,
            converged: false,
            error_only: HashSet::default(),
            converged_defaults: HashMap::default(),
            unknown_names: HashMap::default(),
            trial_directions: HashMap::default(),
            declared_at: HashMap::default(),
            tol_terms: RefCell::new(Vec::new()),
            forking: None,
            dims_assigned: HashSet::default(),
        }
    }
}

impl Solve<'_> {
    /// `solve`: entry checks, the sketch, the tolerance, the steps and the solution.
    fn write(&mut self, w: &mut Writer, layout: &Layout) {
        w.line("/// Solves the model: the assembly plan's steps, in order. Never panics, allocates nothing.");
        w.line("///");
        w.line("/// # Errors");
        w.line("///");
        w.line("/// A [`SolveError`] naming the constraint that cannot be met (no intersection, inconsistent,");
        w.line("/// degenerate, or a branch with no assembly here) and by how much, or a non-finite param.");
        // `#[inline]` lets a caller in another crate inline a small solve (a four-bar: its
        // answer then stays in registers instead of a `Solution` in memory); LLVM still weighs
        // its size, so a long solve stays a call.
        w.line("#[inline]");
        w.open("pub fn solve(params: &Params, branches: &Branches, defaults: &Defaults) -> Result<Solution, SolveError> {");
        if !self.cx.plan.iterations.is_empty() {
            // One text of the plan, generic over what its outer iterations do: solve them
            // here, scan them for every root in `solve_all`.
            w.line("assemble(params, branches, defaults, &mut gcs_runtime::outer::Newton)");
            w.close("}");
            w.line("");
            w.line("/// The plan's steps, each outer iteration driven by `outer`: solved to the assembly");
            w.line("/// nearest its start (`solve`), or scanned for every root (`solve_all`).");
            w.line("#[inline]");
            w.open("fn assemble<O: gcs_runtime::outer::Outer>(params: &Params, branches: &Branches, defaults: &Defaults, outer: &mut O) -> Result<Solution, SolveError> {");
        }
        w.line("let _ = (params, branches, defaults);");
        let (decls, tol, groups, mut body) = self.entry_and_steps(w, layout);
        let tail = self.ledger.borrow().mark();
        self.solution_init(&mut body, layout);
        let ledger = self.ledger.borrow();
        let later: Vec<&str> = ledger.reads(tail, ledger.mark()).collect();
        self.declarations(w, decls, tol);
        w.push(&scopes::in_blocks(&groups, &later, body.indent));
        w.push(&body);
        w.close("}");
    }

    /// The entry checks and the sketch's comment, written to `w`; the sketch's declarations,
    /// the tolerance's and the plan's steps in groups, each still to be written, and the
    /// writer the steps were taken out of, at the indent they end at.
    fn entry_and_steps(
        &mut self,
        w: &mut Writer,
        layout: &Layout,
    ) -> (Vec<Decl>, Option<String>, Vec<Group>, Writer) {
        self.check_params(w);
        self.check_sketches(w);
        w.line("// The sketch: where every geom starts.");
        let (worked, decls) = self.sketch(layout);
        let tol = self.tolerance(&worked);
        let mut steps = Writer::at(w.indent);
        self.cx.reads_tol.set(false);
        let groups = self.steps_in_groups(&mut steps);
        (decls, tol, groups, steps)
    }

    /// The sketch's declarations, now that the steps are written, and the tolerance where the
    /// steps written read it.
    fn declarations(&self, w: &mut Writer, decls: Vec<Decl>, tol: Option<String>) {
        scopes::declare(w, &self.bindings(decls));
        if let Some(tol) = tol.filter(|_| self.cx.reads_tol.get()) {
            w.line(&tol);
        }
    }

    /// The body of `solve_all`'s outer closure written as one tree of the plan (see
    /// `fork`): the entry checks, the sketch, the steps with a loop over the roots of each
    /// branch variable where its root is taken, and each leaf's solution kept. None when
    /// the steps are too many `let`s to write flat (`scopes::FLAT_LETS`): nested in loops
    /// and closures they could not be put in blocks.
    pub(super) fn write_tree(&mut self, indent: usize, layout: &Layout) -> Option<Writer> {
        let mut w = Writer::at(indent);
        let (decls, tol, groups, steps) = self.entry_and_steps(&mut w, layout);
        if groups.iter().map(|g| g.lets.len()).sum::<usize>() > scopes::FLAT_LETS {
            return None;
        }
        // The groups' code is the steps' text from its start, where the forks' copies go.
        let mut body = Writer::at(steps.indent);
        groups.iter().for_each(|g| body.push(&g.code));
        self.solution_init(&mut body, layout);
        self.close_forks(&mut body);
        self.declarations(&mut w, decls, tol);
        w.push(&body);
        Some(w)
    }

    /// The geoms the solve works on (every geom the plan reads or moves, and those the
    /// solution reports but for constants), and their sketch's declarations.
    fn sketch(&mut self, layout: &Layout) -> (Vec<GeomId>, Vec<Decl>) {
        let (cx, reported) = (self.cx, self.cx.scope);
        let worked: Vec<GeomId> = cx
            .model
            .top_level()
            .map(|(id, _)| id)
            .filter(|g| (reported.contains(g) && !layout.is_constant(*g)) || cx.touched(*g))
            .collect();
        let mut decls = Vec::new();
        for &g in &worked {
            self.declare_sketch(g, reported.contains(&g), &mut decls);
        }
        (worked, decls)
    }

    /// The declarations, now that the steps are written: a frame the code never reads or
    /// moves is left out, and only a moved one is `mut`.
    fn bindings(&self, decls: Vec<Decl>) -> Vec<Binding> {
        self.bindings_typed(decls)
            .into_iter()
            .map(|(b, _)| b)
            .collect()
    }

    /// [`Solve::bindings`], each with its Rust type.
    fn bindings_typed(&self, decls: Vec<Decl>) -> Vec<(Binding, &'static str)> {
        let frame_ty = self.cx.space.rust(super::api::Ty::Frame);
        decls
            .into_iter()
            .filter_map(|decl| match decl {
                Decl::Frame(g, frame) => {
                    let mutable = self.frame_writes.contains(&g);
                    let read = self.frame_reads.borrow().contains(&g);
                    let value = self.declared_at.get(&g).cloned().unwrap_or(frame.value);
                    (mutable || read).then_some((
                        Binding {
                            mutable,
                            value,
                            ..frame
                        },
                        frame_ty,
                    ))
                }
                // In `solve_all`'s tree a dimension set after a fork is bound anew there.
                Decl::Dim(g, binding) => Some((
                    Binding {
                        mutable: match self.forking {
                            Some(_) => self.dims_assigned.contains(&g),
                            None => binding.mutable,
                        },
                        ..binding
                    },
                    "f64",
                )),
                Decl::Value(binding, ty) => Some((binding, ty)),
            })
            .collect()
    }

    /// Params and defaults must be finite and within `gcs_runtime::num::MAX_MAGNITUDE`.
    fn check_params(&self, w: &mut Writer) {
        let m = self.cx.model;
        let params = m
            .params
            .iter()
            .map(|(id, p)| format!("({}, params.{})", lit(&p.name), self.cx.params[&id]));
        let defaults = (self.cx.plan.defaults.iter().zip(&self.cx.defaults))
            .map(|(d, field)| format!("({}, defaults.{field})", lit(&d.name)));
        let list: Vec<String> = params.chain(defaults).collect();
        if list.is_empty() {
            return;
        }
        w.line(&format!(
            "gcs_runtime::error::check_all_finite(&[{}])?;",
            list.join(", ")
        ));
    }

    /// The sketches that params can make unusable (a zero direction, a negative radius, an
    /// overflow), tested before any is read, as the interpreter tests them.
    fn check_sketches(&self, w: &mut Writer) {
        for (g, test, fault) in self.cx.sketch_checks() {
            let name = &self.cx.model.geoms[g].name;
            w.line(&format!(
                "// The sketch of `{name}` depends on params: is it usable?"
            ));
            w.open(&format!("if {test} {{"));
            w.line(&format!(
                "return Err({});",
                self.cx
                    .error_with(name, fault.what(), "InvalidInput", "f64::NAN")
            ));
            w.close("}");
        }
    }

    /// The sketch of top-level geom `g`: its frame, its dimension (unless the plan sets it
    /// before anything reads it) and its members' local coordinates that params set.
    fn declare_sketch(&mut self, g: GeomId, reported: bool, decls: &mut Vec<Decl>) {
        let geom = &self.cx.model.geoms[g];
        let name = self.names.fresh(&geom.name);
        let (ctor, facts) = self.cx.sketch_frame(g);
        decls.push(Decl::Frame(
            g,
            Binding {
                mutable: false,
                name: name.clone(),
                value: ctor,
            },
        ));
        self.facts.frames.insert(g, facts);
        self.frames.insert(g, name);
        if let Some(what) = dimension_name(geom.kind) {
            self.declare_dimension(g, &format!("{}_{what}", geom.name), decls);
        }
        // The solution stores the local coordinates of the geoms it reports; other geoms need
        // them only where a step reads them.
        for local in self.cx.param_locals(g) {
            if reported || self.cx.reads_feature(local.feature) {
                let ty = match local.vector {
                    true => self.cx.space.rust(super::api::Ty::Vector),
                    false => self.cx.space.rust(super::api::Ty::Point),
                };
                self.declare_local(local.feature, (&local.name, ty), local.value, decls);
            }
        }
    }

    /// The dimension of geom `g`, in a local called after `name`: declared here unless the
    /// plan sets it before anything reads it, where it is declared then.
    fn declare_dimension(&mut self, g: GeomId, name: &str, decls: &mut Vec<Decl>) {
        let name = self.names.fresh(name);
        if self.cx.dim_set_before_read(g) {
            self.deferred.insert(g);
        } else {
            decls.push(Decl::Dim(
                g,
                Binding {
                    mutable: self.cx.dim_set(g),
                    name: name.clone(),
                    value: self.cx.sketch_dim_declared(g),
                },
            ));
        }
        self.dims.insert(g, name);
    }

    /// Declares the local holding feature `f`'s local coordinates.
    fn declare_local(
        &mut self,
        f: GeomId,
        (name, ty): (&str, &'static str),
        value: String,
        decls: &mut Vec<Decl>,
    ) {
        let name = self.names.fresh(name);
        decls.push(Decl::Value(
            Binding {
                mutable: false,
                name: name.clone(),
                value,
            },
            ty,
        ));
        self.locals.insert(f, name);
    }

    /// Whether the plan has a step that reads the run-time tolerance whatever it computes: a
    /// check, a point that must lie on its locus, an iteration's close.
    fn checks_anything(&self) -> bool {
        let checked =
            |s: &Step| matches!(s.op, Op::Check { .. } | Op::Onto { .. } | Op::Close { .. });
        self.cx.plan.steps.iter().any(checked)
    }

    /// The tolerance of run-time checks, relative to the scale of the geoms the plan works on
    /// as the interpreter measures it; none when nothing is checked. It reads the frames and
    /// dimensions, so it is declared after them.
    fn tolerance(&self, worked: &[GeomId]) -> Option<String> {
        // A segment length a closure gives may be checked against it too.
        let closing = |(i, s): (usize, &Step)| {
            matches!(s.op, Op::SetDim { .. }) && self.cx.plan.closing_length(i).is_some()
        };
        if !self.checks_anything() && !self.cx.plan.steps.iter().enumerate().any(closing) {
            return None;
        }
        let mut terms = Vec::new();
        // The values when every term is a literal: the tolerance is then one, computed here.
        let mut values: Option<Vec<f64>> = Some(Vec::new());
        let mut chunks = Vec::new();
        for &g in worked.iter().filter(|&&g| self.cx.touched(g)) {
            let chunk_at = terms.len();
            let dim_literal = || match self.dims.get(&g) {
                None => Some(None),
                Some(_) if self.deferred.contains(&g) || self.cx.dim_set(g) => None,
                Some(_) => self.cx.sketch_dim_value3(g).map(Some),
            };
            match (
                self.facts.frames.get(&g).and_then(|f| f.literal3),
                dim_literal(),
            ) {
                (Some(f), Some(dim)) => {
                    if let Some(v) = values.as_mut() {
                        v.extend(f.origin.iter().copied().chain(dim));
                    }
                }
                _ => values = None,
            }
            // A frame known to the bit: its sketch's coordinates, as literals (its local may
            // be declared where the plan's first moves leave it).
            if let Some(f) = self.facts.frames.get(&g).and_then(|f| f.literal3) {
                terms.extend(f.origin.iter().map(|x| super::writer::float(*x)));
            } else {
                let f = self.frame(g);
                let coordinates = self.cx.space.coordinates().iter();
                terms.extend(coordinates.map(|x| format!("{f}.origin.{x}")));
            }
            if let Some(d) = self.dims.get(&g) {
                if self.deferred.contains(&g) {
                    // Not declared yet: its sketch value, as the interpreter has it now.
                    terms.extend(self.cx.sketch_dim(g));
                } else {
                    terms.push(d.clone());
                }
            }
            chunks.push(terms[chunk_at..].to_vec());
        }
        *self.tol_terms.borrow_mut() = chunks;
        if let Some(v) = values {
            let tol = gcs_runtime::tol::CHECK_REL * (1.0 + gcs_runtime::tol::scale(&v));
            return Some(format!(
                "let tol = {}; // CHECK_REL * (1 + scale), of the sketch's constants",
                super::writer::float(tol)
            ));
        }
        Some(format!(
            "let tol = gcs_runtime::tol::CHECK_REL * (1.0 + gcs_runtime::tol::scale(&[{}]));",
            terms.join(", ")
        ))
    }

    /// Writes the plan's steps, each group up to the step that satisfies a constraint opened
    /// with a comment quoting that constraint and its place in the file; returns each group
    /// (so that a long solve can be put in blocks), taken out of `w`.
    fn steps_in_groups(&mut self, w: &mut Writer) -> Vec<Group> {
        let steps = &self.cx.plan.steps;
        let mut group_start = true;
        // Where the current group's code starts: a group whose steps all turn out to move
        // nothing says so under its comment.
        let mut group_code = 0;
        let mut group_starts = Vec::new();
        for (i, step) in steps.iter().enumerate() {
            if let Some(it) = self.cx.plan.iterations.iter().find(|it| it.start == i) {
                self.iteration(w, it);
            }
            if self.cx.plan.iterations.iter().any(|it| it.end == i) {
                self.iterated.clear();
                self.converged = false;
            }
            if group_start {
                group_starts.push((w.out.len(), self.ledger.borrow().mark()));
                if let Some(end) = steps[i..].iter().find(|s| !s.satisfies.is_empty()) {
                    self.constraint_comments(w, end);
                }
                group_start = false;
                group_code = w.out.len();
            }
            self.step(w, i, step);
            if !step.satisfies.is_empty() {
                if w.out.len() == group_code {
                    w.comment("Already true where the sketch puts the geoms: nothing moves.");
                }
                group_start = true;
            }
        }
        let text = Writer {
            out: std::mem::take(&mut w.out),
            starts: std::mem::take(&mut w.starts),
            ..Writer::at(w.indent)
        };
        let ledger = self.ledger.borrow();
        let end = (text.out.len(), ledger.mark());
        (group_starts.iter())
            .zip(group_starts.iter().skip(1).chain([&end]))
            .map(|(&(from, at), &(to, until))| Group {
                code: text.slice(from, to),
                lets: ledger.lets(at, until, text.indent),
                reads: ledger.reads(at, until).map(str::to_string).collect(),
            })
            .collect()
    }

    /// An outer iteration (000, section 5.2.1): a closure that assembles region `it` for a
    /// trial of its defaults and writes the errors of its closes, driven to zero by `outer`
    /// (the runtime's `iterate::solve` in `solve`) from the `Defaults` given. The region's steps are then
    /// written again, straight, with the defaults converged to: what they define is what the
    /// rest of `solve` reads.
    fn iteration(&mut self, w: &mut Writer, it: &Iteration) {
        let (cx, plan) = (self.cx, self.cx.plan);
        let varied: Vec<String> = plan.varied(it).iter().map(|n| format!("`{n}`")).collect();
        let closes = plan.closes(it);
        let closed: Vec<String> = (closes.iter())
            .map(|c| format!("`{}`", cx.model.constraints[*c].name))
            .collect();
        let trial = self.names.fresh("trial");
        let errors = self.names.fresh("errors");
        let start: Vec<String> = (it.defaults.iter())
            .map(|d| format!("defaults.{}", cx.defaults[d.0 as usize]))
            .collect();
        // An angle's natural step is a radian; a length's, the geoms' size (`tol` is
        // `CHECK_REL * (1 + size)`), as the interpreter takes them.
        let scale: Vec<String> = (it.defaults.iter())
            .map(|d| {
                if plan.defaults[d.0 as usize].is_angle() {
                    "1.0".to_string()
                } else {
                    "tol / gcs_runtime::tol::CHECK_REL".to_string()
                }
            })
            .collect();
        w.line("");
        w.line(&format!(
            "// No loop is rigid here: vary {} until {} close{} (an outer iteration).",
            varied.join(", "),
            closed.join(", "),
            if closed.len() == 1 { "s" } else { "" }
        ));
        self.let_line(
            w,
            &format!("mut {trial}"),
            &trial,
            &format!("[{}]", start.join(", ")),
        );
        // An angle's directions near its start, declared here once the trial reads them.
        let (directions_at, directions_indent) = (w.out.len(), w.indent);
        let directions_mark = self.ledger.borrow().mark();
        for (k, d) in it.defaults.iter().enumerate() {
            if plan.defaults[d.0 as usize].is_angle() {
                let name = (self.names).fresh(&format!("{}_directions", cx.defaults[d.0 as usize]));
                let directions = TrialDirections { name, used: false };
                self.trial_directions.insert((trial.clone(), k), directions);
            }
        }
        self.note_read(&trial);
        // One angle's turn, searched for a root when its iteration fails (as the interpreter
        // says it).
        let span = match it.defaults.as_slice() {
            [d] if plan.defaults[d.0 as usize].is_angle() => {
                ".spanning(gcs_runtime::iterate::Span::Turn)"
            }
            _ => "",
        };
        // From the sketch's own defaults and branches (a cold solve), the sketch's assembly
        // mode is kept, as the interpreter keeps it.
        let hold = match it.mode {
            Some(mode) => {
                let sketch: Vec<String> = (it.defaults.iter())
                    .map(|d| super::writer::float(plan.defaults[d.0 as usize].sketch))
                    .collect();
                let branches = if cx.plan.branches.is_empty() {
                    ""
                } else {
                    " && *branches == Branches::default()"
                };
                w.line(
                    "// From the sketch's defaults and branches, the iteration keeps the sketch's",
                );
                w.line(&format!(
                    "// assembly mode: {}.",
                    it.mode_words().unwrap_or_default()
                ));
                let name = self.names.fresh("hold");
                self.let_read(
                    w,
                    &name,
                    &format!(
                        "({trial} == [{}]{branches}).then_some(gcs_runtime::mode::Orientation::{mode:?})",
                        sketch.join(", ")
                    ),
                );
                format!(".holding({name})")
            }
            None => String::new(),
        };
        w.open(&format!(
            "outer.iterate(&mut {trial}, &[{}], &gcs_runtime::iterate::Settings::for_size(tol / gcs_runtime::tol::CHECK_REL - 1.0){span}{hold}, |{trial}, {errors}| {{",
            scale.join(", ")
        ));
        // The trial works on copies of the frames the region moves: those its code writes,
        // declared once the body is written.
        let facts = self.facts.clone();
        let deferred = self.deferred.clone();
        let written_before = std::mem::take(&mut self.frame_writes);
        // A dimension the region sets is bound anew where it is set (`set_dim`).
        let shadows_at = w.out.len();
        for (k, d) in it.defaults.iter().enumerate() {
            self.iterated.insert(*d, (trial.clone(), k));
        }
        self.closing = Some((errors.clone(), 0));
        let body_at = self.ledger.borrow().mark();
        for i in it.start..it.end {
            self.step(w, i, &plan.steps[i]);
        }
        self.closing = None;
        // What the trial computes for the steps after the region only: not read here.
        let unread = self.ledger.borrow().unread_since(body_at);
        if !unread.is_empty() {
            let refs: Vec<String> = unread.iter().map(|n| format!("&{n}")).collect();
            let refs = match refs.as_slice() {
                [one] => one.clone(),
                _ => format!("({})", refs.join(", ")),
            };
            unread.iter().for_each(|n| self.note_read(n));
            w.line(&format!("let _ = {refs};"));
        }
        let written = std::mem::replace(&mut self.frame_writes, written_before);
        let mut shadows = Writer::at(w.indent);
        let mut written: Vec<GeomId> = written.into_iter().collect();
        written.sort();
        let mut names = Vec::new();
        for g in &written {
            let f = self.frame(*g);
            self.frame_reads.borrow_mut().insert(*g);
            shadows.line(&format!("let mut {f} = {f};"));
            names.push(f);
        }
        self.ledger
            .borrow_mut()
            .declare_at(body_at, &names, shadows.indent);
        self.frame_writes.extend(written);
        w.insert(shadows_at, &shadows);
        w.line("Ok(())");
        w.close("})");
        let mut declared = Writer::at(directions_indent);
        let mut names = Vec::new();
        for k in 0..it.defaults.len() {
            match self.trial_directions.get(&(trial.clone(), k)) {
                Some(TrialDirections { name, used: true }) => {
                    declared.line(&format!("let {name} = DirectionsNear::new({trial}[{k}]);"));
                    names.push(name.clone());
                }
                Some(_) => {
                    self.trial_directions.remove(&(trial.clone(), k));
                }
                None => {}
            }
        }
        self.ledger
            .borrow_mut()
            .declare_at(directions_mark, &names, directions_indent);
        w.insert(directions_at, &declared);
        let first = &cx.model.constraints[closes[0]];
        // A failure other than the assembly's own at the start is named after the first close.
        w.line(&format!(
            ".map_err(|failure| failure.into_error({}, {}))?;",
            lit(&first.name),
            lit(&first.text)
        ));
        // An angle converged to is reported in (-pi, pi]: a turn more is the same assembly.
        for (k, d) in it.defaults.iter().enumerate() {
            if plan.defaults[d.0 as usize].is_angle() {
                self.note_read(&trial);
                w.line(&format!(
                    "{trial}[{k}] = gcs_runtime::num::wrap_angle({trial}[{k}]);"
                ));
            }
        }
        // The region again, at the defaults converged to, without what only its error
        // functions read, nor the circle of a nearest point that is not written (whose turns
        // read its point instead).
        let unwritten_nearest = |s: &Step| match s.op {
            Op::Nearest { point, .. } => (s.out)
                .is_some_and(|(r, _)| cx.turned_toward.contains(&r))
                .then_some(point),
            _ => None,
        };
        let is_error = |s: &Step| {
            matches!(
                s.op,
                Op::Error { .. } | Op::Implicit { .. } | Op::Close { .. }
            ) || unwritten_nearest(s).is_some()
        };
        // A register is the errors' alone when every step that reads it is an error, or
        // defines a register that is (a closing error's locus, made for it: a sphere about an
        // orbit's centre on its axis). Readers come after what they read: one pass backwards.
        let mut only: HashMap<Reg, bool> = HashMap::default();
        for s in plan.steps.iter().rev() {
            let feeds = is_error(s) || s.out.is_some_and(|(r, _)| only.get(&r) == Some(&true));
            for r in s.op.reads() {
                *only.entry(r).or_insert(true) &= feeds;
            }
        }
        for r in plan.steps.iter().filter_map(unwritten_nearest) {
            only.insert(r, false);
        }
        self.error_only = (plan.steps[it.start..it.end].iter())
            .filter(|s| is_error(s) || s.out.is_some_and(|(r, _)| only.get(&r) == Some(&true)))
            .flat_map(|s| s.op.reads().into_iter().chain(s.out.map(|(r, _)| r)))
            .filter(|r| only.get(r) == Some(&true))
            .collect();
        self.facts = facts;
        self.deferred = deferred;
        for (k, d) in it.defaults.iter().enumerate() {
            self.iterated.insert(*d, (trial.clone(), k));
            self.converged_defaults.insert(*d, (trial.clone(), k));
        }
        self.converged = true;
    }

    /// The comment that opens a group of steps: the constraints its last step satisfies, each
    /// with its place in the file.
    fn constraint_comments(&self, w: &mut Writer, end: &Step) {
        let m = self.cx.model;
        w.line("");
        for c in &end.satisfies {
            let con = &m.constraints[*c];
            let label = con
                .label
                .as_ref()
                .map_or(String::new(), |l| format!("{l}: "));
            w.comment(&format!(
                "{label}{} ({}:{})",
                con.text,
                self.cx.file,
                m.line(con.span)
            ));
        }
    }

    /// `Ok(Solution { .. })`: each field from the local of what it holds; in `solve_all`'s
    /// tree, the solution kept in the list (`keep`).
    fn solution_init(&self, w: &mut Writer, layout: &Layout) {
        w.line("");
        if self.forking.is_some() {
            w.open("let solution = Solution {");
        } else {
            w.open("Ok(Solution {");
        }
        for field in &layout.fields {
            let local = self.field_value(field.holds);
            w.line(&field_init(&field.name, &local));
        }
        if !self.cx.plan.branches.is_empty() {
            w.line("branches: *branches,");
        }
        self.defaults_init(w);
        if self.forking.is_some() {
            w.close("};");
            w.line("keep(&mut found, &mut kept, solution);");
        } else {
            w.close("})");
        }
    }

    /// The code of frame `g`'s value now: its literal while it is known to the bit (in space),
    /// else its local.
    pub(super) fn frame_value(&self, g: GeomId) -> String {
        match self.facts.frames.get(&g).and_then(|f| f.literal3) {
            Some(f) => super::sketch3::frame3(&f),
            None => self.frame(g),
        }
    }

    /// Writes steps `range` of a plan without outer iterations (a piece of a large model's
    /// solve), each group up to the step that satisfies a constraint opened with a comment
    /// quoting that constraint, as [`Solve::steps_in_groups`] writes the whole plan.
    pub(super) fn groups(&mut self, w: &mut Writer, range: std::ops::Range<usize>) {
        let steps = &self.cx.plan.steps;
        let mut group_start = true;
        let mut group_code = 0;
        for i in range.clone() {
            let step = &steps[i];
            if group_start {
                if let Some(end) = steps[i..range.end].iter().find(|s| !s.satisfies.is_empty()) {
                    self.constraint_comments(w, end);
                }
                group_start = false;
                group_code = w.out.len();
            }
            self.step(w, i, step);
            if !step.satisfies.is_empty() {
                if w.out.len() == group_code {
                    w.comment("Already true where the sketch puts the geoms: nothing moves.");
                }
                group_start = true;
            }
        }
    }

    /// The code of a solution field's value at the end of `solve`.
    fn field_value(&self, holds: Holds) -> String {
        match holds {
            Holds::Frame(g) => self.frame_value(g),
            Holds::Dim(g) => self.dim(g),
            Holds::Local(f) => {
                self.note_read(&self.locals[&f]);
                self.locals[&f].clone()
            }
            Holds::LineSketch(g) => match super::api::line_sketch(self.cx, g) {
                Some(from) => self.cx.point_code(from),
                None => unreachable!("only a line's sketch point is held"),
            },
        }
    }

    /// The `defaults` field of the solution: each as given, or as its iteration converged.
    fn defaults_init(&self, w: &mut Writer) {
        if !self.cx.plan.defaults.is_empty() {
            let fields: Vec<String> = (self.cx.defaults.iter().enumerate())
                .map(
                    |(k, field)| match self.converged_defaults.get(&DefaultId(k as u32)) {
                        Some((trial, k)) => {
                            self.note_read(trial);
                            format!("{field}: {trial}[{k}]")
                        }
                        None => format!("{field}: defaults.{field}"),
                    },
                )
                .collect();
            w.line(&format!("defaults: Defaults {{ {} }},", fields.join(", ")));
        }
    }

    /// The code of register `r`, noted as read: ask for it only for code that is written.
    pub(super) fn r(&self, r: Reg) -> String {
        self.code(self.facts.value(r))
    }

    /// The code of `v`, noted as read (see [`Solve::r`]).
    pub(super) fn code(&self, v: &Value) -> String {
        self.note(v);
        v.code()
    }

    /// Notes a read of the local `v` is, if it is one.
    pub(super) fn note(&self, v: &Value) {
        if let Some(name) = v.reads() {
            self.note_read(name);
        }
    }

    /// Notes a read (or an assignment, or a move) of local `name`.
    pub(super) fn note_read(&self, name: &str) {
        self.ledger.borrow_mut().read(name);
    }

    /// `let {pattern} = {code};`, declaring `name`.
    pub(super) fn let_line(&self, w: &mut Writer, pattern: &str, name: &str, code: &str) {
        w.line(&format!("let {pattern} = {code};"));
        self.ledger.borrow_mut().declare(name, w.indent);
    }

    /// `let {name} = {code};` for a local that the code of its own step goes on to read.
    pub(super) fn let_read(&self, w: &mut Writer, name: &str, code: &str) {
        self.let_line(w, name, name, code);
        self.note_read(name);
    }
}
