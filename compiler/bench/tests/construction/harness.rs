//! The construction checker's harness, shared by the plane's (`construction.rs`) and space's
//! (`construction3d.rs`): the classification of an entry, the solving and verifying of its
//! instances, the defaults' checker, the test itself, and the writer of the fragment table.
//!
//! What differs between the two spaces is a [`Space`]: the geom kinds, their states and
//! constraint forms, how an instance is made, the plan's op names, how a solution is verified,
//! and the table's words. Each test file implements it and keeps only its space's cases; the
//! method is described in their headers.

use gcs_bench::baseline::{Method, Numeric, Options};
use gcs_compiler::analyse;
use gcs_compiler::analysis::Analysis;
use gcs_compiler::plan::{DefaultVar, Op};
use gcs_compiler::solution::Solution;
use gcs_lang::constraints::ConstraintKind as CK;
use gcs_lang::model::ConstraintId;
use gcs_lang::Model;
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::fmt::Write as _;

// ---------------------------------------------------------------- a deterministic RNG

/// xorshift64*, seeded through splitmix64. Each space adds its own `unit` and `point` (and
/// what else it draws) in an `impl Rng` of its own.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        let mut z = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        Rng(z | 1)
    }
    pub fn next(&mut self) -> u64 {
        let mut x = self.0;
        x ^= x >> 12;
        x ^= x << 25;
        x ^= x >> 27;
        self.0 = x;
        x.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    pub fn f(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.f()
    }
    pub fn sign(&mut self) -> f64 {
        if self.next() & 1 == 0 {
            1.0
        } else {
            -1.0
        }
    }
    pub fn angle(&mut self) -> f64 {
        self.range(-PI, PI)
    }
    pub fn log_range(&mut self, a: f64, b: f64) -> f64 {
        (a.ln() + (b.ln() - a.ln()) * self.f()).exp()
    }
}

// ---------------------------------------------------------------- what a space gives

/// One space's checker: its geom kinds, their states and constraint forms, how an instance is
/// made, and what the plan, the verification and the table say there.
pub trait Space: Sized + 'static {
    type Kind: GeomKind;
    type Form: ConstraintForm;
    /// What a state records of the motion its prefix leaves `P`, for tangent instances (`()`
    /// where `make` works it out from the prefix).
    type StateMotion: Copy + Send + Sync;
    /// The space's numeric baseline (`gcs_bench::baseline::Baseline` or `Baseline3`).
    type Baseline: Numeric;

    /// Every kind, in the table's order.
    const KINDS: &'static [Self::Kind];
    /// Random instances per checked entry.
    const N_RANDOM: usize;
    /// The space's own near-degenerate modes, run after the tangent ones (see [`degenerate`]).
    const OWN_MODES: &'static [Mode] = &[];
    /// The known causes of wrong runs.
    const KNOWN_WRONG: &'static [Known] = &[];
    /// The known causes of degenerate refusals of valid sketches: instances refused as
    /// degenerate where the baseline finds an isolated assembly near the sketch (see
    /// `Judged::Near`).
    const KNOWN_DEGENERATE: &'static [Known] = &[];
    /// The table's file and words.
    const TABLE: Table;
    /// Whether a state may take fewer defaults than `P`'s DOF (a relation pending at the first
    /// default, and solved after it); never more. Otherwise exactly as many.
    const FEWER_DEFAULTS: bool = false;
    /// Whether a solve that panics on an inconsistent instance counts as refusing it, rather
    /// than failing the test.
    const SOLVE_PANIC_REFUSES: bool = false;
    /// Whether a NaN residual in the defaults' checker counts as off, rather than passed over.
    const NAN_DEFAULT_WRONG: bool = false;

    /// The states of a kind, and the last-constraint forms that apply to it.
    fn catalogue(kind: Self::Kind) -> (Vec<State<Self>>, Vec<Self::Form>);
    /// Whether `last` is probed after `prefix`.
    fn probed(_prefix: &[Self::Form], _last: Self::Form) -> bool {
        true
    }
    /// Instance `seed` of an entry, in `mode`.
    fn make(e: &Entry<Self>, seed: u64, mode: Mode) -> Instance;
    /// An op's kind as a fragment lists it (`None`: not listed); [`op_name`] names the ops both
    /// spaces name alike.
    fn op_name(op: &Op) -> Option<String>;
    /// Whether the op, right after the step that satisfies `z`, closes the record (a settle,
    /// part of the fragment when it satisfies part of the prefix).
    fn settles(_op: &Op) -> bool {
        false
    }
    /// Whether the op is a turn that a check right after it completes: the check is then part
    /// of a fragment.
    fn turns(_op: &Op) -> bool {
        false
    }
    /// The claimed constraints' residuals beyond tolerance in a solution, as
    /// `(relative residual, words)`.
    fn violations(v: &Solved<'_>) -> Vec<(f64, String)>;
    /// Whether a default is an angle (moved by 0.25 rad, not 0.25 of the size).
    fn angle_default(d: &DefaultVar) -> bool;
    /// The space's numeric baseline of a model (`gcs_bench::baseline`), which judges the
    /// instances the plans refuse as degenerate.
    fn baseline(model: &Model) -> Result<Self::Baseline, String>;
}

/// A kind of the probed geom `P`.
pub trait GeomKind: Copy + Ord + Send + Sync {
    /// The kind as the table names it.
    fn name(self) -> &'static str;
}

/// A constraint between a feature of `P` and a new fixed geom (or a unary one).
pub trait ConstraintForm: Copy + Send + Sync {
    /// The form as it reads in the table (fixed geoms by their kind).
    fn text(self) -> String;
}

/// What sets one space's table apart: its file and words, and the parts the 2d table predates.
pub struct Table {
    /// The test, `compiler/bench/tests/{test}.rs`.
    pub test: &'static str,
    /// The command that writes the table.
    pub command: &'static str,
    /// The table's file under `docs/`.
    pub file: &'static str,
    pub title: &'static str,
    /// The introduction's words on the probe's members, after the sentence on the probe.
    pub members: &'static str,
    /// The introduction's words on the near-degenerate instances.
    pub degenerate: &'static str,
    /// The introduction's last words.
    pub last: &'static str,
    /// The end of the sentence on the instances no branch solved.
    pub unsolved: &'static str,
    /// Where the analysis adds its defaults.
    pub defaults_source: &'static str,
    /// An example of a freedom left unparameterized.
    pub refused_example: &'static str,
    /// Whether the totals end saying that every plan passed the plan validator.
    pub validated: bool,
    /// Whether the totals count failed analyses, entries that rarely solve and known wrong
    /// runs, the instances no branch solved are given by mode (with the first few examples),
    /// and the entries that rarely solve are listed.
    pub detailed: bool,
}

/// A known cause of wrong runs (or of degenerate refusals of valid sketches): what the plans
/// do wrong, the instance modes its runs show in (`analysis` for a plan the analysis could not
/// build), and the entries it affects, by `kind | state | constraint form` as the table writes
/// them.
#[allow(dead_code)] // the plane's checker knows none
pub struct Known {
    pub why: &'static str,
    pub modes: &'static [&'static str],
    pub entries: &'static [&'static str],
}

/// A state of `P`: a prefix of constraints with fixed geoms, and what it leaves.
pub struct State<S: Space> {
    pub name: &'static str,
    pub prefix: Vec<S::Form>,
    pub motion: S::StateMotion,
}

/// One row of the table: a state of a kind, and the last constraint `z`.
pub struct Entry<S: Space> {
    pub kind: S::Kind,
    pub state: &'static str,
    pub prefix: Vec<S::Form>,
    #[allow(dead_code)] // space works it out from the prefix
    pub motion: S::StateMotion,
    pub last: S::Form,
}

impl<S: Space> Entry<S> {
    /// The key `KNOWN_WRONG` lists it by.
    pub fn key(&self) -> String {
        format!(
            "{} | {} | {}",
            self.kind.name(),
            self.state,
            self.last.text()
        )
    }
}

/// Every entry: each form after each state of each kind, as the space probes them.
fn entries<S: Space>() -> Vec<Entry<S>> {
    let mut out = Vec::new();
    for &kind in S::KINDS {
        let (states, forms) = S::catalogue(kind);
        for s in &states {
            for &f in &forms {
                if !S::probed(&s.prefix, f) {
                    continue;
                }
                out.push(Entry {
                    kind,
                    state: s.name,
                    prefix: s.prefix.clone(),
                    motion: s.motion,
                    last: f,
                });
            }
        }
    }
    out
}

// ---------------------------------------------------------------- instances

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// A random rigid motion of the sketch (moderate or small), and a dimension change.
    Random,
    /// The new locus tangent to the motion the prefix leaves.
    Tangent,
    /// Nearly tangent.
    NearTangent,
    /// `n`'s z axis nearly parallel to `m`'s (a body's markers, in space).
    #[allow(dead_code)] // not in the plane
    NearParallel,
    /// `n` and `a` at `m`'s point (a body's markers, in space).
    #[allow(dead_code)] // not in the plane
    Coincident,
    /// The sketch exactly at the target.
    Exact,
    /// The sketch 1e-9 (relative) from the target.
    Tiny,
    /// Everything scaled.
    Scale(f64),
    /// The prefix derived from a target moved by 1e-2: no solution (for checks only).
    Inconsistent,
}

impl Mode {
    pub fn name(self) -> String {
        match self {
            Mode::Random => "random".into(),
            Mode::Tangent => "tangent".into(),
            Mode::NearTangent => "near-tangent".into(),
            Mode::NearParallel => "nearly parallel axes".into(),
            Mode::Coincident => "coincident markers".into(),
            Mode::Exact => "exact".into(),
            Mode::Tiny => "tiny".into(),
            Mode::Scale(k) => format!("scale {k:e}"),
            Mode::Inconsistent => "inconsistent".into(),
        }
    }
}

