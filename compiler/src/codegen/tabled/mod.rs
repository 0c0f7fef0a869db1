//! A large model's solver as a few functions and tables of their data (issues 22 and 36).
//!
//! The flat solve is one straight function; rustc's time on one function grows faster than
//! its length, so a chain of 10,000 four-bars does not build. But a large model is a few local
//! problems repeated: its steps differ only in which geoms and registers they work on, in
//! their constants, in the names their errors give and in the params and branch variables
//! they read. So the solve is cut into *pieces* (see `layout`): the sketch of a few geoms at a
//! time, then runs of a few groups of steps. Each piece is written by the ordinary step
//! emitter on what it loads from a *store* (frames, dimensions and the registers earlier
//! pieces define) and ends by storing what later pieces read (see `piece`).
//!
//! Each piece is first written in its *canonical form* (see `lift`): its locals numbered, its
//! comments left out, and every datum that may differ between pieces (a float or string
//! literal, a param, a branch variable, a default, a store slot) recorded as a hole of its row
//! as the emitter writes it. Pieces hash-cons on that form: pieces of one canonical form are
//! one *shape*, written once as a function (from its first piece, its *representative*, with
//! the model's names and comments) and a table with a row of data per piece; a hole every row
//! fills alike is written as the datum itself. Nothing reads the generated text back: two
//! pieces share a function exactly when the emitter, given their plan steps, writes the same
//! code but for their rows. The generated text grows with the number of shapes, plus the
//! tables, a row a line.
//!
//! The store, a slice per kind of value (`layout::Slice`, from the plan's types), is owned
//! by the `Solution`, whose values are read by dotted name through tables of their own shapes
//! (the accessor of each value, with the frame and what else it reads loaded from the store).
//!
//! Only plans without outer iterations are laid out so: an iteration's trial is a closure
//! over its region, not a sequence of pieces.

mod layout;
mod piece;
mod tables;

use super::api::{self, Holds, Layout as ApiLayout, Ty as ApiTy};
use super::context::Context;
use super::lift::{self, Hole};
use super::space::Space;
use super::writer::{lit, Writer};
use layout::{Layout, Slice, Work};
use piece::{Handoff, Spelling};
use rustc_hash::FxHashMap as HashMap;
use tables::{Strings, Table};

/// `Form::Auto` lays out as tables a plan whose flat solve would have at least this many
/// lines of steps (before rustfmt, which makes them two to three times as many), and keeps
/// smaller ones flat: readable, a comment a step. Measured with `gcs bench --form`
/// (docs/BENCHMARKS.md).
pub(super) const TABLED_LINES: usize = 12_000;

/// Plans of fewer steps are never laid out as tables by `Form::Auto`: too small to reach
/// [`TABLED_LINES`], and then not worth writing their pieces to find out.
pub(super) const TABLED_STEPS: usize = 1024;

/// Why a model's solve cannot be laid out as tables.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Untabled {
    /// The plan iterates over defaults: an iteration's trial runs a region of the plan again
    /// for each value it tries, inside one function.
    Iterates {
        /// The defaults iterated, by name.
        defaults: Vec<String>,
    },
    /// The plan solves a linear system (a closed profile whose directions are all known): its
    /// rows are one system, not pieces a table can hold apart.
    Linear {
        /// The constraints of its first row.
        constraint: String,
    },
    /// The plan solves a three-circle problem (`SpatialOp::ThreeCircles`) or a planar
    /// sub-chain's ends (`SpatialOp::PlanarChainEnds`): one step with several answers, which a
    /// table's slices of one type each cannot hold.
    ThreeCircles {
        /// The constraint whose branch it takes.
        constraint: String,
    },
}

impl std::fmt::Display for Untabled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Untabled::Iterates { defaults } => write!(
                f,
                "its plan iterates on {}, and an iteration's trial runs its region of the plan as \
                 one function: only a plan without outer iterations is laid out as tables",
                defaults
                    .iter()
                    .map(|d| format!("`{d}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            Untabled::Linear { constraint } => write!(
                f,
                "its plan solves a linear system (from `{constraint}` on) as one step: only a \
                 plan without one is laid out as tables"
            ),
            Untabled::ThreeCircles { constraint } => write!(
                f,
                "its plan solves a chain of turns (from `{constraint}` on) as one step with \
                 several answers: only a plan without one is laid out as tables"
            ),
        }
    }
}

/// The pieces of one canonical form.
struct Shape {
    /// Sketch pieces and step pieces have functions of their own kinds.
    sketch: bool,
    /// The pieces, in solve order: the first is the representative.
    pieces: Vec<usize>,
    /// Each piece's holes, in the order its code writes them.
    holes: Vec<Vec<Hole>>,
}

