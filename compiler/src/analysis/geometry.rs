//! What a space gives the shared driver: the trait a geometry module implements.
//!
//! The driver ([`super::driver`]) knows clusters, relations in canonical order, retries,
//! rollback, chains and loops, and plan emission; it knows nothing of the plane or of space.
//! A geometry module knows the rest: how constraints decompose into relations between
//! features, what a cluster's invariants record is, the plan fragments that move a cluster
//! (action analysis), the loci of partially fixed clusters and their intersections (locus
//! analysis), and how to hold a cluster in place. [`super::planar`] is the plane's module;
//! [`super::spatial`] implements the same trait with 3d records (TLA's translational and
//! rotational DOF with their invariant points and axes), relations (point-plane, marker axes)
//! and loops of up to six clusters.
//!
//! One driver generic over the space, with per-space records, relations and fragments: the
//! driver's work (canonical order, retries, rollback, chains and loops, defaults and their
//! iterations, checks, registers and words) does not depend on the space, while a record in
//! space and its fragments share nothing with the plane's but their purpose, so a record
//! generic over both would be an enum of the two.

use super::driver::Builder;
use super::Unsupported;
use crate::plan::Residual;
use gcs_lang::model::{ConstraintId, GeomId};
use gcs_lang::Model;

/// One relation of a constraint's decomposition, with the constraint it comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct Rel<R> {
    /// The relation between features.
    pub relation: R,
    /// The constraint.
    pub constraint: ConstraintId,
    /// Whether it is the constraint's last relation: the step that satisfies it satisfies the
    /// constraint.
    pub last: bool,
    /// Whether an earlier relation (in canonical order) has the same kind and features: then
    /// this one never constructs. It waits until that one is done and both its sides are known,
    /// and is checked (a duplicate holds, a duplicate with another value is a conflict of that
    /// size), whatever the two constraints are called.
    pub duplicate: bool,
}

/// A cluster's invariants record (000, Table 2): what constraints have fixed of it so far.
pub trait Invariants: Clone + PartialEq + std::fmt::Debug {
    /// The degrees of freedom the record leaves.
    fn dof(&self) -> usize;

    /// Whether nothing about the cluster can move any more.
    fn grounded(&self) -> bool {
        self.dof() == 0
    }

    /// Whether the cluster is rigid (no free dimension, nothing pending on one), so that it
    /// may join a rigid chain or loop.
    fn rigid(&self) -> bool;

    /// Whether the cluster is entirely free to move: then any cluster of a group may be its
    /// temporary ground; otherwise only this one.
    fn loose(&self) -> bool;

    /// Holds the cluster where it is: it becomes a temporary ground (SOLVE-RIGID-CHAINS,
    /// SOLVE-LOOP) or the ground of a model with nothing fixed.
    fn hold(&mut self);

    /// Whether point feature `f` of this cluster is invariant (its position is known).
    fn point_known(&self, model: &Model, f: GeomId) -> bool;

    /// The cardinalities of Kramer's Table 2 slots: invariant points, 1D- and 2D-constrained
    /// points, invariant and 1D-constrained vectors, invariant dimensions, fixed-distance
    /// points, lines and planes.
    fn table2(&self) -> [usize; 9];

    /// The constraints the record holds without a step having satisfied them yet (a fixed
    /// distance of a circle whose radius is still free is satisfied when the circle is
    /// placed).
    fn recorded(&self) -> Vec<ConstraintId>;

    /// What freedom the record leaves `geom`, in words (empty when none).
    fn freedom(&self, model: &Model, geom: GeomId) -> String;
}

/// A space's vocabulary for the analysis.
pub(crate) trait Geometry: Sized + Clone {
    /// A cluster's invariants record.
    type Record: Invariants;
    /// A relation between features.
    type Relation: Clone + std::fmt::Debug + PartialEq;

    /// The most clusters IDENTIFY-LOOPS looks at in a loop: 3 in the plane, 6 in space (000).
    const MAX_LOOP: usize;

    /// Every constraint of the model as relations between features, and those the module does
    /// not cover yet (never dropped); reads the sketch where the language leaves a choice to
    /// it. Fails for a model the module cannot read at all (an invalid sketch).
    #[allow(clippy::type_complexity)]
    fn decompose(
        model: &Model,
    ) -> Result<(Vec<Rel<Self::Relation>>, Vec<Unsupported>), super::Unreadable>;