pub struct Instance {
    pub text: String,
    pub prefix_text: String,
    /// The model with every joint written as its parts (labelled `{label}__{i}`), where the
    /// space writes one.
    pub split_text: Option<String>,
    pub scale: f64,
}

/// Writes numbers, tracking the largest length for the tolerance.
pub struct Out {
    pub scale: f64,
}

impl Out {
    /// A length.
    pub fn l(&mut self, x: f64) -> String {
        self.scale = self.scale.max(x.abs());
        format!("{x:?}")
    }
    /// A point.
    pub fn p<const N: usize>(&mut self, p: [f64; N]) -> String {
        let xs: Vec<String> = p.iter().map(|x| self.l(*x)).collect();
        format!("({})", xs.join(", "))
    }
    /// An angle.
    pub fn a(&mut self, x: f64) -> String {
        format!("{x:?}")
    }
    /// A direction.
    pub fn d<const N: usize>(&mut self, v: [f64; N]) -> String {
        let xs: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
        format!("({})", xs.join(", "))
    }
}

/// The statements of an instance as `make` collects them: the fixed geoms' declarations, the
/// prefix's constraints, `z`, and (where the space writes one) the model with every joint
/// written as its parts.
#[derive(Default)]
pub struct Statements {
    pub decls: Vec<String>,
    pub prefix: Vec<String>,
    pub last: Vec<String>,
    pub split: Vec<String>,
}

impl Statements {
    /// The instance: `head` (the space, and a fixed origin, so that no model is grounded at its
    /// probe's sketch), the fixed geoms, the declaration of `P`, then the constraints.
    pub fn instance(&self, head: &str, probe: &str, scale: f64) -> Instance {
        let head = format!("{head}\n{}\n{probe}\n", self.decls.join("\n"));
        let prefix_text = format!("{head}{}\n", self.prefix.join("\n"));
        let text = format!("{prefix_text}{}\n", self.last.join("\n"));
        let split_text =
            (!self.split.is_empty()).then(|| format!("{head}{}\n", self.split.join("\n")));
        Instance {
            text,
            prefix_text,
            split_text,
            scale,
        }
    }
}

/// The size of an instance, which its lengths are drawn relative to.
pub fn size(rng: &mut Rng, mode: Mode) -> f64 {
    let k = match mode {
        Mode::Scale(k) => k,
        _ => 1.0,
    };
    k * rng.range(0.5, 2.0)
}

/// The target the prefix is derived from: the target `t`, or in an inconsistent instance `t`
/// nudged, so that the prefix places `P` slightly elsewhere than `z` wants it.
pub fn prefix_target<C>(mode: Mode, t: C, nudged: impl FnOnce(C) -> C) -> C {
    if mode == Mode::Inconsistent {
        nudged(t)
    } else {
        t
    }
}

/// The motion the prefix leaves that a new locus is made tangent to, and the angle it is off
/// it: tangent, or nearly (1e-9 to 1e-4 rad); none in other modes.
pub fn off_tangent<T>(mode: Mode, tangent: Option<T>, rng: &mut Rng) -> Option<(T, f64)> {
    match (mode, tangent) {
        (Mode::Tangent, Some(t)) => Some((t, 0.0)),
        (Mode::NearTangent, Some(t)) => Some((t, rng.log_range(1e-9, 1e-4))),
        _ => None,
    }
}

/// How far the sketch is from the target: the scale of the rigid motion (and dimension
/// change) applied to the target.
pub fn sketch_motion(mode: Mode, rng: &mut Rng) -> f64 {
    match mode {
        Mode::Exact => 0.0,
        Mode::Tiny => 1e-9,
        Mode::Inconsistent => 1e-3,
        _ => {
            if rng.sign() > 0.0 {
                rng.range(0.05, 1.0)
            } else {
                rng.log_range(1e-4, 1e-2)
            }
        }
    }
}

// ---------------------------------------------------------------- classification

fn load(text: &str) -> Model {
    let (_, model, diags) = gcs_lang::load("probe.gcs", text.as_bytes());
    match model {
        Some(m) if !diags.iter().any(|d| d.is_error()) => m,
        _ => panic!(
            "the checker wrote an invalid model: {:?}\n{text}",
            diags.iter().map(|d| d.message.clone()).collect::<Vec<_>>()
        ),
    }
}

fn label(model: &Model, l: &str) -> Option<ConstraintId> {
    model
        .constraints
        .iter()
        .find(|(_, c)| c.label.as_deref() == Some(l))
        .map(|(id, _)| id)
}

/// The record of `P`'s cluster: signature and DOF.
fn record_of(model: &Model, a: &Analysis) -> String {
    let p = model.geom_named("P").expect("P");
    match a.undefaulted.iter().find(|c| c.geoms.contains(&p)) {
        Some(c) => format!("{} ({} DOF)", c.signature(), c.dof),
        None => "?".into(),
    }
}

/// The ops both spaces name alike, as a fragment lists them.
pub fn op_name(op: &Op) -> Option<String> {
    Some(match op {
        Op::Intersect { meet, .. } => format!("intersect {meet:?}"),
        Op::Onto { .. } => "onto".into(),
        Op::Nearest { .. } => "nearest".into(),
        Op::Translate { .. } => "translate".into(),
        Op::Check { .. } => "check".into(),
        Op::ParallelLine { .. } => "parallel line".into(),
        Op::ShiftedCircle { .. } => "shifted circle".into(),
        Op::SetDim { .. } => "set dimension".into(),
        Op::DirectionTo { .. } => "direction to".into(),
        Op::Default(_) => "default".into(),
        Op::LocusPoint { .. } => "point on locus".into(),
        Op::Close { .. } => "close by iteration".into(),
        _ => return None,
    })
}

#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Outcome {
    Fragment(String),
    Check,
    Recorded,
    NotYet(String),
    /// The prefix does not reach the state.
    Unreached(String),
    /// The analysis failed (a malformed plan): a bug, counted as wrong.
    Failed(String),
}

impl Outcome {
    fn text(&self) -> String {
        match self {
            Outcome::Fragment(ops) => format!("fragment: {ops}"),
            Outcome::Check => "check".into(),
            Outcome::Recorded => "recorded (satisfied when placed)".into(),
            Outcome::NotYet(r) => format!("not yet: {r}"),
            Outcome::Unreached(r) => format!("state not reached: {r}"),
            Outcome::Failed(r) => format!("**analysis failed**: {r}"),
        }
    }
    fn checked(&self) -> bool {
        matches!(self, Outcome::Fragment(_) | Outcome::Check)
    }
}

struct Class {
    outcome: Outcome,
    before: String,
    after: String,
    note: String,
}

fn classify<S: Space>(e: &Entry<S>, inst: &Instance) -> Class {
    let pm = load(&inst.prefix_text);
    let model = load(&inst.text);
    let failed = |why: String| Class {
        outcome: Outcome::Failed(why),
        before: "?".into(),
        after: "?".into(),
        note: String::new(),
    };
    let pa = match analyse(&pm) {
        Ok(a) => a,
        Err(err) => return failed(format!("the prefix: {err}")),
    };
    let before = record_of(&pm, &pa);
    let a = match analyse(&model) {
        Ok(a) => a,
        Err(err) => return failed(err.to_string()),
    };
    let after = record_of(&model, &a);
    let z = label(&model, "z").expect("z");
    let mut note = String::new();
    if let Some(u) = pa.unsolved.first() {
        return Class {
            outcome: Outcome::Unreached(format!(
                "{}: {}",
                pm.constraints[u.constraint].text, u.reason
            )),
            before,
            after,
            note,
        };
    }
    if let Some(u) = a.unsolved.iter().find(|u| u.constraint == z) {
        return Class {
            outcome: Outcome::NotYet(u.reason.clone()),
            before,
            after,
            note,
        };
    }
    if let Some(u) = a.unsolved.first() {
        let _ = write!(
            note,
            "prefix constraint {} no longer solved",
            model.constraints[u.constraint].text
        );
    }
    let steps = &a.plan.steps;
    // The first default the analysis adds for the freedom left: a step satisfying z after it
    // is a fragment that needs the default (the defaults alone are probed below).
    let defaulted = (steps.iter())
        .position(|s| matches!(s.op, Op::Default(_)))
        .unwrap_or(steps.len());
    let Some(j) = steps.iter().position(|s| s.satisfies.contains(&z)) else {
        assert!(
            a.recorded.contains(&z),
            "z is neither satisfied nor recorded"
        );
        return Class {
            outcome: Outcome::Recorded,
            before,
            after,
            note,
        };
    };
    if matches!(steps[j].op, Op::Check { .. }) {
        // A turn about an axis checked where the cone must agree is a fragment and a check.
        let turned = steps[..j]
            .iter()
            .rev()
            .take_while(|s| s.satisfies.is_empty())
            .any(|s| S::turns(&s.op));
        if !turned {
            return Class {
                outcome: Outcome::Check,
                before,
                after,
                note,
            };
        }
    }
    // The fragment starts after the prefix's own steps: after the last step that satisfied
    // something, and after the steps the prefix alone emits (a circle's centre locus).
    let common = steps
        .iter()
        .zip(&pa.plan.steps)
        .take_while(|(x, y)| x == y)
        .count();
    let start = steps[..j]
        .iter()
        .rposition(|s| !s.satisfies.is_empty())
        .map_or(0, |i| i + 1)
        .max(common.min(j));
    let mut ops: Vec<String> = steps[start..=j]
        .iter()
        .filter_map(|s| S::op_name(&s.op))
        .collect();
    let prefix_ids: Vec<ConstraintId> = (0..e.prefix.len())
        .filter_map(|i| label(&model, &format!("p{i}")))
        .collect();
    let last_prefix = steps
        .iter()
        .rposition(|s| s.satisfies.iter().any(|c| prefix_ids.contains(c)));
    match last_prefix {
        Some(i) if i > j => {
            // Only the record closing right after z (a settle) belongs to it.
            let settle = steps[j + 1..]
                .iter()
                .take_while(|s| S::settles(&s.op))
                .count();
            let after_ops: Vec<String> = steps[j + 1..j + 1 + settle]
                .iter()
                .filter(|s| !s.satisfies.is_empty() || s.out.is_some())
                .filter_map(|s| S::op_name(&s.op))
                .collect();
            let closes = steps[j + 1..j + 1 + settle]
                .iter()
                .any(|s| s.satisfies.iter().any(|c| prefix_ids.contains(c)));
            if closes && !after_ops.is_empty() {
                ops.push(format!("then {}", after_ops.join(" + ")));
            }
            if steps[j + 1 + settle..]
                .iter()
                .any(|s| s.satisfies.iter().any(|c| prefix_ids.contains(c)))
            {
                let _ = write!(note, "runs before part of the prefix");
            }
        }
        _ => {}
    }
    if j > defaulted {
        if !note.is_empty() {
            note.push_str("; ");
        }
        note.push_str("after a default");
    }
    Class {
        outcome: Outcome::Fragment(ops.join(" + ")),
        before,
        after,
        note,
    }
}

