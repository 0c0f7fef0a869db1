//! Plan fragments for the sketcher's constraints of space that are relations of their own
//! (as in the plane's `sketcher.rs`): a midpoint goes to the midpoint of the known ends, or an
//! end to the known end reflected through it; a point goes to the mirror image of the other
//! across a known plane.

use super::{Rel, Spatial, Target};
use crate::analysis::driver::Builder;
use crate::plan::{Op, SpatialOp, Ty};
use gcs_lang::model::GeomId;

impl Builder<'_, Spatial> {
    /// `midpoint(p, s)`, `a` and `b` the ends of `s`: with both ends known, `p` goes to their
    /// midpoint; with `p` and one end known, the other end goes to that end reflected through
    /// `p`.
    pub(super) fn midpoint(&mut self, p: GeomId, a: GeomId, b: GeomId, r: &Rel) -> bool {
        let sname = self.name(self.model.top_level_of(a));
        let (ka, kb) = (self.point_known(a), self.point_known(b));
        if ka && kb && !self.point_known(p) {
            let (pa, pb) = (self.point(a), self.point(b));
            let words = format!("the midpoint of {sname}");
            let mid = self.value(Op::Midpoint { a: pa, b: pb }, Ty::Point, words);
            return self.move_point(p, Target::Point(mid), r);
        }
        if self.point_known(p) && ka != kb {
            let (known, free) = if ka { (a, b) } else { (b, a) };
            let (from, at) = (self.point(known), self.point(p));
            let words = format!("{} reflected through {}", self.name(known), self.name(p));
            let op = Op::Reflect {
                point: from,
                through: at,
            };
            let x = self.value(op, Ty::Point, words);
            return self.move_point(free, Target::Point(x), r);
        }
        false
    }

    /// `symmetric(p, q, plane)`: with the plane known, the one of `p` and `q` not known goes
    /// to the other's mirror image across it (a mirror is its own inverse).
    pub(super) fn mirror(
        &mut self,
        p: GeomId,
        q: GeomId,
        (base, normal): (GeomId, GeomId),
        r: &Rel,
    ) -> bool {
        if !(self.point_known(base) && self.dir_known(normal)) {
            return false;
        }
        for (known, free) in [(p, q), (q, p)] {
            if self.point_known(known) && !self.point_known(free) {
                let (at, b, n) = (self.point(known), self.point(base), self.direction(normal));
                let words = format!(
                    "the mirror image of {} across {}",
                    self.name(known),
                    self.plane_words(base, normal, None)
                );
                let op = Op::Spatial(SpatialOp::MirrorPlane {
                    point: at,
                    base: b,
                    normal: n,
                });
                let image = self.value(op, Ty::Point, words);
                return self.move_point(free, Target::Point(image), r);
            }
        }
        false
    }
}