    /// The features (points, directions, geoms with a dimension) a relation involves.
    fn features(relation: &Self::Relation) -> Vec<GeomId>;

    /// Whether a relation is unary (a dimension), satisfied before anything moves (000,
    /// Appendix A.3).
    fn is_dimension(relation: &Self::Relation) -> bool;

    /// The record of top-level geom `g` before any constraint.
    fn record(model: &Model, g: GeomId) -> Self::Record;

    /// Action analysis: satisfies `r` by moving the cluster of the side that is not known, with
    /// the freedom its record leaves, or makes it a check when it is already implied. Returns
    /// whether it did; a failed attempt is rolled back by the driver.
    fn action(b: &mut Builder<'_, Self>, r: &Rel<Self::Relation>) -> bool;

    /// Whether relation `r` is implied by what is known (both its sides, or one rigid cluster
    /// holding both): then a run-time check is all it needs.
    fn implied(b: &Builder<'_, Self>, r: &Self::Relation) -> bool;

    /// Locus analysis: satisfies `r` by intersecting the loci of two partially fixed clusters.
    fn locus(b: &mut Builder<'_, Self>, r: &Rel<Self::Relation>) -> bool;

    /// How a relation already implied is measured at run time: the registers of its
    /// features and values (measured now, or reused), and the residual that checks it.
    fn residual(b: &mut Builder<'_, Self>, relation: &Self::Relation) -> Residual;

    /// Grounds a model in which nothing is fixed, so that it is solved up to a rigid motion.
    fn ground(b: &mut Builder<'_, Self>);

    /// The linear stage, when action, locus, chain and loop analysis are stuck: clusters whose
    /// directions are all known and whose remaining relations are linear in their slides and
    /// free lengths are solved together, as one linear system. Returns whether it solved any.
    fn linear(_b: &mut Builder<'_, Self>) -> bool {
        false
    }

    /// Whether partly fixed clusters `a` and `b` may each only turn about one and the same
    /// known point: a rigid chain or loop of such clusters is then held by either, as one of
    /// a single partly fixed cluster is (two links pinned at one joint and welded together).
    fn share_pivot(_b: &Builder<'_, Self>, _a: usize, _other: usize) -> bool {
        false
    }

    /// Chains of clusters that are not rigid but keep an invariant between their ends (in
    /// space, bodies joined by revolutes with parallel axes: a planar sub-chain keeps a plane
    /// fixed in the body before it): when one end is partly fixed and the other holds a known
    /// point, the invariant places the first end. Tried when action, locus, chain, loop and
    /// linear analysis are stuck, before a default. Returns whether it placed one.
    fn subchains(_b: &mut Builder<'_, Self>) -> bool {
        false
    }

    /// Adds defaults (000, section 5.2.1) when nothing else applies: fixes one freedom of one
    /// cluster of the `candidates` (non-grounded clusters, fewest DOF first, then by name) at
    /// a default parameter with a geometric meaning (an angle about a pivot, a position along
    /// a locus, a position, a dimension), whose sketch value moves nothing. Returns whether it
    /// added one; the driver then goes back to action and locus analysis.
    fn default(b: &mut Builder<'_, Self>, candidates: &[usize]) -> bool;

    /// Whether a point (feature `point`) that a one-DOF turn about the axis feature `axis` must
    /// bring onto its orbit is kept in the orbit's plane by the model (in space: a joint's axis
    /// through the point kept parallel to the orbit's, as in a planar sub-chain). Its distance
    /// from the orbit's sphere is then a signed closing error, which a scan brackets, where its
    /// distance from the circle only touches zero; a guard checks the plane at the answer.
    fn kept_in_orbit_plane(_b: &Builder<'_, Self>, _axis: GeomId, _point: GeomId) -> bool {
        false
    }

    /// Whether the driver looks one stage ahead when several clusters of one freedom tie for a
    /// default: in space, which of an arm's two ends turning about known axes takes it decides
    /// whether the chains between them close with one default (`subchains`) or need three.
    const LOOK_AHEAD: bool = false;

    /// Whether the default [`Geometry::default`] would give cluster `k` leaves a pending
    /// relation degenerate on the sketch (a turn the relation then needs cannot change what it
    /// measures there): the driver then gives the default to the next cluster in its order.
    fn default_leaves_degenerate(_b: &Builder<'_, Self>, _k: usize) -> bool {
        false
    }
}
