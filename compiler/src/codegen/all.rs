//! `solve_all` and its fixed-capacity list `Assemblies`: every real assembly of the model at
//! given params, found as the interpreter's [`crate::all`] finds them (the same combinations
//! of branches, the same scan or grid of starts, the same rule for when two solutions are one
//! assembly), so that the two lists agree.
//!
//! A model with more branch combinations than [`crate::plan::MAX_COMBINATIONS`] gets no
//! `solve_all`: the interpreter would only list the assemblies of its first combinations, and
//! a module of a large model is no place for a loop that cannot finish its search.

use super::api::Layout;
use super::context::Context;
use super::writer::{float, Writer};
use crate::plan::{grid, BranchId, MAX_COMBINATIONS};

/// The most assemblies a generated list holds: a scan's roots, or one per branch combination.
const CAPACITY: usize = gcs_runtime::outer::MAX_ROOTS;

/// Writes `MAX_ASSEMBLIES`, `Assemblies` and `solve_all`, when the model's branch combinations
/// can all be tried.
pub(super) fn solve_all(w: &mut Writer, cx: &Context<'_>, layout: &Layout) {
    let plan = cx.plan;
    // As the interpreter's search: a symmetric branch stays the sketch's (`Branches::default`).
    let counts: Vec<usize> = (plan.branches.iter())
        .map(|b| if b.symmetric { 1 } else { b.count.max(1) })
        .collect();
    let Some(combinations) = (counts.iter())
        .try_fold(1usize, |n, &c| n.checked_mul(c))
        .filter(|&n| n <= MAX_COMBINATIONS)
    else {
        return;
    };
    let (varied, one_angle) = crate::all::varied_defaults(plan);
    // As the interpreter's: a scan of a turn is complete only where it brackets every root.
    let complete = crate::all::exhaustive(plan);
    let capacity = if varied.is_empty() {
        combinations.min(CAPACITY)
    } else {
        CAPACITY
    };
    // Closed form with branches to vary: the plan's steps as one tree (`fork`).
    let forked: rustc_hash::FxHashSet<BranchId> = (counts.iter().enumerate())
        .filter(|&(_, &c)| c > 1)
        .map(|(k, _)| BranchId(k as u32))
        .collect();
    let tree = (varied.is_empty() && !forked.is_empty())
        .then(|| super::fork::tree(cx, layout, forked, w.indent + 2))
        .flatten();
    assemblies(w, (cx, layout), (capacity, one_angle, varied.is_empty()));
    let carries = match (plan.branches.is_empty(), plan.defaults.is_empty()) {
        (false, false) => {
            w.line("/// Every real assembly at `params`, each with its branches (`Solution::branches`) and");
            "defaults (`Solution::defaults`)."
        }
        (false, true) => {
            "Every real assembly at `params`, each with its branches (`Solution::branches`)."
        }
        (true, false) => {
            "Every real assembly at `params`, each with its defaults (`Solution::defaults`)."
        }
        (true, true) => "Every real assembly at `params`.",
    };
    w.line(&format!("/// {carries}"));
    w.line("/// Never panics, allocates nothing.");
    w.line("///");
    if tree.is_some() {
        w.line("/// The plan's steps are one tree: where a branch variable's root is taken, each of its");
        w.line("/// roots is taken in turn, the steps before it solved once for all of them.");
    } else if !plan.branches.is_empty() {
        w.line("/// Each combination of the branch variables is solved.");
    }
    if one_angle {
        let d = &plan.defaults[varied[0]];
        w.line(&format!(
            "/// The outer iteration's error is scanned over a whole turn of `{}`,",
            d.name
        ));
        w.line("/// and the plan solved from each root; the runtime's `outer::Scan` says which roots a scan");
        w.line("/// finds. The other defaults (free motions) keep the values given, which every assembly shares.");
        if !complete {
            w.line("/// The error is a distance in space, which touches zero at its roots without changing");
            w.line(
                "/// sign: a scan does not bracket them, and the list is not known to be complete.",
            );
        }
    } else if !varied.is_empty() {
        w.line(&format!(
            "/// Where the plan iterates, it is solved from a grid of {} values of each default it",
            grid(varied.len())
        ));
        w.line("/// varies (a turn for an angle, the given value give or take the model's size for a length):");
        w.line("/// a search that is not known to find every assembly, as `Assemblies::is_complete` says.");
    } else {
        w.line("/// The plan has no outer iteration: each combination has at most one assembly.");
    }
    if let Some(tree) = tree {
        // A closure a branch's root's steps are in, so that `?` ends that root's only.
        w.line("#[allow(dead_code, clippy::redundant_closure_call)]");
        w.open("pub fn solve_all(params: &Params, defaults: &Defaults) -> Assemblies {");
        w.line(&format!("let mut found = Assemblies::new({complete});"));
        w.line("// The sum and scale of each solution listed, computed once (`keep`).");
        w.line("let mut kept = [(0.0, 0.0); MAX_ASSEMBLIES];");
        w.line("let branches = &Branches::default();");
        w.comment("A failure before the first branch's root is taken: no assembly.");
        w.open("let _ = (|| -> Result<(), SolveError> {");
        w.line("let _ = (params, branches, defaults);");
        w.push(&tree);
        w.line("Ok(())");
        w.close("})();");
        w.line("found");
        w.close("}");
        return;
    }
    w.line("#[allow(dead_code)]");
    w.open("pub fn solve_all(params: &Params, defaults: &Defaults) -> Assemblies {");
    w.line(&format!("let mut found = Assemblies::new({complete});"));
    w.line("// The sum and scale of each solution listed, computed once (`keep`).");
    w.line("let mut kept = [(0.0, 0.0); MAX_ASSEMBLIES];");
    let each = |w: &mut Writer| combination_body(w, cx, &varied, one_angle);
    // One scan serves every value of the branches its iteration does not see
    // (`all::scanned_branches`), as in the interpreter: those vary inside, over the roots.
    let scanned = crate::all::scanned_branches(plan);
    let unseen: Vec<usize> = (0..counts.len())
        .filter(|&b| counts[b] > 1 && !scanned[b])
        .collect();
    if one_angle && !unseen.is_empty() {
        let seen: Vec<usize> = (0..counts.len())
            .filter(|&b| counts[b] > 1 && scanned[b])
            .collect();
        let count_of = |set: &[usize]| set.iter().map(|&b| counts[b]).product::<usize>();
        let (outer, inner) = (count_of(&seen), count_of(&unseen));
        if outer > 1 {
            w.open(&format!("for scanned in 0..{outer}usize {{"));
        }
        w.line(&format!(
            "let branches = {};",
            branches_of(cx, &counts, &seen, "scanned", "Branches::default()")
        ));
        scan_lines(w);
        w.open(&format!("for combination in 0..{inner}usize {{"));
        w.line(&format!(
            "let branches = {};",
            branches_of(cx, &counts, &unseen, "combination", "branches")
        ));
        roots_loop(w, cx, &varied);
        w.close("}");
        if outer > 1 {
            w.close("}");
        }
    } else if combinations == 1 {
        w.line("let branches = Branches::default();");
        each(w);
    } else {
        w.open(&format!("for combination in 0..{combinations}usize {{"));
        let all: Vec<usize> = (0..counts.len()).filter(|&b| counts[b] > 1).collect();
        w.line(&format!(
            "let branches = {};",
            branches_of(cx, &counts, &all, "combination", "Branches::default()")
        ));
        each(w);
        w.close("}");
    }
    w.line("found");
    w.close("}");
}

