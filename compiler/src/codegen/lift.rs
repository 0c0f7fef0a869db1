//! Lifting the data of a large model's pieces out of their code, as the step emitter writes it.
//!
//! A large model's solve is laid out as a few functions and tables of their data (`tabled`):
//! the pieces of the plan that differ only in their constants, the names their errors give, the
//! inputs they read and the slots of the store they work on share one function. What varies
//! is lifted into the piece's *row* at the one place each kind of datum is written: a float
//! literal ([`super::writer::float`]), a string literal ([`super::writer::lit`]), a param, a
//! branch variable or a default ([`param`], [`branch`], [`default`]), a store slot ([`slot`]).
//! Nothing is read back from the generated text.
//!
//! While a piece is written [`canonical`]ly, each datum is recorded as a [`Hole`] and written
//! as a placeholder: with the piece's locals numbered (a numbered `Namer`) and its comments
//! left out, the text is the piece's canonical form, equal for two pieces exactly when one
//! function computes both from their rows. The representative of each shape is then written
//! again with its own names ([`render`]), each hole as the literal itself where every row has
//! the same value, else as a read of the row; the emitter must write the same holes in the
//! same order both times, which `render` checks.
//!
//! Outside those two scopes (the flat solve, the API) every datum is written as it is.

use std::cell::RefCell;

/// A datum of a piece that its row may hold, in the order the code writes it.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) enum Hole {
    /// A float literal, by its bits (so that equal means the same literal).
    Float(u64),
    /// A string literal's content.
    Text(String),
    /// A param, by its index in model order.
    Param(usize),
    /// A branch variable, by its index in the plan.
    Branch(usize),
    /// A default, by its index in the plan.
    Default(usize),
    /// A slot of the store.
    Slot(u32),
}

/// The column of a row a kind of hole is read from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(super) enum Column {
    /// Floats: `row.k`.
    K,
    /// String ids: `row.text`.
    Text,
    /// Indices of params, branch variables and defaults: `row.input`.
    Input,
    /// Store slots: `row.at`.
    At,
}

impl Hole {
    /// The column of a row that holds it.
    pub(super) fn column(&self) -> Column {
        match self {
            Hole::Float(_) => Column::K,
            Hole::Text(_) => Column::Text,
            Hole::Param(_) | Hole::Branch(_) | Hole::Default(_) => Column::Input,
            Hole::Slot(_) => Column::At,
        }
    }
}

/// How the representative writes a hole.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Rendering {
    /// As the datum itself: every row has the same.
    Fixed,
    /// Read from entry `n` of its column of the row.
    Row(usize),
}

/// What the current scope does with holes.
enum Mode {
    /// Records each and writes its placeholder.
    Canonical(Vec<Hole>),
    /// Writes each as `renderings` says, checking that it is the one `expected` next.
    Render {
        expected: Vec<Hole>,
        renderings: Vec<Rendering>,
        at: usize,
        /// The first datum written other than the one expected, if any.
        mismatch: Option<String>,
    },
}

thread_local! {
    /// The scope being written, if any: code generation runs on one thread, and a scope is
    /// set and cleared by [`canonical`] and [`render`] only, so that the emitter's literal
    /// writers need no argument to know where a datum goes.
    static SCOPE: RefCell<Option<Mode>> = const { RefCell::new(None) };
}

/// Clears the scope when dropped, so that an unwinding bug leaves none behind.
struct Clear;

impl Drop for Clear {
    fn drop(&mut self) {
        SCOPE.with(|s| s.borrow_mut().take());
    }
}

/// Runs `write` with every datum it writes recorded and written as a placeholder: its text is
/// then the canonical form, the holes the row.
pub(super) fn canonical<R>(write: impl FnOnce() -> R) -> (R, Vec<Hole>) {
    SCOPE.with(|s| {
        let previous = s.borrow_mut().replace(Mode::Canonical(Vec::new()));
        assert!(previous.is_none(), "bug in gcs: lift scopes do not nest");
    });
    let clear = Clear;
    let out = write();
    let holes = SCOPE.with(|s| match s.borrow_mut().take() {
        Some(Mode::Canonical(holes)) => holes,
        _ => Vec::new(),
    });
    drop(clear);
    (out, holes)
}

/// Runs `write`, which must write the holes `expected` in order, each as `renderings` says;
/// `Err` says where it wrote other data (a bug in the emitter: its two spellings differ).
pub(super) fn render<R>(
    expected: &[Hole],
    renderings: &[Rendering],
    write: impl FnOnce() -> R,
) -> Result<R, String> {
    SCOPE.with(|s| {
        let previous = s.borrow_mut().replace(Mode::Render {
            expected: expected.to_vec(),
            renderings: renderings.to_vec(),
            at: 0,
            mismatch: None,
        });
        assert!(previous.is_none(), "bug in gcs: lift scopes do not nest");
    });
    let clear = Clear;
    let out = write();
    let mismatch = SCOPE.with(|s| match s.borrow_mut().as_mut() {
        Some(Mode::Render {
            at,
            expected,
            mismatch,
            ..
        }) => mismatch.take().or_else(|| {
            (*at != expected.len()).then(|| {
                format!(
                    "a piece's representative writes {} data where its canonical form has {}",
                    at,
                    expected.len()
                )
            })
        }),
        _ => None,
    });
    drop(clear);
    match mismatch {
        Some(why) => Err(why),
        None => Ok(out),
    }
}