// ---------------------------------------------------------------- the checker

pub const REL: f64 = 1e-12;

#[derive(Default)]
struct Stats {
    instances: usize,
    runs: usize,
    /// Instances some branch solved, all verified.
    solved: usize,
    /// Instances the default branches solved.
    default_solved: usize,
    /// Random instances (of `N_RANDOM`) some branch solved.
    random_solved: usize,
    /// Instances no branch solved, by error kind.
    unsolved: BTreeMap<String, usize>,
    /// Instances no branch solved, by mode.
    unsolved_modes: BTreeMap<String, usize>,
    /// Instances whose analysis did not claim `z` (classified otherwise).
    reclassified: usize,
    /// Wrong runs: the largest relative residual, the instance's mode, and the details.
    wrong: Vec<(f64, String, String)>,
    /// Inconsistent instances of a check (no solution): run, refused with an error, and the
    /// accepted ones (a solution violating the check's constraint).
    inconsistent: usize,
    inconsistent_refused: usize,
    inconsistent_accepted: Vec<String>,
    /// An example of an unsolved instance.
    unsolved_example: Option<String>,
    /// The instances refused as degenerate, as the baseline judges them.
    degenerate: Vec<Refusal>,
}

/// The near-degenerate modes, after the random instances: the new locus tangent to the motion
/// the prefix leaves (twice), nearly tangent (twice), the space's own, the sketch at the
/// target and 1e-9 from it, and everything scaled by 1e-3 and 1e3.
pub fn degenerate<S: Space>() -> Vec<Mode> {
    let mut modes = vec![
        Mode::Tangent,
        Mode::Tangent,
        Mode::NearTangent,
        Mode::NearTangent,
    ];
    modes.extend(S::OWN_MODES);
    modes.extend([Mode::Exact, Mode::Tiny, Mode::Scale(1e-3), Mode::Scale(1e3)]);
    modes
}

/// A solution a plan returned, for its space to verify.
pub struct Solved<'a> {
    pub model: &'a Model,
    /// The model with every joint written as its parts, or `model` itself where the space
    /// writes none.
    #[allow(dead_code)] // the plane verifies the model itself
    pub split: &'a Model,
    pub sol: &'a Solution,
    /// The constraints the plan's steps claim to satisfy.
    pub claimed: &'a [ConstraintId],
    /// The instance's largest length.
    pub scale: f64,
}

impl Solved<'_> {
    /// The tolerance of a length: `REL` relative to the instance's scale, or to the answer's
    /// own magnitude when it lies farther out (a root far along a parabola's arm, met by a line
    /// nearly tangent to it): its coordinates carry rounding relative to that.
    pub fn tol_len(&self) -> f64 {
        (REL * self.scale.max(f64::MIN_POSITIVE)).max(REL * magnitude_of(self.sol))
    }
}

/// Whether a constraint's residual is an angle (horizontal and vertical are the plane's;
/// parallel_z, offset_z and helical of space).
pub fn angular(k: CK) -> bool {
    matches!(
        k,
        CK::Angle
            | CK::Parallel
            | CK::Perpendicular
            | CK::Horizontal
            | CK::Vertical
            | CK::ParallelZ
            | CK::OffsetZ
            | CK::OffsetX
            | CK::Helical
    )
}

/// Every branch combination (at most 64; beyond, a deterministic sample).
fn combos(counts: &[usize], defaults: &[usize]) -> Vec<Vec<usize>> {
    let mut out = vec![defaults.to_vec()];
    let total: usize = counts.iter().map(|c| (*c).max(1)).product();
    let step = total.div_ceil(64).max(1);
    let mut n = 0;
    while n < total {
        let mut idx = Vec::with_capacity(counts.len());
        let mut r = n;
        for &c in counts {
            let c = c.max(1);
            idx.push(r % c);
            r /= c;
        }
        if idx != defaults {
            out.push(idx);
        }
        n += step;
    }
    out
}

/// The largest coordinate or dimension of a solution.
fn magnitude_of(s: &Solution) -> f64 {
    (s.points.iter().flat_map(|(_, x)| x.iter()))
        .chain(s.scalars.iter().map(|(_, x)| x))
        .fold(0.0, |m: f64, x| m.max(x.abs()))
}

fn panic_text(p: Box<dyn std::any::Any + Send>) -> String {
    p.downcast_ref::<String>()
        .cloned()
        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_default()
}

type Verdict = Result<(), Result<(f64, String), String>>;

fn run_instance<S: Space>(
    entry_id: &str,
    seed: u64,
    mode: Mode,
    inst: &Instance,
    stats: &mut Stats,
) {
    stats.instances += 1;
    let model = load(&inst.text);
    let split = inst.split_text.as_deref().map(load);
    let split = split.as_ref().unwrap_or(&model);
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        let a = analyse(&model).map_err(|e| e.to_string())?;
        let z = label(&model, "z").expect("z");
        let claimed: Vec<ConstraintId> = a
            .plan
            .steps
            .iter()
            .flat_map(|s| s.satisfies.iter().copied())
            .collect();
        let counts: Vec<usize> = a.plan.branches.iter().map(|b| b.count).collect();
        let defaults: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
        let params = model.default_params();
        let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        let mut results: Vec<(Vec<usize>, Verdict)> = Vec::new();
        for combo in combos(&counts, &defaults) {
            // The plan as it is, even when it leaves geoms free (`solve` refuses those): the
            // fragments are what is checked.
            let r = gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo);
            let verdict = match r {
                Ok(sol) => {
                    let bad = S::violations(&Solved {
                        model: &model,
                        split,
                        sol: &sol,
                        claimed: &claimed,
                        scale: inst.scale,
                    });
                    if bad.is_empty() {
                        Ok(())
                    } else {
                        let worst = bad.iter().map(|b| b.0).fold(0.0, f64::max);
                        let words: Vec<String> = bad.into_iter().map(|b| b.1).collect();
                        Err(Ok((worst, words.join("; "))))
                    }
                }
                Err(e) => Err(Err(format!("{:?} {:.3e}", e.kind, e.magnitude))),
            };
            results.push((combo, verdict));
        }
        Ok::<_, String>((claimed.contains(&z), freedom(&a.plan), results))
    }));
    let failure = match outcome {
        Ok(Ok(x)) => Ok(x),
        Ok(Err(e)) => Err(format!("analysis failed: {e}")),
        Err(p) => Err(format!("panic: {}", panic_text(p))),
    };
    let (claims_z, free, results) = match failure {
        Ok(x) => x,
        Err(msg) => {
            stats.wrong.push((
                f64::INFINITY,
                mode.name(),
                format!(
                    "{entry_id}: seed {seed} ({}): {msg}\n```gcs\n{}```",
                    mode.name(),
                    inst.text
                ),
            ));
            return;
        }
    };
    if !claims_z {
        stats.reclassified += 1;
    }
    let mut any = false;
    let mut first_err = None;
    for (i, (combo, v)) in results.iter().enumerate() {
        stats.runs += 1;
        match v {
            Ok(()) => {
                any = true;
                if i == 0 {
                    stats.default_solved += 1;
                }
            }
            Err(Ok((worst, msg))) => {
                stats.wrong.push((
                    *worst,
                    mode.name(),
                    format!(
                        "{entry_id}: seed {seed} ({}), branches {combo:?}: {msg}\n```gcs\n{}```",
                        mode.name(),
                        inst.text
                    ),
                ));
            }
            Err(Err(msg)) => {
                if first_err.is_none() {
                    first_err = Some(msg.clone());
                }
            }
        }
    }
    if any {
        stats.solved += 1;
        if mode == Mode::Random {
            stats.random_solved += 1;
        }
    } else {
        let e =
            first_err.unwrap_or_else(|| "Wrong (every run violated a claimed constraint)".into());
        let kind = e.split(' ').next().unwrap_or("").to_string();
        if kind == "Degenerate" {
            let judged = judge::<S>(&model, split, inst, free);
            stats.degenerate.push(Refusal {
                judged,
                mode: mode.name(),
                words: format!(
                    "{entry_id}: seed {seed} ({}): {e}\n```gcs\n{}```",
                    mode.name(),
                    inst.text
                ),
            });
        }
        *stats.unsolved.entry(kind).or_default() += 1;
        *stats.unsolved_modes.entry(mode.name()).or_default() += 1;
        if stats.unsolved_example.is_none() {
            stats.unsolved_example = Some(format!(
                "seed {seed} ({}): {e}\n```gcs\n{}```",
                mode.name(),
                inst.text
            ));
        }
    }
}