/// The whole module of a large model, or `Ok(None)` when its flat solve would have fewer
/// than `min_lines` lines of steps.
pub(super) fn module(
    cx: &Context<'_>,
    api: &ApiLayout,
    min_lines: usize,
) -> Result<Option<super::format::Module>, Untabled> {
    if !cx.plan.iterations.is_empty() {
        let defaults = (cx.plan.iterations.iter())
            .flat_map(|it| cx.plan.varied(it))
            .map(str::to_string)
            .collect();
        return Err(Untabled::Iterates { defaults });
    }
    if let Some(system) = cx.plan.steps.iter().find_map(|s| match &s.op {
        crate::plan::Op::Planar(crate::plan::PlanarOp::Linear(system)) => Some(system),
        _ => None,
    }) {
        let constraint = (system.rows.first())
            .map(|r| cx.model.constraints[r.constraint].name.clone())
            .unwrap_or_default();
        return Err(Untabled::Linear { constraint });
    }
    if let Some(c) = cx.plan.steps.iter().find_map(|s| match &s.op {
        crate::plan::Op::Spatial(
            crate::plan::SpatialOp::ThreeCircles { constraint, .. }
            | crate::plan::SpatialOp::PlanarChainEnds { constraint, .. },
        ) => Some(*constraint),
        _ => None,
    }) {
        let constraint = cx.model.constraints[c].name.clone();
        return Err(Untabled::ThreeCircles { constraint });
    }
    let mut layout = Layout::new(cx, api);
    let pieces = std::mem::take(&mut layout.pieces);
    let mut handoff = Handoff::new(cx, &layout);
    // Each piece's canonical form, hash-consed.
    let mut shapes: Vec<Shape> = Vec::new();
    // Keyed by the holes' columns too: a datum the emitter looks at without writing it (a key
    // it compares) leaves no placeholder in the text, but its row still holds it.
    let mut by_form: HashMap<(bool, String, Vec<lift::Column>), usize> = HashMap::default();
    let mut order: Vec<(usize, usize)> = Vec::with_capacity(pieces.len());
    let mut lines = 0;
    for (k, piece) in pieces.iter().enumerate() {
        let (text, holes) = lift::canonical(|| {
            piece::write(cx, &mut layout, &mut handoff, piece, Spelling::Canonical)
        });
        let sketch = matches!(piece.work, Work::Sketch(_));
        if !sketch {
            lines += text.lines();
        }
        let next = shapes.len();
        let columns = holes.iter().map(Hole::column).collect();
        let n = *by_form.entry((sketch, text.out, columns)).or_insert(next);
        if n == next {
            shapes.push(Shape {
                sketch,
                pieces: Vec::new(),
                holes: Vec::new(),
            });
        }
        order.push((n, shapes[n].pieces.len()));
        shapes[n].pieces.push(k);
        shapes[n].holes.push(holes);
    }
    drop(by_form);
    if lines < min_lines {
        return Ok(None);
    }
    let mut strings = Strings::default();
    let mut tables = String::new();
    let mut w = Writer::default();
    super::api::header(&mut w, &cx.file, cx.space);
    api::params(&mut w, cx);
    inputs(&mut w, &mut tables, &mut strings, cx, true);
    inputs(&mut w, &mut tables, &mut strings, cx, false);
    store(&mut w, &layout, cx.space);
    solution(&mut w, &mut tables, &mut strings, cx, api, &layout);
    // The functions of the shapes, in two kinds, each numbered in solve order.
    let mut functions = Writer::default();
    let mut numbers = vec![0usize; shapes.len()];
    let mut counts = [0usize; 2];
    let mut signatures: Vec<Vec<(String, String, bool)>> = vec![Vec::new(), Vec::new()];
    for (n, shape) in shapes.iter().enumerate() {
        let kind = usize::from(!shape.sketch);
        numbers[n] = counts[kind];
        counts[kind] += 1;
        let rows: Vec<&[Hole]> = shape.holes.iter().map(Vec::as_slice).collect();
        let (renderings, widths) = lift::renderings(&rows);
        let representative = &pieces[shape.pieces[0]];
        let code = lift::render(&shape.holes[0], &renderings, || {
            piece::write(
                cx,
                &mut layout,
                &mut handoff,
                representative,
                Spelling::Representative,
            )
        })
        .unwrap_or_else(|why| panic!("bug in gcs: {why}"));
        let name = match shape.sketch {
            true => format!("sketch_{}", numbers[n]),
            false => format!("piece_{}", numbers[n]),
        };
        let table = name.to_uppercase();
        function(&mut functions, cx, (&name, &table), shape, &pieces, &code);
        // Its rows, a table per column (`TABLE_AT`, `TABLE_K`, `TABLE_TEXT`, `TABLE_INPUT`),
        // a row to a line, the first column's with the first constraint the piece works on.
        let columns = [
            (lift::Column::At, "AT", "u32"),
            (lift::Column::K, "K", "f64"),
            (lift::Column::Text, "TEXT", "u32"),
            (lift::Column::Input, "INPUT", "u32"),
        ];
        let mut lines: [Vec<String>; 4] = Default::default();
        for (holes, &k) in shape.holes.iter().zip(&shape.pieces) {
            let row = lift::row_entries(holes, &renderings, widths);
            let texts: Vec<String> = (row.text.iter())
                .map(|t| strings.id(t).to_string())
                .collect();
            let cells: [Vec<String>; 4] = [
                row.at.iter().map(u32::to_string).collect(),
                row.k.iter().map(|v| float_entry(*v)).collect(),
                texts,
                row.input.iter().map(u32::to_string).collect(),
            ];
            let first = cells.iter().position(|c| !c.is_empty());
            for (c, cell) in cells.into_iter().enumerate() {
                if cell.is_empty() {
                    continue;
                }
                let comment = match Some(c) == first {
                    true => piece_comment(cx, &pieces[k].work),
                    false => String::new(),
                };
                lines[c].push(format!("{},{comment}", cell.join(", ")));
            }
        }
        let mut reads = Vec::new();
        let mut reads_row = false;
        for ((column, suffix, ty), rows) in columns.into_iter().zip(lines) {
            let width = widths[column as usize];
            let field = suffix.to_lowercase();
            match width {
                0 => reads.push(format!("{field}: &[]")),
                _ => {
                    let name = format!("{table}_{suffix}");
                    reads.push(format!("{field}: row_of(&{name}, row, {width})"));
                    reads_row = true;
                    Table::flat_rows(&name, ty, width, rows).write(&mut tables, 1);
                }
            }
        }
        let row = format!("Row {{ {} }}", reads.join(", "));
        signatures[kind].push((name, row, reads_row));
    }
    solve_into(&mut w, cx, &signatures);
    orders(&mut tables, &order, &shapes, &numbers);
    w.out.push_str(&functions.out);
    row_struct(&mut w);
    strings.write(&mut w, &mut tables);
    // The tables last, after the line that says they are data, which `format` leaves as
    // written.
    Ok(Some(super::format::Module::with_tables(w.out, &tables)))
}