/// Where the datum `hole` goes: `None` outside a scope (written as it is); else the code that
/// stands for it. `fixed` is its code when every row has the same, `row` its read from entry
/// `n` of its column.
fn hole(
    hole: Hole,
    fixed: impl FnOnce() -> String,
    row: impl FnOnce(usize) -> String,
) -> Option<String> {
    SCOPE.with(|s| {
        let mut scope = s.borrow_mut();
        match scope.as_mut()? {
            Mode::Canonical(holes) => {
                // A datum equal to one already written is the same hole: the emitter may
                // share code by its text (a circle built once for two steps), and equal data
                // must then read alike in the canonical form as in the representative.
                let index = match holes.iter().position(|h| *h == hole) {
                    Some(index) => index,
                    None => {
                        holes.push(hole.clone());
                        holes.len() - 1
                    }
                };
                let tag = match hole.column() {
                    Column::K => 'k',
                    Column::Text => 't',
                    Column::Input => 'i',
                    Column::At => 'a',
                };
                // Canonical text is compared, never compiled: a placeholder of the datum's
                // kind, numbered so that two texts agree only where their data line up.
                Some(format!("${tag}{index}"))
            }
            Mode::Render {
                expected,
                renderings,
                at,
                mismatch,
            } => {
                if let Some(i) = expected[..*at].iter().position(|h| *h == hole) {
                    return Some(match renderings[i] {
                        Rendering::Fixed => fixed(),
                        Rendering::Row(n) => row(n),
                    });
                }
                let i = *at;
                if expected.get(i) != Some(&hole) {
                    mismatch.get_or_insert_with(|| {
                        format!(
                            "a piece's representative writes {hole:?} where its canonical form has {:?}",
                            expected.get(i)
                        )
                    });
                    return Some(fixed());
                }
                *at += 1;
                Some(match renderings[i] {
                    Rendering::Fixed => fixed(),
                    Rendering::Row(n) => row(n),
                })
            }
        }
    })
}

/// A float literal's code in a scope (see [`super::writer::float`]).
pub(super) fn float(v: f64, literal: impl FnOnce() -> String) -> Option<String> {
    hole(Hole::Float(v.to_bits()), literal, |n| format!("row.k[{n}]"))
}

/// A string literal's code in a scope (see [`super::writer::lit`]).
pub(super) fn text(s: &str, literal: impl FnOnce() -> String) -> Option<String> {
    hole(Hole::Text(s.to_string()), literal, |n| {
        format!("text(row.text[{n}])")
    })
}

/// The code of param `index`, field `field` of `Params`.
pub(super) fn param(index: usize, field: &str) -> String {
    hole(
        Hole::Param(index),
        || format!("params.{field}"),
        |n| format!("p[row.input[{n}] as usize]"),
    )
    .unwrap_or_else(|| format!("params.{field}"))
}

/// The code of branch variable `index`, field `field` of `Branches` in a flat module: a large
/// model's `Branches` holds them in an array.
pub(super) fn branch(index: usize, field: &str) -> String {
    hole(
        Hole::Branch(index),
        || format!("branches.indices[{index}]"),
        |n| format!("branches.indices[row.input[{n}] as usize]"),
    )
    .unwrap_or_else(|| format!("branches.{field}"))
}

/// The code of default `index`, field `field` of `Defaults` in a flat module (an array in a
/// large model's).
pub(super) fn default(index: usize, field: &str) -> String {
    hole(
        Hole::Default(index),
        || format!("defaults.values[{index}]"),
        |n| format!("defaults.values[row.input[{n}] as usize]"),
    )
    .unwrap_or_else(|| format!("defaults.{field}"))
}

/// The code of the index of slot `index` of the store (only in a scope: a flat solve has no
/// store).
pub(super) fn slot(index: u32) -> String {
    hole(
        Hole::Slot(index),
        || index.to_string(),
        |n| format!("row.at[{n}] as usize"),
    )
    .unwrap_or_else(|| index.to_string())
}