/// An instance no branch solved, the first error `Degenerate`.
struct Refusal {
    judged: Judged,
    /// The instance's mode.
    mode: String,
    /// The entry, seed, mode and error, and the model.
    words: String,
}

/// What the baseline makes of an instance the plans refused (its details are printed by
/// `GCS_ENTRY`, through `Debug`).
#[derive(Clone, Debug)]
#[allow(dead_code)]
enum Judged {
    /// An isolated assembly, verified, whose every point and dimension lies within [`NEAR`]
    /// of the instance's scale of the sketch (and every direction within `NEAR`): how far it
    /// lies, relative to the scale.
    Near(f64),
    /// A verified assembly near the sketch among more assemblies around it than the plan has
    /// free defaults to choose among them ([`freedom`]): a point on two coincident lines,
    /// where the plan has none. The dimension of the assemblies around it, as [`dimension`]
    /// measures it, and the plan's free defaults.
    NotIsolated { dimension: usize, free: usize },
    /// A verified assembly farther from the sketch.
    Far(f64),
    /// No verified assembly (neither method converged, or `verify` found a constraint off).
    Unsolved(String),
    /// The baseline cannot express the model.
    Unexpressed(String),
}

/// How far from the sketch an assembly still counts as near it, relative to the instance's
/// scale: half of it. A random sketch lies up to about the scale from the target it was
/// moved from (a turn of up to 0.6 rad about a point up to the scale away, and a shift), and
/// a near-degenerate one much closer; an assembly within half the scale is one the sketch
/// points at, where a plan that reads its branches and defaults from the sketch should land.
const NEAR: f64 = 0.5;

/// How far [`dimension`] puts the baseline off an assembly: each unknown by up to this many
/// of its units (what moves the solution by the instance's scale, or a direction by 1), and
/// again by a tenth of that.
const PUSH: f64 = 1e-3;

/// The baseline's assembly from `x`, verified: Newton, then Levenberg-Marquardt, each to the
/// checker's own tolerance ([`REL`] of the scale, rad for angles), the answer verified as a
/// plan's is ([`Space::violations`], every constraint claimed). `Err` says why not.
fn assemble<S: Space>(
    b: &mut S::Baseline,
    model: &Model,
    split: &Model,
    inst: &Instance,
    x0: &[f64],
) -> Result<(Vec<f64>, Solution), String> {
    let params = model.default_params();
    let claimed: Vec<ConstraintId> = model.constraints.iter().map(|(id, _)| id).collect();
    let mut why = String::new();
    for method in [Method::Newton, Method::LevenbergMarquardt] {
        let mut x = x0.to_vec();
        let opts = Options {
            method,
            tolerance: REL * inst.scale.min(1.0),
            max_iterations: 200,
            trace: false,
        };
        let out = b.solve(&params, &mut x, &opts);
        let Some(sol) = b.solution(&params, &x) else {
            let _ = write!(why, "{method:?}: no configuration; ");
            continue;
        };
        let bad = S::violations(&Solved {
            model,
            split,
            sol: &sol,
            claimed: &claimed,
            scale: inst.scale,
        });
        if bad.is_empty() {
            return Ok((x, sol));
        }
        let words: Vec<String> = bad.into_iter().map(|b| b.1).collect();
        let _ = write!(why, "{method:?}: {:?}, {}; ", out.stop, words.join(", "));
    }
    Err(why)
}

/// Whether the baseline finds an assembly near the sketch of `model`, isolated but for the
/// `free` defaults of its plan (see [`Judged`]).
fn judge<S: Space>(model: &Model, split: &Model, inst: &Instance, free: usize) -> Judged {
    let mut b = match S::baseline(model) {
        Ok(b) => b,
        Err(e) => return Judged::Unexpressed(e),
    };
    let params = model.default_params();
    let start = b.start_from_sketch(&params);
    let Some(sketch) = b.solution(&params, &start) else {
        return Judged::Unexpressed("the sketch is unusable".into());
    };
    let (x, sol) = match assemble::<S>(&mut b, model, split, inst, &start) {
        Ok(found) => found,
        Err(why) => return Judged::Unsolved(why),
    };
    let moved = distance(&sol, &sketch, inst.scale);
    if moved > NEAR {
        return Judged::Far(moved);
    }
    let dimension = dimension::<S>(&mut b, model, split, inst, &x, &sol);
    if dimension > free {
        return Judged::NotIsolated { dimension, free };
    }
    Judged::Near(moved)
}

/// The defaults a plan leaves free: those no iteration closes (one per `Close` step).
fn freedom(plan: &gcs_compiler::plan::Plan) -> usize {
    let closes = (plan.steps.iter())
        .filter(|s| matches!(s.op, Op::Close { .. }))
        .count();
    plan.defaults.len().saturating_sub(closes)
}

/// The dimension of the assemblies around the assembly `x` (`sol`), as the baseline finds
/// them: put off `x` along random directions, by [`PUSH`] and by a tenth of it, the baseline
/// lands back on the assemblies. Where they form a continuum it lands off `sol` along it, about
/// as far as it was put off (the drift shrinks tenfold with the push); at an isolated assembly
/// it lands back on `sol` (to its tolerance, or to the square root of it at a double root), or
/// on another isolated assembly nearby (a near-tangent pair), at a distance that does not
/// shrink with the push. The drifts that shrink with the push, measured on the solution (every
/// point and dimension relative to the scale, every direction), so that a geom's unknowns that
/// nothing reads (where on a line its point lies) do not count, span the continuum's tangent
/// space: their numerical rank is its dimension.
fn dimension<S: Space>(
    b: &mut S::Baseline,
    model: &Model,
    split: &Model,
    inst: &Instance,
    x: &[f64],
    sol: &Solution,
) -> usize {
    let n = x.len();
    let params = model.default_params();
    let at = flat(sol, inst.scale);
    // Each unknown's unit: what moves the solution by 1 (relative to the scale), measured by
    // a small difference; an unknown that moves nothing (a line's point along it) is not
    // pushed.
    let largest = x.iter().fold(f64::MIN_POSITIVE, |m: f64, v| m.max(v.abs()));
    let mut effect = vec![0.0; n];
    for i in 0..n {
        let h = 1e-7 * x[i].abs().max(1e-3 * largest);
        let mut xi = x.to_vec();
        xi[i] += h;
        if let Some(s) = b.solution(&params, &xi) {
            let d = flat(&s, inst.scale);
            effect[i] = d
                .iter()
                .zip(&at)
                .map(|(p, q)| (p - q) * (p - q))
                .sum::<f64>()
                .sqrt()
                / h;
        }
    }
    let strongest = effect.iter().fold(0.0, |m: f64, e| m.max(*e));
    let unit: Vec<f64> = (effect.iter())
        .map(|e| if *e > 1e-6 * strongest { 1.0 / e } else { 0.0 })
        .collect();
    let mut rng = Rng::new(n as u64);
    let mut drifts: Vec<f64> = Vec::new();
    let mut rows = 0;
    for _ in 0..n + 2 {
        let dir: Vec<f64> = (0..n)
            .map(|_| rng.range(-1.0, 1.0) / (n as f64).sqrt())
            .collect();
        let mut land = |push: f64| {
            let x0: Vec<f64> = (0..n).map(|i| x[i] + push * dir[i] * unit[i]).collect();
            let (_, landed) = assemble::<S>(b, model, split, inst, &x0).ok()?;
            let to = flat(&landed, inst.scale);
            Some(
                to.iter()
                    .zip(&at)
                    .map(|(t, a)| (t - a) / push)
                    .collect::<Vec<f64>>(),
            )
        };
        let (Some(far), Some(near)) = (land(PUSH), land(PUSH / 10.0)) else {
            continue;
        };
        // In units of the push, a drift along a continuum is the same at both pushes.
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let gap: Vec<f64> = far.iter().zip(&near).map(|(a, b)| a - b).collect();
        if norm(&far) > 1e-4 && norm(&gap) <= 0.6 * norm(&far) {
            drifts.extend(&far);
            rows += 1;
        }
    }
    // Along a continuum most pushes have a part along it; one or two drifting with the push
    // are a valley too flat for the push to tell (a double root of nearly concentric circles).
    if 2 * rows < n + 2 {
        return 0;
    }
    let m = nalgebra::DMatrix::from_row_slice(rows, at.len(), &drifts);
    let sv = m.singular_values();
    let top = sv.max();
    sv.iter().filter(|s| **s > 0.05 * top).count()
}

/// A solution's values in one list: every point's coordinates and dimension relative to
/// `scale`, every direction's components.
fn flat(s: &Solution, scale: f64) -> Vec<f64> {
    (s.points
        .iter()
        .flat_map(|(_, p)| p.iter().map(|x| x / scale)))
    .chain(s.scalars.iter().map(|(_, x)| x / scale))
    .chain(s.vectors.iter().flat_map(|(_, v)| v.iter().copied()))
    .collect()
}

/// Inconsistent instances of a check entry: the plan must refuse them (a `SolveError`), never
/// return a solution that violates the checked constraint. Reported, not asserted: the checker's
/// bar is the solvable instances.
fn run_inconsistent<S: Space>(entry_id: &str, seed: u64, inst: &Instance, stats: &mut Stats) {
    let model = load(&inst.text);
    let Ok(a) = analyse(&model) else { return };
    let z = label(&model, "z").expect("z");
    if !a
        .plan
        .steps
        .iter()
        .any(|s| s.satisfies.contains(&z) && matches!(s.op, Op::Check { .. }))
    {
        return;
    }
    stats.inconsistent += 1;
    let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    let counts: Vec<usize> = a.plan.branches.iter().map(|b| b.count).collect();
    let defaults: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let params = model.default_params();
    for combo in combos(&counts, &defaults) {
        let solve = || gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo);
        let solved = if S::SOLVE_PANIC_REFUSES {
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(solve)).map_or(None, Result::ok)
        } else {
            solve().ok()
        };
        let Some(sol) = solved else {
            continue;
        };
        let res = gcs_compiler::verify::residuals(&model, &sol, &params);
        let rz = res
            .iter()
            .find(|r| r.constraint == z)
            .map_or(0.0, |r| r.value);
        if rz.is_nan() || rz > 1e-9 * inst.scale.max(1.0) {
            stats.inconsistent_accepted.push(format!(
                "{entry_id}: seed {seed}, branches {combo:?}: `{}` checked but violated by {rz:.3e}\n```gcs\n{}```",
                model.constraints[z].text,
                inst.text
            ));
            return;
        }
    }
    stats.inconsistent_refused += 1;
}