/// A float of a table: the literal, always with a decimal point or exponent.
fn float_entry(v: f64) -> String {
    let s = format!("{v:?}");
    match s.as_str() {
        "NaN" => "f64::NAN".into(),
        "inf" => "f64::INFINITY".into(),
        "-inf" => "f64::NEG_INFINITY".into(),
        // `Debug` spells every finite float with a decimal point or an exponent.
        _ => s,
    }
}

/// The comment of a piece's row: the first constraint it works on, and where.
fn piece_comment(cx: &Context<'_>, work: &Work) -> String {
    let m = cx.model;
    let constraint = match work {
        Work::Sketch(geoms) => {
            let first = geoms.first().map(|g| m.geoms[*g].name.as_str());
            return first.map_or(String::new(), |g| format!(" // the sketch of `{g}`, ..."));
        }
        Work::Steps(range) => {
            (cx.plan.steps[range.clone()].iter()).find_map(|s| s.satisfies.first().copied())
        }
    };
    match constraint {
        Some(c) => {
            let con = &m.constraints[c];
            format!(" // {} ({}:{})", con.name, cx.file, m.line(con.span))
        }
        None => String::new(),
    }
}

/// The function of a shape, from its representative's code.
fn function(
    w: &mut Writer,
    cx: &Context<'_>,
    (name, table): (&str, &str),
    shape: &Shape,
    pieces: &[layout::Piece],
    code: &Writer,
) {
    let m = cx.model;
    let first = &pieces[shape.pieces[0]];
    match &first.work {
        Work::Sketch(geoms) => {
            let names: Vec<String> = (geoms.iter())
                .map(|g| format!("`{}`", m.geoms[*g].name))
                .collect();
            w.doc(&format!(
                "The sketch of {}: where they start, stored for the steps and the solution.",
                names.join(", ")
            ));
        }
        Work::Steps(range) => {
            let satisfied: Vec<String> = (cx.plan.steps[range.clone()].iter())
                .flat_map(|s| s.satisfies.iter())
                .map(|c| {
                    let con = &m.constraints[*c];
                    let label = con
                        .label
                        .as_ref()
                        .map_or(String::new(), |l| format!("{l}: "));
                    format!("{label}{}", con.text)
                })
                .collect();
            w.doc(&format!(
                "Satisfies {}.",
                satisfied
                    .iter()
                    .map(|s| format!("`{s}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }
    if shape.pieces.len() > 1 {
        w.line("///");
        let more = shape.pieces.len() - 1;
        let pieces = if more == 1 { "piece" } else { "pieces" };
        w.doc(&format!(
            "And {more} more {pieces} like it: the rows of `{table}`."
        ));
    }
    w.line(
        "#[allow(unused_mut, unused_variables, unused_assignments, clippy::too_many_arguments)]",
    );
    let (fixed, result) = match shape.sketch {
        true => ("tol_scale: &mut f64", ""),
        false => (
            "branches: &Branches, defaults: &Defaults, tol: f64",
            " -> Result<(), SolveError>",
        ),
    };
    w.open(&format!(
        "fn {name}(store: &mut Store, params: &Params, p: &[f64], {fixed}, row: &Row<'_>){result} {{"
    ));
    // The code was written at the function's indent.
    w.push(code);
    if !shape.sketch {
        w.line("Ok(())");
    }
    w.close("}");
    w.line("");
}

/// `Row`: the type of a piece's row of data.
fn row_struct(w: &mut Writer) {
    w.line(
        "/// A piece's data: the store's slots it reads and writes, its constants, the names its",
    );
    w.line(
        "/// errors give (ids of `text`), and the params, branch variables or defaults it reads.",
    );
    w.line("#[derive(Clone, Copy, Debug)]");
    w.open("struct Row<'a> {");
    w.line("at: &'a [u32],");
    w.line("k: &'a [f64],");
    w.line("text: &'a [u32],");
    w.line("input: &'a [u32],");
    w.close("}");
    w.line("");
    w.line("/// Row `row` of a flat table of rows `width` entries wide.");
    w.open("fn row_of<T>(table: &'static [T], row: usize, width: usize) -> &'static [T] {");
    w.line("table.get(row * width..(row + 1) * width).unwrap_or(&[])");
    w.close("}");
    w.line("");
}

/// `solve_into` and `solve`: the sketch's pieces, the tolerance, the steps' pieces.
fn solve_into(w: &mut Writer, cx: &Context<'_>, signatures: &[Vec<(String, String, bool)>]) {
    let m = cx.model;
    w.line("/// Solves the model into `solution`: the sketch's pieces, then the assembly plan's steps,");
    w.line("/// each a call of the function of its shape with its row (`SKETCH_ORDER`, `ORDER`). Never");
    w.line(
        "/// panics, allocates nothing. After an error, `solution` holds the steps done before it.",
    );
    w.line("///");
    w.line("/// # Errors");
    w.line("///");
    w.line("/// A [`SolveError`] naming the constraint that cannot be met (no intersection, inconsistent,");
    w.line("/// degenerate, or a branch with no assembly here) and by how much, or a non-finite param.");
    w.open("pub fn solve_into(params: &Params, branches: &Branches, defaults: &Defaults, solution: &mut Solution) -> Result<(), SolveError> {");
    let list: Vec<String> = (m.params.iter())
        .map(|(id, p)| format!("({}, params.{})", lit(&p.name), cx.params[&id]))
        .collect();
    if !list.is_empty() {
        w.line(&format!(
            "gcs_runtime::error::check_all_finite(&[{}])?;",
            list.join(", ")
        ));
    }
    if !cx.plan.defaults.is_empty() {
        w.open("for (&name, value) in DEFAULTS_NAMES.iter().zip(defaults.values.iter()) {");
        w.line("gcs_runtime::error::check_all_finite(&[(text(name), *value)])?;");
        w.close("}");
    }
    for (g, test, fault) in cx.sketch_checks() {
        let name = &m.geoms[g].name;
        w.line(&format!(
            "// The sketch of `{name}` depends on params: is it usable?"
        ));
        w.open(&format!("if {test} {{"));
        w.line(&format!(
            "return Err({});",
            cx.error_with(name, fault.what(), "InvalidInput", "f64::NAN")
        ));
        w.close("}");
    }
    let fields: Vec<String> = (m.params.iter())
        .map(|(id, _)| format!("params.{}", cx.params[&id]))
        .collect();
    w.line(&format!(
        "let p: [f64; {}] = [{}];",
        m.params.len(),
        fields.join(", ")
    ));
    w.line("let store = &mut solution.store;");
    w.line("let mut tol_scale = 0.0f64;");
    let calls = |w: &mut Writer, kind: usize, table: &str| {
        let sketch = kind == 0;
        let list = &signatures[kind];
        // The row index, where some shape has data to read.
        match list.iter().any(|(_, _, reads_row)| *reads_row) {
            true => {
                w.open(&format!("for &[shape, row] in {table}.iter() {{"));
                w.line("let row = row as usize;");
            }
            false => w.open(&format!("for &[shape, _] in {table}.iter() {{")),
        }
        w.open("match shape {");
        for (n, (name, row, _)) in list.iter().enumerate() {
            let arm = if n + 1 == list.len() {
                "_".to_string()
            } else {
                n.to_string()
            };
            match sketch {
                true => w.line(&format!(
                    "{arm} => {name}(store, params, &p, &mut tol_scale, &{row}),"
                )),
                false => w.line(&format!(
                    "{arm} => {name}(store, params, &p, branches, defaults, tol, &{row})?,"
                )),
            }
        }
        if list.is_empty() {
            w.line("_ => {}");
        }
        w.close("}");
        w.close("}");
    };
    calls(w, 0, "SKETCH_ORDER");
    w.line("let tol = gcs_runtime::tol::CHECK_REL * (1.0 + tol_scale);");
    calls(w, 1, "ORDER");
    w.line("solution.branches = *branches;");
    w.line("solution.defaults = *defaults;");
    w.line("Ok(())");
    w.close("}");
    w.line("");
    w.line("/// Solves the model into a new [`Solution`], which this allocates; [`solve_into`] reuses one.");
    w.line("///");
    w.line("/// # Errors");
    w.line("///");
    w.line("/// As [`solve_into`].");
    w.line("#[allow(dead_code)]");
    w.open("pub fn solve(params: &Params, branches: &Branches, defaults: &Defaults) -> Result<Solution, SolveError> {");
    w.line("let mut solution = Solution::new();");
    w.line("solve_into(params, branches, defaults, &mut solution)?;");
    w.line("Ok(solution)");
    w.close("}");
    w.line("");
}

/// The orders of the calls: `[shape, row]` of each piece, sketch pieces and step pieces apart.
fn orders(tables: &mut String, order: &[(usize, usize)], shapes: &[Shape], numbers: &[usize]) {
    let mut lists = [Vec::new(), Vec::new()];
    for &(n, row) in order {
        let kind = usize::from(!shapes[n].sketch);
        lists[kind].push(format!("[{}, {row}]", numbers[n]));
    }
    let [sketch, steps] = lists;
    Table::packed("SKETCH_ORDER", "[u32; 2]", sketch).write(tables, 8);
    Table::packed("ORDER", "[u32; 2]", steps).write(tables, 8);
}

/// The store: a slice per kind of value the pieces hand on.
fn store(w: &mut Writer, layout: &Layout, space: &dyn Space) {
    w.line("/// Where the solve keeps what crosses its pieces: a slice per kind of value.");
    w.line("#[derive(Clone, Debug, PartialEq)]");
    w.open("struct Store {");
    for slice in layout.counts.keys() {
        w.line(&format!("{}: Box<[{}]>,", slice.field(), slice.rust(space)));
    }
    w.close("}");
    w.line("");
    w.open("impl Store {");
    w.open("fn new() -> Store {");
    w.open("Store {");
    for (slice, n) in &layout.counts {
        w.line(&format!(
            "{}: vec![{}; {n}].into_boxed_slice(),",
            slice.field(),
            slice.zero()
        ));
    }
    w.close("}");
    w.close("}");
    w.close("}");
    w.line("");
}

/// `Branches` (`branch`) or `Defaults` of a large model: the values in an array in model
/// order, set and read by name through a sorted table.
fn inputs(
    w: &mut Writer,
    tables: &mut String,
    strings: &mut Strings,
    cx: &Context<'_>,
    branch: bool,
) {
    let (name, ty, what, list): (&str, &str, &str, Vec<(String, String)>) = if branch {
        let list = (cx.plan.branches.iter())
            .map(|b| (b.name.clone(), b.default.to_string()))
            .collect();
        ("Branches", "u8", "branch variable", list)
    } else {
        let sketch = cx.plan.sketch_defaults();
        let list = (cx.plan.defaults.iter().zip(sketch))
            .map(|(d, v)| (d.name.clone(), float_entry(v)))
            .collect();
        ("Defaults", "f64", "default", list)
    };
    let upper = name.to_uppercase();
    let field = if branch { "indices" } else { "values" };
    let n = list.len();
    let eq = if branch { ", Eq" } else { "" };
    if branch {
        w.line("/// Which assembly: an index per branch variable, in model order, each with a geometric");
        w.line("/// meaning (`Branches::meaning`). Set and read by the variable's name.");
    } else {
        w.line("/// Values of the degrees of freedom the analysis had to default, in model order. Set and");
        w.line("/// read by the default's name.");
    }
    w.line(&format!("#[derive(Clone, Copy, Debug, PartialEq{eq})]"));
    w.open(&format!("pub struct {name} {{"));
    w.line(&format!("{field}: [{ty}; {n}],"));
    w.close("}");
    w.line("");
    w.line("#[allow(dead_code)]");
    w.open(&format!("impl {name} {{"));
    w.line(&format!(
        "/// Sets the {what} called `name` (as in the model); `false` when there is none."
    ));
    w.open(&format!(
        "pub fn set(&mut self, name: &str, value: {ty}) -> bool {{"
    ));
    w.open(&format!("match find(&{upper}_BY_NAME, name) {{"));
    w.open("Some(k) => {");
    w.line(&format!("self.{field}[k] = value;"));
    w.line("true");
    w.close("}");
    w.line("None => false,");
    w.close("}");
    w.close("}");
    w.line("");
    w.line(&format!("/// The {what} called `name`, if there is one."));
    w.open(&format!("pub fn get(&self, name: &str) -> Option<{ty}> {{"));
    w.line(&format!(
        "find(&{upper}_BY_NAME, name).map(|k| self.{field}[k])"
    ));
    w.close("}");
    w.line("");
    w.line(&format!(
        "/// Every {what}'s value, in model order (`{name}::names`)."
    ));
    w.open(&format!("pub fn as_slice(&self) -> &[{ty}] {{"));
    w.line(&format!("&self.{field}"));
    w.close("}");
    w.line("");
    w.line(&format!(
        "/// Every {what}'s value, in model order, to set."
    ));
    w.open(&format!("pub fn as_mut_slice(&mut self) -> &mut [{ty}] {{"));
    w.line(&format!("&mut self.{field}"));
    w.close("}");
    w.line("");
    w.line(&format!("/// The {what}s' names, in model order."));
    w.open("pub fn names() -> impl Iterator<Item = &'static str> {");
    w.line(&format!("{upper}_NAMES.iter().map(|&id| text(id))"));
    w.close("}");
    if branch {
        w.line("");
        w.line("/// What index `index` of the branch variable called `name` means, if it has one.");
        w.open("pub fn meaning(name: &str, index: u8) -> Option<&'static str> {");
        w.line("let k = find(&BRANCHES_BY_NAME, name)?;");
        w.line("let first = *BRANCHES_MEANING_AT.get(k)? as usize;");
        w.line("let end = *BRANCHES_MEANING_AT.get(k + 1)? as usize;");
        w.line("let at = first + usize::from(index);");
        w.line("(at < end).then(|| text(BRANCHES_MEANING[at]))");
        w.close("}");
    }
    w.close("}");
    w.line("");
    w.open(&format!("impl Default for {name} {{"));
    w.line(if branch {
        "/// The sketch's assembly."
    } else {
        "/// The sketch's values."
    });
    w.open("fn default() -> Self {");
    w.line(&format!("{name} {{ {field}: {upper}_SKETCH }}"));
    w.close("}");
    w.close("}");
    w.line("");
    // The tables.
    let names: Vec<String> = (list.iter())
        .map(|(n, _)| strings.id(n).to_string())
        .collect();
    Table::packed(&format!("{upper}_NAMES"), "u32", names).write(tables, 16);
    let values: Vec<String> = list.iter().map(|(_, v)| v.clone()).collect();
    Table::packed(&format!("{upper}_SKETCH"), ty, values).write(tables, 16);
    let sorted = strings.by_name(list.iter().map(|(n, _)| n.as_str()));
    Table::packed(&format!("{upper}_BY_NAME"), "[u32; 2]", sorted).write(tables, 8);
    if branch {
        // The meanings of branch `k`: `BRANCHES_MEANING[BRANCHES_MEANING_AT[k]..][..count]`.
        let (mut at, mut ids) = (vec!["0".to_string()], Vec::new());
        for b in &cx.plan.branches {
            ids.extend(b.meanings.iter().map(|m| strings.id(m).to_string()));
            at.push(ids.len().to_string());
        }
        Table::packed("BRANCHES_MEANING_AT", "u32", at).write(tables, 16);
        Table::packed("BRANCHES_MEANING", "u32", ids).write(tables, 16);
    }
}

/// The `Solution` of a large model: the store the solve works in, read by name through the
/// shapes of its accessors.
fn solution(
    w: &mut Writer,
    tables: &mut String,
    strings: &mut Strings,
    cx: &Context<'_>,
    api: &ApiLayout,
    layout: &Layout,
) {
    w.line("/// The solved configuration of every geom the outputs need, read by dotted name (`point`,");
    w.line("/// `vector`, `scalar`, `frame`) or all of one kind in model order (`points`, ...). Made once");
    w.line(
        "/// by `Solution::new` (which allocates its storage) and solved into any number of times.",
    );
    w.line("#[derive(Clone, Debug, PartialEq)]");
    w.open("pub struct Solution {");
    w.line("store: Store,");
    w.line("branches: Branches,");
    w.line("defaults: Defaults,");
    w.close("}");
    w.line("");
    w.line("#[allow(dead_code)]");
    w.open("impl Solution {");
    w.line(
        "/// A solution to solve into: its storage, allocated once, at the sketch's branches and",
    );
    w.line("/// defaults.");
    w.open("pub fn new() -> Solution {");
    w.line("Solution { store: Store::new(), branches: Branches::default(), defaults: Defaults::default() }");
    w.close("}");
    w.line("");
    w.line("/// The branch variables this assembly is on: those given to the solve.");
    w.open("pub fn branches(&self) -> Branches {");
    w.line("self.branches");
    w.close("}");
    w.line("");
    w.line("/// The defaults this assembly has: those given to the solve.");
    w.open("pub fn defaults(&self) -> Defaults {");
    w.line("self.defaults");
    w.close("}");
    let accessors = api::accessors(cx, api).0;
    for ty in [ApiTy::Frame, ApiTy::Point, ApiTy::Vector, ApiTy::Scalar] {
        let what = match ty {
            ApiTy::Frame => "frame",
            ApiTy::Point => "point",
            ApiTy::Vector => "vector",
            ApiTy::Scalar => "scalar",
        };
        let rust = ty.rust(cx);
        let upper = what.to_uppercase();
        // Each value's accessor in its canonical form, hash-consed into shapes.
        let mut forms: HashMap<(Vec<String>, Vec<lift::Column>), usize> = HashMap::default();
        let mut shapes: Vec<(usize, Vec<Hole>)> = Vec::new();
        let mut values: Vec<(&str, usize, Vec<Hole>)> = Vec::new();
        let of_ty: Vec<&api::Accessor> = (accessors.iter())
            .map(|(a, _)| a)
            .filter(|a| a.ty == ty)
            .collect();
        for (i, a) in of_ty.iter().enumerate() {
            let (text, holes) = lift::canonical(|| accessor(cx, layout, a, false));
            let next = shapes.len();
            let columns = holes.iter().map(Hole::column).collect();
            let n = *forms.entry((text, columns)).or_insert(next);
            if n == next {
                shapes.push((i, holes.clone()));
            }
            values.push((a.name.as_str(), n, holes));
        }
        // Each shape's renderings, from the holes of every value of that shape.
        let mut renderings = Vec::with_capacity(shapes.len());
        let mut widths = [0usize; 4];
        for (n, (rep, rep_holes)) in shapes.iter().enumerate() {
            let rows: Vec<&[Hole]> = (values.iter())
                .filter(|v| v.1 == n)
                .map(|v| v.2.as_slice())
                .collect();
            let (r, counts) = lift::renderings(&rows);
            for c in 0..4 {
                widths[c] = widths[c].max(counts[c]);
            }
            let code = lift::render(rep_holes, &r, || accessor(cx, layout, of_ty[*rep], true))
                .unwrap_or_else(|why| panic!("bug in gcs: {why}"));
            renderings.push((r, counts, code));
        }
        let (at_len, k_len) = (
            widths[lift::Column::At as usize],
            widths[lift::Column::K as usize],
        );
        w.line("");
        w.line(&format!(
            "/// Every {what} of the solution, by its dotted name in the model, in model order."
        ));
        w.open(&format!(
            "pub fn {what}s(&self) -> impl Iterator<Item = (&'static str, {rust})> + '_ {{"
        ));
        let ids = format!("&{upper}S, {at_len}");
        let ks = match k_len {
            0 => "&[], 0".to_string(),
            _ => format!("&{upper}S_K, {k_len}"),
        };
        w.line(&format!(
            "(0..{upper}S.len() / {}).filter_map(move |k| Some((text(access({ids}, {ks}, k)?.name), self.{what}_at(k))))",
            2 + at_len
        ));
        w.close("}");
        w.line("");
        w.line(&format!(
            "/// The {what} called `name` (its dotted name in the model), if the solution has it."
        ));
        w.open(&format!(
            "pub fn {what}(&self, name: &str) -> Option<{rust}> {{"
        ));
        w.line(&format!(
            "find(&{upper}S_BY_NAME, name).map(|k| self.{what}_at(k))"
        ));
        w.close("}");
        w.line("");
        w.line(&format!(
            "/// The {what} at `k` in model order: the shape of the code that computes it, the"
        ));
        w.line(&format!(
            "/// store's slots it reads and its constants (`{upper}S`)."
        ));
        w.line("#[allow(unused_variables, clippy::match_single_binding)]");
        w.open(&format!("fn {what}_at(&self, k: usize) -> {rust} {{"));
        w.line(&format!(
            "let Some(row) = access({ids}, {ks}, k) else {{ return {}; }};",
            cx.space.zero(ty)
        ));
        w.open("match row.shape {");
        let count = renderings.len();
        for (n, (_, _, code)) in renderings.iter().enumerate() {
            let arm = if n + 1 == count {
                "_".to_string()
            } else {
                n.to_string()
            };
            w.open(&format!("{arm} => {{"));
            for line in code {
                w.line(line);
            }
            w.close("}");
        }
        if count == 0 {
            w.line(&format!("_ => {},", cx.space.zero(ty)));
        }
        w.close("}");
        w.close("}");
        // Its tables, a row a value: its name's id, its shape and the store's slots it reads
        // (`POINTS`), and its constants (`POINTS_K`).
        let mut ids = Vec::with_capacity(values.len());
        let mut constants = Vec::with_capacity(values.len());
        for (name, n, holes) in &values {
            let (r, counts, _) = &renderings[*n];
            let row = lift::row_entries(holes, r, *counts);
            let mut at: Vec<String> = row.at.iter().map(u32::to_string).collect();
            at.resize(at_len, "0".into());
            let mut k: Vec<String> = row.k.iter().map(|v| float_entry(*v)).collect();
            k.resize(k_len, "0.0".into());
            let mut id = vec![strings.id(name).to_string(), n.to_string()];
            id.extend(at);
            ids.push(format!("{},", id.join(", ")));
            constants.push(format!("{},", k.join(", ")));
        }
        Table::flat_rows(&format!("{upper}S"), "u32", 2 + at_len, ids).write(tables, 1);
        if k_len > 0 {
            Table::flat_rows(&format!("{upper}S_K"), "f64", k_len, constants).write(tables, 1);
        }
        let sorted = strings.by_name(values.iter().map(|(n, ..)| *n));
        Table::packed(&format!("{upper}S_BY_NAME"), "[u32; 2]", sorted).write(tables, 8);
    }
    w.close("}");
    w.line("");
    w.line("/// A value of the solution: its name's id, the shape of its accessor, the store's slots it");
    w.line("/// reads and its constants.");
    w.line("#[derive(Clone, Copy, Debug)]");
    w.open("struct Access {");
    w.line("name: u32,");
    w.line("shape: u32,");
    w.line("at: &'static [u32],");
    w.line("k: &'static [f64],");
    w.close("}");
    w.line("");
    w.line("/// Value `k` of a solution's tables: `ids` holds each value's name, shape and `at` slots,");
    w.line("/// `ks` its `kw` constants.");
    w.open("fn access(ids: &'static [u32], at: usize, ks: &'static [f64], kw: usize, k: usize) -> Option<Access> {");
    w.line("let row = ids.get(k * (2 + at)..(k + 1) * (2 + at))?;");
    w.open("Some(Access {");
    w.line("name: row[0],");
    w.line("shape: row[1],");
    w.line("at: &row[2..],");
    w.line("k: ks.get(k * kw..(k + 1) * kw).unwrap_or(&[]),");
    w.close("})");
    w.close("}");
    w.line("");
    w.line("/// The index, in model order, of the entry called `name` of a table sorted by name");
    w.line("/// (`[name's string id, index]`).");
    w.open("fn find(by_name: &[[u32; 2]], name: &str) -> Option<usize> {");
    w.line("let k = by_name.binary_search_by(|&[n, _]| text(n).cmp(name)).ok()?;");
    w.line("Some(by_name[k][1] as usize)");
    w.close("}");
    w.line("");
}

/// The body of accessor `a` of a large model's solution: what it reads loaded from the store,
/// then its value. In the canonical form (`named` false) the locals have fixed names.
fn accessor(cx: &Context<'_>, layout: &Layout, a: &api::Accessor, named: bool) -> Vec<String> {
    let mut loads: Vec<(Holds, String)> = Vec::new();
    let mut read = |holds: Holds| -> Option<String> {
        let slot = match holds {
            Holds::Frame(g) => layout.frame.get(&g).map(|&i| (Slice::Frame, i)),
            Holds::Dim(g) => layout.dim.get(&g).map(|&i| (Slice::Scalar, i)),
            Holds::Local(_) | Holds::LineSketch(_) => {
                layout.held.get(&holds).map(|s| (s.slice, s.index))
            }
        }?;
        if let Some((_, name)) = loads.iter().find(|(h, _)| *h == holds) {
            return Some(name.clone());
        }
        let mut name: String = match (named, holds) {
            (true, Holds::Frame(g)) => super::names::Namer::snake(&cx.model.geoms[g].name),
            (_, Holds::Frame(_)) => "frame".into(),
            (_, Holds::Dim(_)) => "dim".into(),
            (_, Holds::Local(_)) => "local".into(),
            (_, Holds::LineSketch(_)) => "sketch".into(),
        };
        // A joint's value reads two geoms' frames and locals: the second of a kind is `_2`.
        let taken = |n: &str| loads.iter().any(|(_, l)| l == n);
        if taken(&name) {
            let base = name.clone();
            name = (2..)
                .map(|k| format!("{base}_{k}"))
                .find(|n| !taken(n))
                .unwrap_or(base);
        }
        let _ = slot;
        loads.push((holds, name.clone()));
        Some(name)
    };
    let body = a.body(cx, &mut read);
    let mut out = Vec::new();
    for (holds, name) in &loads {
        let (slice, index) = match *holds {
            Holds::Frame(g) => (Slice::Frame, layout.frame[&g]),
            Holds::Dim(g) => (Slice::Scalar, layout.dim[&g]),
            _ => {
                let s = layout.held[holds];
                (s.slice, s.index)
            }
        };
        out.push(format!(
            "let {name} = self.store.{}[{}];",
            slice.field(),
            lift::slot(index)
        ));
    }
    out.push(body);
    out
}