/// For each hole of a shape, how its representative writes it, given every row's holes (in
/// the same order and of the same kinds): fixed where every row has the same datum, else an
/// entry of its column, shared by holes that agree in every row. Also the number of entries of
/// each column.
pub(super) fn renderings(rows: &[&[Hole]]) -> (Vec<Rendering>, [usize; 4]) {
    let Some(first) = rows.first() else {
        return (Vec::new(), [0; 4]);
    };
    let n = first.len();
    let mut out: Vec<Rendering> = Vec::with_capacity(n);
    let mut counts = [0usize; 4];
    // The first hole of each distinct column of values, by its values in every row.
    let mut seen: rustc_hash::FxHashMap<Vec<&Hole>, usize> = Default::default();
    for i in 0..n {
        let column: Vec<&Hole> = rows.iter().map(|r| &r[i]).collect();
        if column.iter().all(|h| *h == column[0]) {
            out.push(Rendering::Fixed);
            continue;
        }
        match seen.get(&column) {
            Some(&j) => out.push(out[j]),
            None => {
                let c = first[i].column() as usize;
                out.push(Rendering::Row(counts[c]));
                counts[c] += 1;
                seen.insert(column, i);
            }
        }
    }
    (out, counts)
}

/// The entries of one row, per column, as `renderings` lays them out.
pub(super) fn row_entries(holes: &[Hole], renderings: &[Rendering], counts: [usize; 4]) -> Row {
    let mut row = Row {
        k: vec![0.0; counts[Column::K as usize]],
        text: vec![String::new(); counts[Column::Text as usize]],
        input: vec![0; counts[Column::Input as usize]],
        at: vec![0; counts[Column::At as usize]],
    };
    for (h, r) in holes.iter().zip(renderings) {
        let Rendering::Row(n) = *r else {
            continue;
        };
        match h {
            Hole::Float(bits) => row.k[n] = f64::from_bits(*bits),
            Hole::Text(s) => row.text[n] = s.clone(),
            Hole::Param(i) | Hole::Branch(i) | Hole::Default(i) => row.input[n] = *i as u32,
            Hole::Slot(s) => row.at[n] = *s,
        }
    }
    row
}

/// One row of a shape's tables: its entries in each column.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Row {
    pub(super) k: Vec<f64>,
    pub(super) text: Vec<String>,
    pub(super) input: Vec<u32>,
    pub(super) at: Vec<u32>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outside_a_scope_data_are_written_as_they_are() {
        assert_eq!(float(1.5, || "1.5".into()), None);
        assert_eq!(param(0, "theta"), "params.theta");
        assert_eq!(branch(2, "elbow"), "branches.elbow");
    }

    #[test]
    fn a_canonical_scope_records_holes_and_writes_placeholders() {
        let (text, holes) = canonical(|| {
            let a = float(1.5, || "1.5".into()).unwrap_or_default();
            let b = text("elbow", || "\"elbow\"".into()).unwrap_or_default();
            format!("{a} {b} {}", param(3, "theta"))
        });
        assert_eq!(text, "$k0 $t1 $i2");
        assert_eq!(
            holes,
            [
                Hole::Float(1.5f64.to_bits()),
                Hole::Text("elbow".into()),
                Hole::Param(3)
            ]
        );
        // The scope is closed.
        assert_eq!(param(3, "theta"), "params.theta");
    }

    #[test]
    fn equal_data_are_one_hole() {
        let (text, holes) = canonical(|| {
            let a = float(2.0, || "2.0".into()).unwrap_or_default();
            let b = float(3.0, || "3.0".into()).unwrap_or_default();
            let c = float(2.0, || "2.0".into()).unwrap_or_default();
            format!("{a} {b} {c}")
        });
        assert_eq!(text, "$k0 $k1 $k0");
        assert_eq!(holes.len(), 2);
    }

    #[test]
    fn renderings_fix_what_every_row_shares_and_share_columns_that_agree() {
        let f = |v: f64| Hole::Float(v.to_bits());
        let a = [f(1.0), f(2.0), Hole::Slot(4)];
        let b = [f(1.0), f(3.0), Hole::Slot(5)];
        let (r, counts) = renderings(&[&a, &b]);
        assert_eq!(r, [Rendering::Fixed, Rendering::Row(0), Rendering::Row(0)]);
        assert_eq!(counts, [1, 0, 0, 1]);
        let row = row_entries(&b, &r, counts);
        assert_eq!((row.k, row.at), (vec![3.0], vec![5]));
        let text = render(&b, &r, || {
            let x = float(1.0, || "1.0".into()).unwrap_or_default();
            let y = float(3.0, || "3.0".into()).unwrap_or_default();
            let z = float(3.0, || "3.0".into()).unwrap_or_default();
            format!("{x} {y} {z} {}", slot(5))
        });
        assert_eq!(
            text.as_deref(),
            Ok("1.0 row.k[0] row.k[0] row.at[0] as usize")
        );
    }

    #[test]
    fn a_representative_that_writes_other_data_is_refused() {
        let expected = [Hole::Float(1.0f64.to_bits())];
        let other = render(&expected, &[Rendering::Fixed], || {
            float(2.0, || "2.0".into());
        });
        assert!(other.is_err_and(|why| why.contains("representative writes Float")));
        let fewer = render(&expected, &[Rendering::Fixed], || ());
        assert!(fewer.is_err_and(|why| why.contains("writes 0 data")));
        // The scope is closed either way.
        assert_eq!(param(3, "theta"), "params.theta");
    }
}