const N_INCONSISTENT: usize = 4;

// ---------------------------------------------------------------- the test and the report

struct Row<S: Space> {
    id: String,
    key: String,
    kind: S::Kind,
    state: &'static str,
    form: String,
    class: Class,
    stats: Option<Stats>,
}

impl<S: Space> Row<S> {
    /// Its wrong runs' modes (`analysis` for a failed analysis).
    fn wrong_modes(&self) -> Vec<String> {
        let mut modes: Vec<String> = (self.stats.iter())
            .flat_map(|s| s.wrong.iter().map(|w| w.1.clone()))
            .collect();
        if matches!(self.class.outcome, Outcome::Failed(_)) {
            modes.push("analysis".into());
        }
        modes
    }
    fn wrong(&self) -> usize {
        self.wrong_modes().len()
    }
    /// Whether a wrong run in `mode` is known.
    fn known(&self, mode: &str) -> bool {
        S::KNOWN_WRONG
            .iter()
            .any(|k| k.entries.contains(&self.key.as_str()) && k.modes.contains(&mode))
    }
    /// Its wrong runs that no known cause lists.
    fn unexpected(&self) -> usize {
        self.wrong_modes().iter().filter(|m| !self.known(m)).count()
    }
    /// Its degenerate refusals that the baseline solves near the sketch.
    fn near_refusals(&self) -> Vec<&Refusal> {
        (self.stats.iter())
            .flat_map(|s| &s.degenerate)
            .filter(|r| matches!(r.judged, Judged::Near(_)))
            .collect()
    }
    /// Whether a degenerate refusal in `mode` is known.
    fn known_degenerate(&self, mode: &str) -> bool {
        S::KNOWN_DEGENERATE
            .iter()
            .any(|k| k.entries.contains(&self.key.as_str()) && k.modes.contains(&mode))
    }
    /// Its id, kind, state and constraint form, as the report's lists name it.
    fn named(&self) -> String {
        format!(
            "{} {} ({}), `{}`",
            self.id,
            self.kind.name(),
            self.state,
            self.form
        )
    }
    /// Whether a checked entry solves fewer than half of its random instances.
    fn rarely(&self) -> bool {
        self.stats
            .as_ref()
            .is_some_and(|s| 2 * s.random_solved < S::N_RANDOM)
    }
}

fn row<S: Space>(n: usize, e: &Entry<S>) -> Row<S> {
    let id = format!("#{n}");
    let canonical = S::make(e, (n as u64) << 32, Mode::Random);
    let class = classify(e, &canonical);
    let stats = class.outcome.checked().then(|| {
        let mut stats = Stats::default();
        let modes = std::iter::repeat_n(Mode::Random, S::N_RANDOM).chain(degenerate::<S>());
        for (i, mode) in modes.enumerate() {
            let seed = ((n as u64) << 32) | (i as u64 + 1);
            let inst = S::make(e, seed, mode);
            run_instance::<S>(&id, seed, mode, &inst, &mut stats);
        }
        if class.outcome == Outcome::Check {
            for i in 0..N_INCONSISTENT {
                let seed = ((n as u64) << 32) | (1000 + i as u64);
                let inst = S::make(e, seed, Mode::Inconsistent);
                run_inconsistent::<S>(&id, seed, &inst, &mut stats);
            }
        }
        stats
    });
    Row {
        id,
        key: e.key(),
        kind: e.kind,
        state: e.state,
        form: e.last.text(),
        class,
        stats,
    }
}

/// Runs `f` on every item on a few threads, keeping the items' order.
fn parallel_map<T: Sync, R: Send>(items: &[T], f: impl Fn(usize, &T) -> R + Sync) -> Vec<R> {
    let threads = std::thread::available_parallelism()
        .map_or(2, |n| n.get())
        .clamp(1, 8);
    let mut out: Vec<(usize, R)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let f = &f;
                scope.spawn(move || {
                    (k..items.len())
                        .step_by(threads)
                        .map(|i| (i, f(i, &items[i])))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("a checker thread"))
            .collect()
    });
    out.sort_by_key(|(i, _)| *i);
    out.into_iter().map(|(_, r)| r).collect()
}

/// The construction checker of a space: probes every entry and every state's defaults, checks
/// them, and writes (`GCS_WRITE_FRAGMENTS=1`) or compares the table. `GCS_PROBE` and
/// `GCS_ENTRY` print one model instead (see [`probe`] and [`instance`]).
pub fn check<S: Space>() {
    // Debugging aids: print one model's plan and solves instead of running the checker.
    if std::env::var("GCS_PROBE").is_ok() {
        probe();
        return;
    }
    if std::env::var("GCS_ENTRY").is_ok() {
        instance::<S>();
        return;
    }
    let table = &S::TABLE;
    let t0 = std::time::Instant::now();
    let entries = entries::<S>();
    let rows = parallel_map(&entries, row);
    let defaults = default_rows::<S>();
    let elapsed = t0.elapsed().as_secs_f64();
    let report = report(&rows) + &defaults_report::<S>(&defaults);
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../docs")
        .join(table.file);
    println!("{}- runtime {elapsed:.1} s", summary(&rows));
    if std::env::var("GCS_WRITE_FRAGMENTS").as_deref() == Ok("1") {
        std::fs::write(&path, &report).unwrap_or_else(|e| panic!("write docs/{}: {e}", table.file));
    }
    let mut unexpected = 0;
    for r in &rows {
        if r.unexpected() == 0 {
            continue;
        }
        unexpected += r.unexpected();
        if let Outcome::Failed(why) = &r.class.outcome {
            println!(
                "WRONG {} {} [analysis]: analysis failed: {why}",
                r.id, r.key
            );
        }
        for (_, mode, w) in r.stats.iter().flat_map(|s| &s.wrong) {
            if !r.known(mode) {
                println!("WRONG {} {} [{mode}]: {w}", r.id, r.key);
            }
        }
    }
    let stale: Vec<String> = S::KNOWN_WRONG
        .iter()
        .flat_map(|k| k.entries.iter().map(move |e| (k, e)))
        .filter(|(k, e)| {
            !rows.iter().any(|r| {
                r.key == **e
                    && r.wrong_modes()
                        .iter()
                        .any(|m| k.modes.contains(&m.as_str()))
            })
        })
        .map(|(k, e)| format!("{e} ({})", k.modes.join(", ")))
        .collect();
    assert_eq!(
        unexpected, 0,
        "wrong runs not in KNOWN_WRONG: see the WRONG lines above"
    );
    assert!(
        stale.is_empty(),
        "entries in KNOWN_WRONG that are no longer wrong in its modes (remove them): {stale:?}"
    );
    let mut refused = 0;
    for r in &rows {
        for n in r.near_refusals() {
            if !r.known_degenerate(&n.mode) {
                refused += 1;
                println!("VALID SKETCH REFUSED {} {}: {}", r.id, r.key, n.words);
            }
        }
    }
    let stale: Vec<String> = S::KNOWN_DEGENERATE
        .iter()
        .flat_map(|k| k.entries.iter().map(move |e| (k, e)))
        .filter(|(k, e)| {
            !rows.iter().any(|r| {
                r.key == **e
                    && (r.near_refusals().iter()).any(|n| k.modes.contains(&n.mode.as_str()))
            })
        })
        .map(|(k, e)| format!("{e} ({})", k.modes.join(", ")))
        .collect();
    assert_eq!(
        refused, 0,
        "valid sketches refused as degenerate, not in KNOWN_DEGENERATE: see the VALID SKETCH REFUSED lines above"
    );
    assert!(
        stale.is_empty(),
        "entries in KNOWN_DEGENERATE whose valid sketches are no longer refused in its modes (remove them): {stale:?}"
    );
    for r in &defaults {
        for w in &r.wrong {
            println!("WRONG DEFAULT {} {}: {w}", r.kind.name(), r.state);
        }
        let enough = if S::FEWER_DEFAULTS {
            r.defaults.len() <= r.dof
        } else {
            r.defaults.len() == r.dof
        };
        assert!(
            r.refused || enough,
            "{} {}: {} defaults for {} DOF",
            r.kind.name(),
            r.state,
            r.defaults.len(),
            r.dof
        );
    }
    let wrong_defaults: usize = defaults.iter().map(|r| r.wrong.len()).sum();
    assert_eq!(
        wrong_defaults, 0,
        "wrong default fragments: see the WRONG DEFAULT lines above"
    );
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == report,
        "docs/{} is out of date: regenerate it with {}",
        table.file,
        table.command
    );
}

