//! Degrees-of-freedom analysis of a model into a [`Plan`] (paper 000, sections 3-5 and
//! Appendix A).
//!
//! The analysis has a shared core and one module per space. The core ([`driver`]) runs
//! POSITION-ANALYSIS over clusters: action and locus analysis until stuck, then the smallest
//! rigid chain or loop as a macro-geom, with rollback of failed attempts and the plan's
//! registers and explanations. A space's module implements the [`geometry::Geometry`] trait:
//! the decomposition of constraints into relations between features, invariants records, the
//! plan fragments of action analysis, the loci and intersections of locus analysis, and how a
//! cluster is held. [`planar`] is the plane's, [`spatial`] space's (TLA's records and
//! fragments).

mod driver;
pub mod geometry;
pub mod loops;
pub mod planar;
pub mod spatial;

use crate::plan::Plan;
use gcs_lang::model::{ConstraintId, GeomId, Space};
use gcs_lang::Model;

/// Why a constraint has no plan yet.
#[derive(Clone, Debug, PartialEq)]
pub struct Unsupported {
    /// The constraint.
    pub constraint: ConstraintId,
    /// What is missing.
    pub reason: String,
}

/// A cluster at the end of the analysis: geoms that move together, and what its invariants
/// record says, whatever the space.
#[derive(Clone, Debug, PartialEq)]
pub struct Cluster {
    /// The top-level geoms (empty for a cluster merged into a macro-geom).
    pub geoms: Vec<GeomId>,
    /// The degrees of freedom its record leaves.
    pub dof: usize,
    /// The cardinalities of Kramer's Table 2 slots (see [`geometry::Invariants::table2`]).
    pub table2: [usize; 9],
    /// What freedom is left, in words (empty when none).
    pub freedom: String,
}

impl Cluster {
    /// The signature as Kramer writes it: `IR[100_10_1_000]`.
    pub fn signature(&self) -> String {
        let t = self.table2;
        format!(
            "IR[{}{}{}_{}{}_{}_{}{}{}]",
            t[0], t[1], t[2], t[3], t[4], t[5], t[6], t[7], t[8]
        )
    }
}

/// The outcome of the analysis.
#[derive(Clone, Debug)]
pub struct Analysis {
    /// The plan.
    pub plan: Plan,
    /// Every cluster at the end.
    pub clusters: Vec<Cluster>,
    /// Every cluster as action, locus and loop analysis left it, before the first default
    /// (the same as `clusters` when there is none): what the constraints alone fix.
    pub undefaulted: Vec<Cluster>,
    /// Relations no fragment could satisfy, by constraint, with the reason.
    pub unsolved: Vec<Unsupported>,
    /// Constraints held in an invariants record and satisfied once their geom is placed,
    /// which the model's freedom does not allow (a fixed distance of a circle of free radius
    /// that nothing places).
    pub recorded: Vec<ConstraintId>,
    /// Constraints that are implied by others (kept as run-time checks).
    pub redundant: Vec<ConstraintId>,
}

impl Analysis {
    /// The defaults no outer iteration varies: each parameterizes a motion the constraints
    /// leave free (case (a) of 000, section 5.2.1), so their number is the model's mobility.
    pub fn free_defaults(&self) -> Vec<crate::plan::DefaultId> {
        (0..self.plan.defaults.len() as u32)
            .map(crate::plan::DefaultId)
            .filter(|d| {
                !self
                    .plan
                    .iterations
                    .iter()
                    .any(|it| it.defaults.contains(d))
            })
            .collect()
    }

    /// The DOF left on each top-level geom's cluster, for geoms not grounded.
    pub fn free_geoms(&self) -> Vec<(GeomId, usize)> {
        let mut out = Vec::new();
        for c in self.clusters.iter().filter(|c| c.dof > 0) {
            for &g in &c.geoms {
                out.push((g, c.dof));
            }
        }
        out
    }
}

/// Why the analysis cannot read a model at all. Every model it can read gets a plan, with
/// whatever it cannot solve reported in [`Analysis::unsolved`].
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Unreadable {
    /// The sketch of a geom is invalid (a value that is not finite, a zero direction).
    InvalidSketch {
        /// The geom's name.
        geom: String,
        /// What is wrong with its sketch.
        what: String,
    },
}

impl std::fmt::Display for Unreadable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Unreadable::InvalidSketch { geom, what } => {
                write!(f, "the sketch of `{geom}` is invalid: {what}")
            }
        }
    }
}

impl std::error::Error for Unreadable {}

impl Unreadable {
    /// The error of a sketch that cannot be evaluated.
    pub(crate) fn sketch(model: &Model, bad: crate::config::BadSketch) -> Self {
        Unreadable::InvalidSketch {
            geom: model.geoms[bad.geom].name.clone(),
            what: bad.what,
        }
    }
}

/// Analyses a model. Fails only for a sketch it cannot read: every model gets a plan, with
/// whatever it cannot solve reported in [`Analysis::unsolved`]. Its branch
/// variables' defaults are not chosen yet: [`crate::pipeline::analyse`] does that, and
/// validates the plan.
///
/// `moves` runs a plan on the sketch (the analysis runs none itself): for each run-time check
/// and `Onto`, by step, whether its residual moves with the defaults. A check that depends on
/// a default only on paper (a point displaced along the very line it must lie on) then stays
/// a check, and the default a free motion, rather than an iteration with nothing to close.
///
/// `values` runs the plan written so far on the sketch and reads registers: a linear stage
/// asks it which coefficients of its system vanish there, to choose its pivots.
pub(crate) fn analyse(model: &Model, moves: Moves, values: Values) -> Result<Analysis, Unreadable> {
    match model.space {
        Space::D2 => driver::analyse::<planar::Planar>(model, moves, values),
        Space::D3 => driver::analyse::<spatial::Spatial>(model, moves, values),
    }
}

/// For each step of a plan with defaults and no iterations yet, whether a check's residual or
/// an `Onto`'s gap changes when the defaults move (`None` where that is not known: the step is
/// neither, or the plan does not run); see [`analyse`].
pub(crate) type Moves = fn(&Model, &crate::plan::Plan) -> Vec<Option<bool>>;

/// The values of registers of a plan being written, run on the sketch (each default at its
/// least-motion value, each branch at the sketch's root): a scalar as `[x, 0, 0]`, a point or
/// a direction as its coordinates (`z` 0 in the plane). `None` where the plan does not run.
pub(crate) type Values =
    fn(&Model, &crate::plan::Plan, &[crate::plan::Reg]) -> Option<Vec<[f64; 3]>>;