/// `Branches` with the branch variables of `set` (by index, `counts` each) read from `index`
/// in mixed radix, the first varying fastest, and the others from `base` (none left when
/// `set` is every branch variable).
fn branches_of(
    cx: &Context<'_>,
    counts: &[usize],
    set: &[usize],
    index: &str,
    base: &str,
) -> String {
    let mut stride = 1;
    let mut fields = Vec::new();
    for &b in set {
        let count = counts[b];
        let digit = if stride == 1 {
            format!("{index} % {count}")
        } else {
            format!("{index} / {stride} % {count}")
        };
        fields.push(format!("{}: ({digit}) as u8", cx.branches[b]));
        stride *= count;
    }
    if fields.is_empty() {
        base.to_string()
    } else if set.len() == counts.len() {
        format!("Branches {{ {} }}", fields.join(", "))
    } else {
        format!("Branches {{ {}, ..{base} }}", fields.join(", "))
    }
}

/// The scan of the outer iteration's turn on `branches`, its roots in `scan`.
fn scan_lines(w: &mut Writer) {
    w.line("let mut scan = gcs_runtime::outer::Scan::default();");
    w.line("// The scan ends this solve at the iteration, with the roots listed.");
    w.line("let _ = assemble(params, &branches, defaults, &mut scan);");
    w.open("if scan.truncated() {");
    w.line("found.mark_incomplete();");
    w.close("}");
}