fn summary<S: Space>(rows: &[Row<S>]) -> String {
    let table = &S::TABLE;
    let mut o = String::new();
    let count = |f: &dyn Fn(&Outcome) -> bool| rows.iter().filter(|r| f(&r.class.outcome)).count();
    let stats: Vec<&Stats> = rows.iter().filter_map(|r| r.stats.as_ref()).collect();
    let verified = rows
        .iter()
        .filter(|r| {
            r.stats
                .as_ref()
                .is_some_and(|s| s.wrong.is_empty() && s.solved > 0)
        })
        .count();
    let keys: std::collections::BTreeSet<(S::Kind, String, String)> = rows
        .iter()
        .filter(|r| !matches!(r.class.outcome, Outcome::Unreached(_)))
        .map(|r| (r.kind, r.class.before.clone(), r.form.clone()))
        .collect();
    let _ = writeln!(o, "- entries: {}", rows.len());
    let _ = writeln!(
        o,
        "- distinct (geom kind, signature, constraint form) keys: {}",
        keys.len()
    );
    let _ = writeln!(
        o,
        "- fragment: {}",
        count(&|x| matches!(x, Outcome::Fragment(_)))
    );
    let _ = writeln!(o, "- check: {}", count(&|x| *x == Outcome::Check));
    let _ = writeln!(
        o,
        "- recorded (kept in the record, satisfied when the geom is placed): {}",
        count(&|x| *x == Outcome::Recorded)
    );
    let _ = writeln!(
        o,
        "- not yet: {}",
        count(&|x| matches!(x, Outcome::NotYet(_)))
    );
    let _ = writeln!(
        o,
        "- state not reached by its prefix: {}",
        count(&|x| matches!(x, Outcome::Unreached(_)))
    );
    if table.detailed {
        let _ = writeln!(
            o,
            "- analysis failed (a malformed plan): {}",
            count(&|x| matches!(x, Outcome::Failed(_)))
        );
    }
    let _ = writeln!(
        o,
        "- entries checked (fragment or check): {}; verified (no wrong run, at least one instance solved): {verified}",
        stats.len()
    );
    let inst: usize = stats.iter().map(|s| s.instances).sum();
    let runs: usize = stats.iter().map(|s| s.runs).sum();
    let solved: usize = stats.iter().map(|s| s.solved).sum();
    let dsolved: usize = stats.iter().map(|s| s.default_solved).sum();
    let recl: usize = stats.iter().map(|s| s.reclassified).sum();
    let wrong: usize = stats.iter().map(|s| s.wrong.len()).sum();
    let mut unsolved: BTreeMap<String, usize> = BTreeMap::new();
    for s in &stats {
        for (k, v) in &s.unsolved {
            *unsolved.entry(k.clone()).or_default() += v;
        }
    }
    let _ = writeln!(
        o,
        "- instances: {inst} ({} random and {} near-degenerate per entry); solves (instance x branch combination): {runs}",
        S::N_RANDOM,
        degenerate::<S>().len()
    );
    let _ = writeln!(
        o,
        "- instances solved and verified: {solved} (on the default branches: {dsolved}); not solved by any branch: {} {:?}",
        inst - solved,
        unsolved
    );
    let refusals: Vec<&Refusal> = stats.iter().flat_map(|s| &s.degenerate).collect();
    let judged = |f: &dyn Fn(&Judged) -> bool| refusals.iter().filter(|r| f(&r.judged)).count();
    let near: Vec<(&Row<S>, &Refusal)> = (rows.iter())
        .flat_map(|r| r.near_refusals().into_iter().map(move |n| (r, n)))
        .collect();
    let known = near
        .iter()
        .filter(|(r, n)| r.known_degenerate(&n.mode))
        .count();
    let _ = writeln!(
        o,
        "- degenerate refusals (not solved by any branch, the first error `Degenerate`), judged by the baseline from the sketch: {}",
        refusals.len()
    );
    let _ = writeln!(
        o,
        "  - degenerate refusals the baseline solves near the sketch (an isolated assembly, verified, within {NEAR} of the scale): {}{}",
        near.len(),
        if near.is_empty() {
            String::new()
        } else {
            format!(", all of whose causes the test's KNOWN_DEGENERATE lists: {}", known == near.len())
        }
    );
    let _ = writeln!(
        o,
        "  - with no isolated solution (near the sketch, a continuum of assemblies wider than the plan's free defaults): {}; an assembly farther from the sketch: {}; none found: {}",
        judged(&|j| matches!(j, Judged::NotIsolated { .. })),
        judged(&|j| matches!(j, Judged::Far(_))),
        judged(&|j| matches!(j, Judged::Unsolved(_) | Judged::Unexpressed(_))),
    );
    if table.detailed {
        let _ = writeln!(
            o,
            "- checked entries that solve fewer than half of their random instances: {}",
            rows.iter().filter(|r| r.rarely()).count()
        );
    }
    let _ = writeln!(
        o,
        "- instances whose plan did not claim the probed constraint (classified otherwise on that sketch): {recl}"
    );
    let _ = writeln!(o, "- wrong runs (solved, but a claimed constraint violated beyond 1e-12 relative, or a panic): {wrong}");
    let precision: usize = stats
        .iter()
        .map(|s| s.wrong.iter().filter(|w| w.0 <= 1e-9).count())
        .sum();
    let _ = writeln!(
        o,
        "  - of which precision losses (relative residual between 1e-12 and 1e-9): {precision}; wrong results beyond 1e-9: {}",
        wrong - precision
    );
    let wrong_entries = rows.iter().filter(|r| r.wrong() > 0).count();
    if table.detailed {
        let known = rows
            .iter()
            .filter(|r| r.wrong() > 0 && r.unexpected() == 0)
            .count();
        let _ = writeln!(
            o,
            "- entries with a wrong run (or a failed analysis): {wrong_entries}, all of whose wrong runs the test's KNOWN_WRONG lists: {known}"
        );
    } else {
        let _ = writeln!(o, "- entries with a wrong run: {wrong_entries}");
    }
    let inc: usize = stats.iter().map(|s| s.inconsistent).sum();
    let refused: usize = stats.iter().map(|s| s.inconsistent_refused).sum();
    let accepted: usize = stats.iter().map(|s| s.inconsistent_accepted.len()).sum();
    let _ = writeln!(
        o,
        "- inconsistent instances of check entries (reported, not asserted): {inc}; refused with an error: {refused}; accepted with the checked constraint violated: {accepted}"
    );
    if table.validated {
        let _ = writeln!(
            o,
            "- every plan analysed here (entries and instances) passed the plan validator"
        );
    }
    o
}

fn report<S: Space>(rows: &[Row<S>]) -> String {
    let table = &S::TABLE;
    let mut o = String::new();
    let _ = writeln!(o, "# {}\n", table.title);
    let _ = writeln!(
        o,
        "Generated by `compiler/bench/tests/{}.rs` (`{}`); do not edit.\n\
         Each entry probes one free geom `P` of a kind, brought into a state by a prefix of constraints with fixed geoms, \
         and one more constraint between a feature of `P` and a fixed geom. {}The outcome is what the analysis does for \
         that constraint; *before* and *after* are the signature (Kramer's `IR[...]`) and DOF of `P`'s cluster. \
         For every fragment and check, random solvable instances (and near-degenerate ones{}) are solved on every branch \
         and verified independently (`verify`); see the test's header for the method.{}\n",
        table.test, table.command, table.members, table.degenerate, table.last
    );
    let _ = writeln!(o, "## Totals\n");
    o.push_str(&summary(rows));
    let _ = writeln!(o, "\n## Table\n");
    let mut kind = None;
    for r in rows {
        if kind != Some(r.kind) {
            kind = Some(r.kind);
            let _ = writeln!(o, "\n### {}\n", r.kind.name());
            let _ = writeln!(
                o,
                "| id | state | before | constraint | outcome | after | instances: solved / run |"
            );
            let _ = writeln!(o, "| --- | --- | --- | --- | --- | --- | --- |");
        }
        let inst = match &r.stats {
            Some(s) => {
                let mut t = format!("{} / {}", s.solved, s.instances);
                if !s.wrong.is_empty() {
                    let _ = write!(t, ", **{} wrong**", s.wrong.len());
                    if r.unexpected() == 0 {
                        t.push_str(" (known)");
                    }
                }
                t
            }
            None => String::new(),
        };
        let mut outcome = r.class.outcome.text();
        if !r.class.note.is_empty() {
            let _ = write!(outcome, " ({})", r.class.note);
        }
        let _ = writeln!(
            o,
            "| {} | {} | {} | `{}` | {} | {} | {} |",
            r.id,
            r.state,
            r.class.before,
            r.form,
            outcome.replace('|', "\\|"),
            r.class.after,
            inst
        );
    }
    let _ = writeln!(o, "\n## Not yet, by reason\n");
    let mut by: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for r in rows {
        if let Outcome::NotYet(reason) | Outcome::Unreached(reason) = &r.class.outcome {
            let key = match &r.class.outcome {
                Outcome::Unreached(_) => format!("state not reached: {reason}"),
                _ => reason.clone(),
            };
            by.entry(key).or_default().push(format!(
                "{} {} ({}): `{}`",
                r.id,
                r.kind.name(),
                r.state,
                r.form
            ));
        }
    }
    for (reason, list) in &by {
        let _ = writeln!(o, "- **{reason}** ({}):", list.len());
        for l in list {
            let _ = writeln!(o, "  - {l}");
        }
    }
    let _ = writeln!(o, "\n## Instances no branch solved\n");
    let _ = writeln!(
        o,
        "A `SolveError` is never a wrong answer; these are instances built from a solvable target that the plan \
         (on every branch) refused{}\n",
        table.unsolved
    );
    let mut examples = 0;
    for r in rows {
        if let Some(s) = &r.stats {
            let n: usize = s.unsolved.values().sum();
            if n > 0 {
                let _ = write!(
                    o,
                    "- {}: {n} of {} {:?}",
                    r.named(),
                    s.instances,
                    s.unsolved
                );
                if !table.detailed {
                    let _ = writeln!(o);
                    continue;
                }
                let _ = writeln!(o, ", by mode {:?}", s.unsolved_modes);
                if examples < 5 {
                    if let Some(ex) = &s.unsolved_example {
                        examples += 1;
                        let _ = writeln!(o, "  - {}", ex.replace('\n', "\n    "));
                    }
                }
            }
        }
    }
    if table.detailed {
        let _ = writeln!(o, "\n## Entries that rarely solve\n");
        let _ = writeln!(
            o,
            "Fragment and check entries whose plan solves fewer than half of their {} random instances \
             (each solvable by construction): not wrong, but a construction that rarely applies.\n",
            S::N_RANDOM
        );
        for r in rows.iter().filter(|r| r.rarely()) {
            if let Some(s) = &r.stats {
                let _ = writeln!(
                    o,
                    "- {} `{}`: {} of {} random instances solved; not solved: {:?}",
                    r.id,
                    r.key,
                    s.random_solved,
                    S::N_RANDOM,
                    s.unsolved
                );
            }
        }
    }
    let _ = writeln!(o, "\n## Degenerate refusals of valid sketches\n");
    let _ = writeln!(
        o,
        "Every instance refused as degenerate (no branch solved it, the first error `Degenerate`) is given to the \
         numeric baseline (`gcs_bench::baseline`: Newton, then Levenberg-Marquardt, on the raw equations) from its sketch. \
         An assembly it finds, verified as a plan's answer is (every constraint, to 1e-12 relative), is *near the sketch* \
         when every point and dimension lies within {NEAR} of the instance's scale of the sketch (and every direction \
         within {NEAR}): a random sketch lies up to about the scale from the target it was moved from, a near-degenerate one \
         much closer. It is *isolated* when the assemblies around it are no more than the plan's free defaults choose among: \
         the baseline, put off it along random directions by {PUSH:e} and {:e} of each unknown's effect, lands back on it; \
         along a continuum (a point on two coincident lines) it lands off it in proportion to the push, and the rank of \
         those drifts is the continuum's dimension. An isolated assembly near the sketch of a refused instance is a valid \
         sketch refused, listed here; the test fails on one its KNOWN_DEGENERATE does not list.\n",
        PUSH / 10.0
    );
    let mut listed = 0;
    for r in rows {
        for n in r.near_refusals() {
            let known = if r.known_degenerate(&n.mode) {
                " (known)"
            } else {
                ""
            };
            let words = if listed < 5 {
                n.words.replace('\n', "\n    ")
            } else {
                n.words.split("\n```").next().unwrap_or("").to_string()
            };
            listed += 1;
            let moved = match n.judged {
                Judged::Near(m) => m,
                _ => f64::NAN,
            };
            let _ = writeln!(
                o,
                "- {}{known}, the baseline's assembly {moved:.1e} of the scale from the sketch: {words}",
                r.named()
            );
        }
    }
    if listed == 0 {
        let _ = writeln!(o, "None.");
    }
    for (i, k) in S::KNOWN_DEGENERATE.iter().enumerate() {
        let _ = writeln!(
            o,
            "\nKnown cause {} (modes: {}; entries: {}). {}",
            i + 1,
            k.modes.join(", "),
            k.entries
                .iter()
                .map(|e| format!("`{e}`"))
                .collect::<Vec<_>>()
                .join(", "),
            k.why
        );
    }
    let _ = writeln!(o, "\n## Checks that accept inconsistent instances\n");
    let _ = writeln!(
        o,
        "An inconsistent instance of a check entry has no solution; the check must refuse it. One example per entry.\n"
    );
    let mut none = true;
    for r in rows {
        if let Some(s) = &r.stats {
            if let Some(w) = s.inconsistent_accepted.first() {
                // The model text of the first few only.
                let w = if none {
                    w.clone()
                } else {
                    w.split("\n```").next().unwrap_or("").to_string()
                };
                none = false;
                let _ = writeln!(
                    o,
                    "- {}: {} of {} accepted. {w}",
                    r.named(),
                    s.inconsistent_accepted.len(),
                    s.inconsistent
                );
            }
        }
    }
    if none {
        let _ = writeln!(o, "None.");
    }
    let _ = writeln!(o, "\n## Failures\n");
    let mut any = false;
    // By known cause: its entries, and the first wrong run of the first with its model.
    for (i, k) in S::KNOWN_WRONG.iter().enumerate() {
        any = true;
        let _ = writeln!(o, "### Known cause {}\n\n{}\n", i + 1, k.why);
        let _ = writeln!(o, "Modes: {}.\n", k.modes.join(", "));
        let mut example = None;
        for r in rows.iter().filter(|r| k.entries.contains(&r.key.as_str())) {
            let runs: Vec<&(f64, String, String)> = (r.stats.iter())
                .flat_map(|s| &s.wrong)
                .filter(|w| k.modes.contains(&w.1.as_str()))
                .collect();
            let worst = runs.iter().map(|w| w.0).fold(0.0, f64::max);
            if let Outcome::Failed(why) = &r.class.outcome {
                let _ = writeln!(o, "- {} `{}`: analysis failed: {why}", r.id, r.key);
            } else {
                let _ = writeln!(
                    o,
                    "- {} `{}`: {} wrong runs, worst relative residual {worst:.1e}",
                    r.id,
                    r.key,
                    runs.len()
                );
            }
            if example.is_none() {
                example = runs.first().map(|w| w.2.clone());
            }
        }
        if let Some(w) = example {
            let _ = writeln!(o, "\nFirst wrong run: {w}");
        }
        let _ = writeln!(o);
    }
    // Wrong runs no known cause lists, each with its model.
    let mut first = true;
    for r in rows.iter().filter(|r| r.unexpected() > 0) {
        if first {
            let _ = writeln!(o, "### Not in KNOWN_WRONG\n");
            first = false;
        }
        any = true;
        if let Outcome::Failed(why) = &r.class.outcome {
            let _ = writeln!(o, "- {} `{}`: analysis failed: {why}", r.id, r.key);
        }
        for (rel, mode, w) in r.stats.iter().flat_map(|s| &s.wrong) {
            if r.known(mode) {
                continue;
            }
            let class = if *rel <= 1e-9 {
                "precision (relative residual at most 1e-9)"
            } else {
                "wrong result"
            };
            let _ = writeln!(o, "- `{}` [{mode}], {class}: {w}", r.key);
        }
    }
    if !any {
        let _ = writeln!(o, "None: every solved instance verifies.");
    }
    o
}

/// Debugging aid: `GCS_PROBE=model.gcs cargo test -p gcs-bench --test construction --
/// --nocapture` (or `--release --test construction3d`) prints the plan of one model and its
/// solve on every branch.
fn probe() {
    let path = std::env::var("GCS_PROBE").expect("GCS_PROBE=model.gcs");
    let text = std::fs::read_to_string(path).expect("read");
    show(&text);
}

fn show(text: &str) {
    let model = load(text);
    let a = match analyse(&model) {
        Ok(a) => a,
        Err(e) => {
            println!("analysis failed: {e}");
            return;
        }
    };
    println!("{}", a.plan.dump(&model));
    println!("unsolved: {:?}", a.unsolved);
    println!("record of P: {}", record_of(&model, &a));
    let counts: Vec<usize> = a.plan.branches.iter().map(|b| b.count).collect();
    let defaults: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
    let params = model.default_params();
    let scope: std::collections::BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
    for combo in combos(&counts, &defaults) {
        match gcs_compiler::solve_plan(&model, &a.plan, &scope, &params, &combo) {
            Ok(s) => {
                println!("{combo:?}: max residual {:.3e}", s.max_residual);
                for r in gcs_compiler::verify::residuals(&model, &s, &params) {
                    println!("  {} {:.3e}", model.constraints[r.constraint].text, r.value);
                }
            }
            Err(e) => println!("{combo:?}: {e:?}"),
        }
    }
}

/// Debugging aid: `GCS_ENTRY=n GCS_INSTANCE=i cargo test -p gcs-bench --test construction
/// -- --nocapture` (or `--release --test construction3d`) prints instance `i` of entry `n` (0
/// the canonical one, 1 to `N_RANDOM` random, then the near-degenerate ones in [`degenerate`]'s
/// order, 1000 and up inconsistent) with its plan and solves.
fn instance<S: Space>() {
    let n: usize = std::env::var("GCS_ENTRY")
        .expect("GCS_ENTRY")
        .parse()
        .expect("n");
    let i: usize = std::env::var("GCS_INSTANCE")
        .map_or(Ok(0), |s| s.parse())
        .expect("i");
    let e = &entries::<S>()[n];
    let mode = match i {
        i if i <= S::N_RANDOM => Mode::Random,
        i if i >= 1000 => Mode::Inconsistent,
        i => degenerate::<S>()[i - 1 - S::N_RANDOM],
    };
    let inst = S::make(e, ((n as u64) << 32) | i as u64, mode);
    println!("{}: {}\n{}", e.key(), mode.name(), inst.text);
    show(&inst.text);
    let model = load(&inst.text);
    let split = inst.split_text.as_deref().map(load);
    let free = analyse(&model).map_or(0, |a| freedom(&a.plan));
    let judged = judge::<S>(&model, split.as_ref().unwrap_or(&model), &inst, free);
    println!("the baseline: {judged:?}");
}

// ---------------------------------------------------------------- default fragments

/// What the analysis does with the freedom a state leaves (000, section 5.2.1): the defaults it
/// adds for `P`, probed on the prefix alone.
struct DefaultRow<S: Space> {
    kind: S::Kind,
    state: &'static str,
    /// `P`'s record before any default, with its DOF.
    before: String,
    dof: usize,
    /// The defaults' names, in plan order.
    defaults: Vec<String>,
    /// Whether the analysis refused to default the freedom (it stays free and is reported).
    refused: bool,
    /// Exact instances (the sketch satisfies the prefix) solved at the sketch's defaults with
    /// nothing moved, of those run.
    still: (usize, usize),
    /// Random instances solved at the sketch's defaults, and with each default moved, with
    /// every constraint verified and the moved default moving `P`, of those run.
    moved: (usize, usize),
    /// Wrong runs.
    wrong: Vec<String>,
}

/// Every point, vector and scalar of `P` in a solution, by name.
fn values_of_p(s: &Solution) -> Vec<(String, Vec<f64>)> {
    values_where(s, |n| n == "P" || n.starts_with("P."))
}