/// The solve from each root of `scan` on `branches`, each kept in `found`.
fn roots_loop(w: &mut Writer, cx: &Context<'_>, varied: &[usize]) {
    let field = &cx.defaults[varied[0]];
    w.open("for &root in scan.roots() {");
    if cx.plan.defaults.len() == 1 {
        w.line(&format!("let start = Defaults {{ {field}: root }};"));
    } else {
        w.line(&format!(
            "let start = Defaults {{ {field}: root, ..*defaults }};"
        ));
    }
    w.line("// One start of many: a failure is not told apart, and no mode is held.");
    w.open("if let Ok(s) = assemble(params, &branches, &start, &mut gcs_runtime::outer::Search) {");
    w.line("keep(&mut found, &mut kept, s);");
    w.close("}");
    w.close("}");
}

/// The solves of one combination `branches`, each kept in `found`.
fn combination_body(w: &mut Writer, cx: &Context<'_>, varied: &[usize], one_angle: bool) {
    let plan = cx.plan;
    if varied.is_empty() {
        w.open("if let Ok(s) = solve(params, &branches, defaults) {");
        w.line("keep(&mut found, &mut kept, s);");
        w.close("}");
        return;
    }
    if one_angle {
        scan_lines(w);
        roots_loop(w, cx, varied);
        return;
    }
    // The interpreter's grid, in its order: the first default varied slowest, at most
    // `MAX_COMBINATIONS` cells.
    let each = grid(varied.len());
    let cells = (varied.iter())
        .try_fold(1usize, |n, _| n.checked_mul(each))
        .map_or(MAX_COMBINATIONS, |n| n.min(MAX_COMBINATIONS));
    let size = 1.0
        + (cx.model.default_params().iter())
            .chain(plan.defaults.iter().map(|d| &d.sketch))
            .fold(0.0f64, |m, x| m.max(x.abs()));
    w.open(&format!("for cell in 0..{cells}usize {{"));
    w.line("let mut start = *defaults;");
    for (k, &d) in varied.iter().enumerate() {
        let field = &cx.defaults[d];
        let stride = each.pow((varied.len() - 1 - k) as u32);
        let digit = if stride == 1 {
            format!("cell % {each}")
        } else {
            format!("cell / {stride} % {each}")
        };
        let t = format!("({digit}) as f64 / {}", float(each as f64));
        if plan.defaults[d].is_angle() {
            w.line(&format!(
                "start.{field} = -std::f64::consts::PI + 2.0 * std::f64::consts::PI * ({t});"
            ));
        } else {
            w.line(&format!(
                "start.{field} = defaults.{field} + {} * (2.0 * ({t}) - 1.0);",
                float(size)
            ));
        }
    }
    w.line("// One start of many: a failure is not told apart, and no mode is held.");
    w.open("if let Ok(s) = assemble(params, &branches, &start, &mut gcs_runtime::outer::Search) {");
    w.line("keep(&mut found, &mut kept, s);");
    w.close("}");
    w.close("}");
}