/// How far apart two solutions of one model lie: the largest difference of a point's
/// coordinate or a dimension relative to `scale`, or of a direction's component.
fn distance(a: &Solution, b: &Solution, scale: f64) -> f64 {
    let by = |x: &[(String, Vec<f64>)], y: &[(String, Vec<f64>)]| {
        let mut d: f64 = 0.0;
        for ((n, u), (m, v)) in x.iter().zip(y) {
            assert_eq!(n, m, "two solutions of one model list the same values");
            for (p, q) in u.iter().zip(v) {
                d = d.max((p - q).abs());
            }
        }
        d
    };
    let dims = (a.scalars.iter().zip(&b.scalars))
        .map(|((_, x), (_, y))| (x - y).abs())
        .fold(0.0, f64::max);
    (by(&a.points, &b.points).max(dims) / scale).max(by(&a.vectors, &b.vectors))
}

fn values_where(s: &Solution, of_p: impl Fn(&str) -> bool) -> Vec<(String, Vec<f64>)> {
    (s.points.iter().chain(&s.vectors))
        .filter(|(n, _)| of_p(n))
        .cloned()
        .chain(
            (s.scalars.iter())
                .filter(|(n, _)| of_p(n))
                .map(|(n, x)| (n.clone(), vec![*x])),
        )
        .collect()
}

/// The largest difference between same-named values.
fn largest_difference(a: &[(String, Vec<f64>)], b: &[(String, Vec<f64>)]) -> f64 {
    let mut d: f64 = 0.0;
    for (n, u) in a {
        if let Some((_, v)) = b.iter().find(|(m, _)| m == n) {
            for (x, y) in u.iter().zip(v) {
                d = d.max((x - y).abs());
            }
        }
    }
    d
}

/// The largest residual of every constraint of `model` in `s`, relative to `scale` for
/// lengths (angles absolute; a joint's, which mixes both, relative). A NaN counts as off where
/// the space says so, and is passed over elsewhere.
fn worst_residual<S: Space>(model: &Model, s: &Solution, scale: f64) -> f64 {
    let params = model.default_params();
    (gcs_compiler::verify::residuals(model, s, &params).iter())
        .map(|r| {
            if S::NAN_DEFAULT_WRONG && r.value.is_nan() {
                f64::INFINITY
            } else if angular(model.constraints[r.constraint].kind) {
                r.value
            } else {
                r.value / scale.max(1.0)
            }
        })
        .fold(0.0, f64::max)
}

/// The checker of the defaults of one state: the sketch's defaults move nothing the
/// constraints do not move, every default keeps the state's constraints, and each moves `P`.
fn default_row<S: Space>(
    kind: S::Kind,
    state: &State<S>,
    last: S::Form,
    n: usize,
) -> DefaultRow<S> {
    let entry = Entry {
        kind,
        state: state.name,
        prefix: state.prefix.clone(),
        motion: state.motion,
        last,
    };
    let canonical = S::make(&entry, (n as u64) << 40, Mode::Random);
    let model = load(&canonical.prefix_text);
    let a = analyse(&model).expect("the prefix analysed");
    let p = model.geom_named("P").expect("P");
    let dof = (a.undefaulted.iter())
        .find(|c| c.geoms.contains(&p))
        .map_or(0, |c| c.dof);
    let mut row = DefaultRow {
        kind,
        state: state.name,
        before: record_of(&model, &a),
        dof,
        defaults: a.plan.defaults.iter().map(|d| d.name.clone()).collect(),
        refused: !a.free_geoms().is_empty(),
        still: (0, 0),
        moved: (0, 0),
        wrong: Vec::new(),
    };
    if row.refused || row.defaults.is_empty() {
        return row;
    }
    for i in 0..N_DEFAULT_INSTANCES {
        for mode in [Mode::Exact, Mode::Random] {
            let seed = ((n as u64) << 40) | (i as u64 + 1);
            let inst = S::make(&entry, seed, mode);
            let model = load(&inst.prefix_text);
            let a = analyse(&model).expect("the prefix analysed");
            let params = model.default_params();
            let scope: std::collections::BTreeSet<_> =
                model.top_level().map(|(id, _)| id).collect();
            let branches: Vec<usize> = a.plan.branches.iter().map(|b| b.default).collect();
            let sketch_defaults = a.plan.sketch_defaults();
            let solve = |defaults: &[f64]| {
                gcs_compiler::solve_plan_with(&model, &a.plan, &scope, &params, &branches, defaults)
            };
            let scale = inst.scale.max(1.0);
            let at_sketch = match solve(&sketch_defaults) {
                Ok(s) => s,
                Err(_) if mode == Mode::Random => continue,
                Err(e) => {
                    row.wrong
                        .push(format!("seed {seed} ({}): {e}", mode.name()));
                    continue;
                }
            };
            let worst = worst_residual::<S>(&model, &at_sketch, scale);
            if worst > REL {
                row.wrong.push(format!(
                    "seed {seed} ({}): a constraint off by {worst:e} at the sketch's defaults\n```gcs\n{}```",
                    mode.name(),
                    inst.prefix_text
                ));
                continue;
            }
            if mode == Mode::Exact {
                row.still.1 += 1;
                let sketch = Solution::of_sketch(&model, &params, &scope).expect("a finite sketch");
                let moved = largest_difference(&values_of_p(&at_sketch), &values_of_p(&sketch));
                if moved <= REL * scale {
                    row.still.0 += 1;
                } else {
                    row.wrong.push(format!(
                        "seed {seed} (exact): P moved {moved:e} at the sketch's defaults\n```gcs\n{}```",
                        inst.prefix_text
                    ));
                }
                continue;
            }
            row.moved.1 += 1;
            let mut ok = true;
            for (k, d) in a.plan.defaults.iter().enumerate() {
                let mut given = sketch_defaults.clone();
                given[k] += if S::angle_default(d) {
                    0.25
                } else {
                    0.25 * scale
                };
                let Ok(s) = solve(&given) else {
                    // A default past where the state lets P go (a length below zero) is an
                    // error, never a wrong answer.
                    continue;
                };
                let worst = worst_residual::<S>(&model, &s, scale);
                let moved = largest_difference(&values_of_p(&s), &values_of_p(&at_sketch));
                if worst > REL || moved <= 1e-6 * scale {
                    ok = false;
                    row.wrong.push(format!(
                        "seed {seed}: default {} moved: constraints off by {worst:e}, P moved {moved:e}\n```gcs\n{}```",
                        d.name, inst.prefix_text
                    ));
                }
            }
            row.moved.0 += usize::from(ok);
        }
    }
    row
}

/// Instances of each mode per state.
const N_DEFAULT_INSTANCES: usize = 6;

/// The default fragments of every state of every kind.
fn default_rows<S: Space>() -> Vec<DefaultRow<S>> {
    let mut states = Vec::new();
    for &kind in S::KINDS {
        let (list, forms) = S::catalogue(kind);
        for s in list {
            states.push((kind, s, forms[0]));
        }
    }
    parallel_map(&states, |i, (kind, s, f)| default_row(*kind, s, *f, i + 1))
}

/// The table's section on defaults.
fn defaults_report<S: Space>(rows: &[DefaultRow<S>]) -> String {
    let table = &S::TABLE;
    let mut o = String::new();
    let _ = writeln!(o, "\n## Defaults\n");
    let _ = writeln!(
        o,
        "Each state's prefix alone, with the freedom it leaves `P`: the defaults the analysis adds \
         (000, section 5.2.1; `{}`). Checked on instances \
         whose sketch already satisfies the prefix (*still*: solved at the sketch's defaults, \
         `P` must not move: least motion) and on random ones (*moved*: at the sketch's defaults \
         and with each default moved by 0.25 rad or 0.25 of the size, every constraint must hold \
         to 1e-12 relative and the moved default must move `P`). *Refused*: the analysis leaves \
         the freedom unparameterized{}, and `gcs check` reports it.\n",
        table.defaults_source, table.refused_example
    );
    let total = rows.len();
    let with = rows.iter().filter(|r| !r.defaults.is_empty()).count();
    let refused = rows.iter().filter(|r| r.refused).count();
    let fixed = (rows.iter())
        .filter(|r| !r.refused && r.defaults.is_empty())
        .count();
    let overstated = (rows.iter())
        .filter(|r| !r.refused && r.defaults.len() != r.dof)
        .count();
    let wrong: usize = rows.iter().map(|r| r.wrong.len()).sum();
    let _ = writeln!(
        o,
        "- states: {total}; with defaults: {with}; fully fixed by their prefix: {fixed}; refused: {refused}"
    );
    let fewer = if S::FEWER_DEFAULTS {
        " (fewer: a relation pending when the first default is taken, and solved after it, which the record's DOF does not count)"
    } else {
        ""
    };
    let _ = writeln!(
        o,
        "- states whose defaults are not as many as `P`'s DOF left: {overstated}{fewer}"
    );
    let _ = writeln!(o, "- wrong runs: {wrong}\n");
    let _ = writeln!(o, "| kind | state | before | defaults | still | moved |");
    let _ = writeln!(o, "|---|---|---|---|---:|---:|");
    for r in rows {
        let names = || {
            r.defaults
                .iter()
                .map(|d| format!("`{d}`"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let defaults = if r.refused {
            if r.defaults.is_empty() {
                "refused".to_string()
            } else {
                format!("refused (after {})", names())
            }
        } else if r.defaults.is_empty() {
            "none".to_string()
        } else {
            names()
        };
        let _ = writeln!(
            o,
            "| {} | {} | {} | {defaults} | {} / {} | {} / {} |",
            r.kind.name(),
            r.state,
            r.before,
            r.still.0,
            r.still.1,
            r.moved.0,
            r.moved.1
        );
    }
    o
}