/// `MAX_ASSEMBLIES`, `Assemblies` (the runtime's list of this module's `Solution`) and
/// `same_assembly`, the rule the list keeps each assembly once by.
fn assemblies(
    w: &mut Writer,
    (cx, layout): (&Context<'_>, &Layout),
    (capacity, one_angle, closed): (usize, bool, bool),
) {
    w.line(
        "/// The most assemblies [`solve_all`] lists; past it, the list says it is not complete.",
    );
    w.line("#[allow(dead_code)]");
    w.line(&format!("pub const MAX_ASSEMBLIES: usize = {capacity};"));
    w.line("");
    w.line("/// Every real assembly [`solve_all`] found, each once, in the order found. It is complete");
    if closed {
        w.line("/// when every branch combination was solved in closed form and the list did not overflow.");
    } else if one_angle {
        w.line("/// when every branch combination was solved, its iteration's error scanned over a turn,");
        w.line("/// and neither the scan nor the list overflowed.");
    } else {
        w.line("/// only if the search were exhaustive: this model's starts from a grid, which is not.");
    }
    w.line("#[allow(dead_code)]");
    w.line("pub type Assemblies = gcs_runtime::outer::Assemblies<Solution, MAX_ASSEMBLIES>;");
    w.line("");
    let compared = Compared::new(cx, layout);
    w.line(
        "/// What `keep` holds of a solution listed: the sum of what `same_assembly` compares, and",
    );
    w.line("/// the scale of its points (their largest coordinate, plus one).");
    w.line("#[allow(dead_code)]");
    w.line("type Kept = (f64, f64);");
    w.line("");
    compared.fingerprint(w);
    compared.same_assembly(w, cx);
    w.line("/// Adds `s` to `found` unless the list has its assembly already (`same_assembly`);");
    w.line(
        "/// `kept` holds the sum and scale of each solution listed (`fingerprint`), by its place",
    );
    w.line(
        "/// in the list. Two whose sums differ by more than all they compare may differ are not",
    );
    w.line("/// compared further.");
    w.line("#[allow(dead_code)]");
    w.open("fn keep(found: &mut Assemblies, kept: &mut [Kept; MAX_ASSEMBLIES], s: Solution) {");
    w.line("let (sum, scale) = fingerprint(&s);");
    w.open("let listed = found.iter().zip(kept.iter()).any(|(t, &(sum_t, scale_t))| {");
    w.line("let tol = gcs_runtime::tol::SAME_ASSEMBLY_REL * scale_t;");
    w.line(&format!(
        "(sum_t - sum).abs() <= {}.0 * tol && same_assembly(t, &s, tol)",
        compared.coordinates(cx).max(1)
    ));
    w.close("});");
    w.open("if listed {");
    w.line("return;");
    w.close("}");
    w.open("if let Some(slot) = kept.get_mut(found.len()) {");
    w.line("*slot = (sum, scale);");
    w.close("}");
    w.line("found.push(s, |_, _| false);");
    w.close("}");
    w.line("");
}

/// What the duplicate test of `solve_all`'s list compares, by accessor: a body by its frame
/// (its origin and rotation), not by all its markers' points and axes, which the frame
/// places; any other geom by its points and directions. Constants, which every solution
/// shares, are not read. The interpreter's rule ([`crate::all`]) compares the points and
/// axes themselves: both say two assemblies are one when they agree to within rounding.
struct Compared {
    frames: Vec<String>,
    points: Vec<String>,
    vectors: Vec<String>,
}

impl Compared {
    fn new(cx: &Context<'_>, layout: &Layout) -> Compared {
        use super::api::{Reads, Ty};
        let mut compared = Compared {
            frames: Vec::new(),
            points: Vec::new(),
            vectors: Vec::new(),
        };
        for (a, accessor) in super::api::accessors(cx, layout).0 {
            let body = cx.model.geoms[a.geom].kind == gcs_lang::model::GeomKind::Body;
            match a.ty {
                _ if matches!(a.reads, Reads::Constant(_)) => {}
                Ty::Frame if body => compared.frames.push(accessor),
                Ty::Point if !body => compared.points.push(accessor),
                Ty::Vector if !body => compared.vectors.push(accessor),
                _ => {}
            }
        }
        compared
    }

    /// Whether nothing is compared: every solution the same assembly.
    fn is_empty(&self) -> bool {
        self.frames.is_empty() && self.points.is_empty() && self.vectors.is_empty()
    }

    /// How many numbers are compared: a frame's origin and rotation (a quaternion's four
    /// components in space, a unit complex's two in the plane), each point's and vector's
    /// coordinates.
    fn coordinates(&self, cx: &Context<'_>) -> usize {
        let dims = cx.space.coordinates().len();
        let rotation = if dims == 3 { 4 } else { 2 };
        self.frames.len() * (dims + rotation) + (self.points.len() + self.vectors.len()) * dims
    }

    /// `fingerprint`: a solution's sum of what is compared (a rotation's by the absolute
    /// values of its components) and its scale.
    fn fingerprint(&self, w: &mut Writer) {
        w.line("/// The sum of what `same_assembly` compares of `s`, and the scale of its points.");
        w.line("#[allow(dead_code)]");
        if self.is_empty() {
            w.open("fn fingerprint(_: &Solution) -> Kept {");
            w.line("(0.0, 1.0)");
            w.close("}");
            w.line("");
            return;
        }
        w.open("fn fingerprint(s: &Solution) -> Kept {");
        w.line("let mut sum = 0.0;");
        let sized = !self.frames.is_empty() || !self.points.is_empty();
        if sized {
            w.line("let mut size = 0.0f64;");
        }
        // A loop over the accessors of a kind, or for one, its statements alone (clippy
        // would call a loop over one element a mistake).
        let each = |w: &mut Writer, names: &[String], var: &str, body: &[&str]| {
            if let [one] = names {
                w.line(&format!("let {var} = s.{one}();"));
                body.iter().for_each(|line| w.line(line));
                return;
            }
            let list = (names.iter())
                .map(|n| format!("s.{n}()"))
                .collect::<Vec<_>>()
                .join(", ");
            w.open(&format!("for {var} in [{list}] {{"));
            body.iter().for_each(|line| w.line(line));
            w.close("}");
        };
        if !self.frames.is_empty() {
            let body = [
                "sum += f.placement_sum();",
                "size = size.max(f.origin.coords.amax());",
            ];
            each(w, &self.frames, "f", &body);
        }
        if !self.points.is_empty() {
            let body = [
                "sum += p.coords.sum();",
                "size = size.max(p.coords.amax());",
            ];
            each(w, &self.points, "p", &body);
        }
        if !self.vectors.is_empty() {
            each(w, &self.vectors, "v", &["sum += v.sum();"]);
        }
        if sized {
            w.line("(sum, 1.0 + size)");
        } else {
            w.line("(sum, 1.0)");
        }
        w.close("}");
        w.line("");
    }

    /// `same_assembly`: whether two solutions agree in every frame, point and vector, read one
    /// at a time until two differ, the last declared first (a chain's far links, which the
    /// most branches move).
    fn same_assembly(&self, w: &mut Writer, cx: &Context<'_>) {
        use super::api::Ty;
        w.line("/// Whether two solutions are one assembly: every body's frame, point and vector within");
        w.line("/// a relative `gcs_runtime::tol::SAME_ASSEMBLY_REL` (`tol` for positions, of the model's");
        w.line("/// size), read one at a time until two differ, the last declared first (a chain's far");
        w.line("/// links, which the most branches move).");
        w.line("#[allow(dead_code)]");
        if self.is_empty() {
            w.open("fn same_assembly(_: &Solution, _: &Solution, _: f64) -> bool {");
            w.line("true");
            w.close("}");
            w.line("");
            return;
        }
        // Positions read `tol`; directions and rotations their own `SAME_ASSEMBLY_REL`.
        let tol = if self.frames.is_empty() && self.points.is_empty() {
            "_"
        } else {
            "tol"
        };
        w.open(&format!(
            "fn same_assembly(a: &Solution, b: &Solution, {tol}: f64) -> bool {{"
        ));
        if !self.points.is_empty() {
            let ty = Ty::Point.rust(cx);
            w.line(&format!(
                "let at = |p: {ty}, q: {ty}| (p - q).amax() <= tol;"
            ));
        }
        if !self.vectors.is_empty() {
            let ty = Ty::Vector.rust(cx);
            w.line(&format!(
                "let near = |u: {ty}, v: {ty}| (u - v).amax() <= gcs_runtime::tol::SAME_ASSEMBLY_REL;"
            ));
        }
        // A statement each, not one `&&` chain, which rustc would recurse through; the
        // frames first (a body's frame says most), each kind the last declared first.
        for f in self.frames.iter().rev() {
            w.open(&format!("if !a.{f}().same_placement(&b.{f}(), tol) {{"));
            w.line("return false;");
            w.close("}");
        }
        for p in self.points.iter().rev() {
            w.open(&format!("if !at(a.{p}(), b.{p}()) {{"));
            w.line("return false;");
            w.close("}");
        }
        for v in self.vectors.iter().rev() {
            w.open(&format!("if !near(a.{v}(), b.{v}()) {{"));
            w.line("return false;");
            w.close("}");
        }
        w.line("true");
        w.close("}");
        w.line("");
    }
}
