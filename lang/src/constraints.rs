//! The one table of constraints ([`TABLE`]: for each, its argument forms, its value, the
//! spaces it is valid in), against which the resolver checks every constraint and nothing
//! else; and beside it, not in the table, [`ConstraintKind::nominal_dof`], the degrees of
//! freedom a constraint nominally removes, which depend on its arguments and value, and
//! [`ConstraintKind::joint_values`], the values of a joint an `output` may name.

use crate::expr::Dim;
use crate::model::{GeomKind, Space};

/// Every constraint of the language.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ConstraintKind {
    /// `coincident(a, b)`
    Coincident,
    /// `distance(a, b) = d`
    Distance,
    /// `on(p, g)`
    On,
    /// `tangent(a, b)`
    Tangent,
    /// `angle(u, v) = a`
    Angle,
    /// `parallel(u, v)`
    Parallel,
    /// `perpendicular(u, v)`
    Perpendicular,
    /// `horizontal(x)`
    Horizontal,
    /// `vertical(x)`
    Vertical,
    /// `length(s) = l`
    Length,
    /// `radius(c) = r`
    Radius,
    /// `equal(a, b)`
    Equal,
    /// `midpoint(p, s)`
    Midpoint,
    /// `symmetric(p, q, l)`
    Symmetric,
    /// `in_line(m1, m2)`
    InLine,
    /// `in_plane(m1, m2)`
    InPlane,
    /// `parallel_z(m1, m2)`
    ParallelZ,
    /// `offset_z(m1, m2) = a`
    OffsetZ,
    /// `offset_x(m1, m2) = a`
    OffsetX,
    /// `helical(m1, m2) = pitch`
    Helical,
    /// `revolute(m1, m2)`
    Revolute,
    /// `prismatic(m1, m2)`
    Prismatic,
    /// `cylindrical(m1, m2)`
    Cylindrical,
    /// `spherical(a, b)`
    Spherical,
    /// `planar(m1, m2)`
    Planar,
    /// `weld(m1, m2)`
    Weld,
}

/// A class of argument a constraint accepts at one position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArgClass {
    /// A point, or a marker (its point).
    Point,
    /// A marker.
    Marker,
    /// A line, or a segment (its supporting line).
    Line,
    /// A segment.
    Segment,
    /// A circle.
    Circle,
    /// A plane.
    Plane,
    /// Anything with a direction: a vector (marker axes included), line, segment, or plane (its
    /// normal).
    Direction,
    /// A vector, line or segment (what can be horizontal or vertical).
    Heading,
}

impl ArgClass {
    /// Whether a geom of `kind` fits.
    pub fn accepts(self, kind: GeomKind) -> bool {
        use GeomKind as K;
        match self {
            ArgClass::Point => matches!(kind, K::Point | K::Marker),
            ArgClass::Marker => kind == K::Marker,
            ArgClass::Line => matches!(kind, K::Line | K::Segment),
            ArgClass::Segment => kind == K::Segment,
            ArgClass::Circle => kind == K::Circle,
            ArgClass::Plane => kind == K::Plane,
            ArgClass::Direction => matches!(kind, K::Vector | K::Line | K::Segment | K::Plane),
            ArgClass::Heading => matches!(kind, K::Vector | K::Line | K::Segment),
        }
    }

    /// The class with its article, for messages.
    pub fn noun(self) -> &'static str {
        match self {
            ArgClass::Point => "a point",
            ArgClass::Marker => "a marker",
            ArgClass::Line => "a line",
            ArgClass::Segment => "a segment",
            ArgClass::Circle => "a circle",
            ArgClass::Plane => "a plane",
            ArgClass::Direction => "a vector, line, segment or plane",
            ArgClass::Heading => "a vector, line or segment",
        }
    }
}

/// What a constraint's value is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ValueKind {
    /// It takes no value.
    None,
    /// A length.
    Length,
    /// An angle (radians).
    Angle,
    /// A helical pitch: length per turn.
    Pitch,
}

impl ValueKind {
    /// The dimension the value must have, if it takes one.
    pub fn dim(self) -> Option<Dim> {
        match self {
            ValueKind::None => None,
            ValueKind::Length | ValueKind::Pitch => Some(Dim::Length),
            ValueKind::Angle => Some(Dim::Angle),
        }
    }
}

/// Which spaces a constraint (or one of its forms) is valid in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Spaces {
    /// 2d and 3d.
    Both,
    /// 2d only.
    Only2d,
    /// 3d only.
    Only3d,
}

impl Spaces {
    /// Whether `space` is allowed.
    pub fn allows(self, space: Space) -> bool {
        match self {
            Spaces::Both => true,
            Spaces::Only2d => space == Space::D2,
            Spaces::Only3d => space == Space::D3,
        }
    }
}

/// One row of the table.
#[derive(Debug)]
pub struct ConstraintSpec {
    /// Which constraint.
    pub kind: ConstraintKind,
    /// Its name in the language.
    pub name: &'static str,
    /// The argument forms it accepts, in canonical order.
    pub forms: &'static [&'static [ArgClass]],
    /// Where each form is valid, when forms differ (`symmetric` mirrors across a line in 2d
    /// and across a plane in 3d); empty when every form is valid wherever the constraint is.
    pub form_spaces: &'static [Spaces],
    /// Whether a two-argument form may also be written the other way round (the arguments are
    /// then normalised to the canonical order).
    pub symmetric: bool,
    /// Its value.
    pub value: ValueKind,
    /// Where it is valid.
    pub spaces: Spaces,
    /// One line for `gcs check` and the docs.
    pub meaning: &'static str,
}

impl ConstraintSpec {
    /// Whether form `i` (an index into `forms`) is valid in `space`.
    pub fn form_allows(&self, i: usize, space: Space) -> bool {
        self.spaces.allows(space) && self.form_spaces.get(i).is_none_or(|s| s.allows(space))
    }
}

use ArgClass as A;

const MARKERS: &[&[ArgClass]] = &[&[A::Marker, A::Marker]];
const POINT_MARKER: &[&[ArgClass]] = &[&[A::Point, A::Marker]];
const DIRECTIONS: &[&[ArgClass]] = &[&[A::Direction, A::Direction]];

/// The table: every constraint of the language.
pub static TABLE: &[ConstraintSpec] = &[
    ConstraintSpec {
        kind: ConstraintKind::Coincident,
        name: "coincident",
        forms: &[&[A::Point, A::Point]],
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "same position",
    },
    ConstraintSpec {
        kind: ConstraintKind::Distance,
        name: "distance",
        forms: &[
            &[A::Point, A::Point],
            &[A::Point, A::Line],
            &[A::Point, A::Plane],
            &[A::Point, A::Circle],
            &[A::Line, A::Circle],
            &[A::Circle, A::Circle],
        ],
        form_spaces: &[],
        symmetric: true,
        value: ValueKind::Length,
        spaces: Spaces::Both,
        meaning: "distance; signed for point-line in 2d and point-plane",
    },
    ConstraintSpec {
        kind: ConstraintKind::On,
        name: "on",
        forms: &[
            &[A::Point, A::Line],
            &[A::Point, A::Plane],
            &[A::Point, A::Circle],
        ],
        form_spaces: &[],
        symmetric: true,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "incidence",
    },
    ConstraintSpec {
        kind: ConstraintKind::Tangent,
        name: "tangent",
        forms: &[&[A::Line, A::Circle], &[A::Circle, A::Circle]],
        form_spaces: &[],
        symmetric: true,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "tangency, internal or external as in the sketch",
    },
    ConstraintSpec {
        kind: ConstraintKind::Angle,
        name: "angle",
        forms: DIRECTIONS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::Angle,
        spaces: Spaces::Both,
        meaning: "angle from u to v",
    },
    ConstraintSpec {
        kind: ConstraintKind::Parallel,
        name: "parallel",
        forms: DIRECTIONS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "angle 0 or pi, as in the sketch",
    },
    ConstraintSpec {
        kind: ConstraintKind::Perpendicular,
        name: "perpendicular",
        forms: DIRECTIONS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "angle pi/2",
    },
    ConstraintSpec {
        kind: ConstraintKind::Horizontal,
        name: "horizontal",
        forms: &[&[A::Heading]],
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Only2d,
        meaning: "parallel to the X axis",
    },
    ConstraintSpec {
        kind: ConstraintKind::Vertical,
        name: "vertical",
        forms: &[&[A::Heading]],
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Only2d,
        meaning: "parallel to the Y axis",
    },
    ConstraintSpec {
        kind: ConstraintKind::Length,
        name: "length",
        forms: &[&[A::Segment]],
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::Length,
        spaces: Spaces::Both,
        meaning: "a segment's length",
    },
    ConstraintSpec {
        kind: ConstraintKind::Radius,
        name: "radius",
        forms: &[&[A::Circle]],
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::Length,
        spaces: Spaces::Both,
        meaning: "a circle's radius",
    },
    ConstraintSpec {
        kind: ConstraintKind::Equal,
        name: "equal",
        forms: &[&[A::Segment, A::Segment], &[A::Circle, A::Circle]],
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "equal lengths or equal radii, whatever they are",
    },
    ConstraintSpec {
        kind: ConstraintKind::Midpoint,
        name: "midpoint",
        forms: &[&[A::Point, A::Segment]],
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "p is the midpoint of s",
    },
    ConstraintSpec {
        kind: ConstraintKind::Symmetric,
        name: "symmetric",
        forms: &[
            &[A::Point, A::Point, A::Line],
            &[A::Point, A::Point, A::Plane],
        ],
        form_spaces: &[Spaces::Only2d, Spaces::Only3d],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "p and q mirror images across a line (2d) or a plane (3d)",
    },
    ConstraintSpec {
        kind: ConstraintKind::InLine,
        name: "in_line",
        forms: POINT_MARKER,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "on the line through m2 along its z axis (2d: its x axis)",
    },
    ConstraintSpec {
        kind: ConstraintKind::InPlane,
        name: "in_plane",
        forms: POINT_MARKER,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Only3d,
        meaning: "in the plane through m2 normal to its z axis",
    },
    ConstraintSpec {
        kind: ConstraintKind::ParallelZ,
        name: "parallel_z",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Only3d,
        meaning: "z axes parallel",
    },
    ConstraintSpec {
        kind: ConstraintKind::OffsetZ,
        name: "offset_z",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::Angle,
        spaces: Spaces::Only3d,
        meaning: "z axes at an angle",
    },
    ConstraintSpec {
        kind: ConstraintKind::OffsetX,
        name: "offset_x",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::Angle,
        spaces: Spaces::Both,
        meaning: "z axes parallel and x axes at an angle about z",
    },
    ConstraintSpec {
        kind: ConstraintKind::Helical,
        name: "helical",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::Pitch,
        spaces: Spaces::Only3d,
        meaning: "z axes parallel, x angle linear in the distance along z",
    },
    ConstraintSpec {
        kind: ConstraintKind::Revolute,
        name: "revolute",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "joint: coincident + parallel_z",
    },
    ConstraintSpec {
        kind: ConstraintKind::Prismatic,
        name: "prismatic",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "joint: in_line + offset_x(0)",
    },
    ConstraintSpec {
        kind: ConstraintKind::Cylindrical,
        name: "cylindrical",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Only3d,
        meaning: "joint: in_line + parallel_z",
    },
    ConstraintSpec {
        kind: ConstraintKind::Spherical,
        name: "spherical",
        forms: &[&[A::Point, A::Point]],
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "joint: coincident",
    },
    ConstraintSpec {
        kind: ConstraintKind::Planar,
        name: "planar",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Only3d,
        meaning: "joint: in_plane + parallel_z",
    },
    ConstraintSpec {
        kind: ConstraintKind::Weld,
        name: "weld",
        forms: MARKERS,
        form_spaces: &[],
        symmetric: false,
        value: ValueKind::None,
        spaces: Spaces::Both,
        meaning: "joint: coincident + offset_x(0): the frames coincide",
    },
];

/// A value of a joint, measured on the solved markers of its constraint `J(m1, m2)` and named
/// in `output` as `J.angle` or `J.travel` (docs/LANGUAGE.md, Outputs).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum JointValue {
    /// `J.angle`: the angle from m1's x axis to m2's, counter-clockwise about m1's z axis (in
    /// 2d, in the plane), in (-pi, pi]: the value `offset_x(m1, m2)` would have.
    Angle,
    /// `J.travel`: the signed distance from m2's point to m1's along the axis the joint slides
    /// along, m2's z axis (in 2d, its x axis).
    Travel,
}

impl JointValue {
    /// Every joint value.
    pub const ALL: [JointValue; 2] = [JointValue::Angle, JointValue::Travel];

    /// The word after the dot.
    pub fn name(self) -> &'static str {
        match self {
            JointValue::Angle => "angle",
            JointValue::Travel => "travel",
        }
    }

    /// The value named by the word after the dot, if it names one.
    pub fn named(word: &str) -> Option<JointValue> {
        JointValue::ALL.into_iter().find(|v| v.name() == word)
    }

    /// The constraints whose joint has this value, in words: "a `revolute`, `cylindrical` or
    /// `offset_x` joint".
    pub fn joints_text(self) -> &'static str {
        match self {
            JointValue::Angle => "a `revolute`, `cylindrical` or `offset_x` joint",
            JointValue::Travel => "a `prismatic`, `cylindrical` or `in_line` joint",
        }
    }
}

/// The row for a constraint name.
pub fn lookup(name: &str) -> Option<&'static ConstraintSpec> {
    TABLE.iter().find(|s| s.name == name)
}

impl ConstraintKind {
    /// Its row of the table.
    pub fn spec(self) -> &'static ConstraintSpec {
        // The table has a row for every kind; `table_covers_every_kind` tests it.
        TABLE.iter().find(|s| s.kind == self).unwrap_or(&TABLE[0])
    }

    /// Its name in the language.
    pub fn name(self) -> &'static str {
        self.spec().name
    }

    /// The values of the joint it makes that an `output` may name (`J.angle`, `J.travel`):
    /// the angle of `revolute`, `cylindrical` and `offset_x`, the travel of `prismatic`,
    /// `cylindrical` and `in_line`; none for any other constraint.
    pub fn joint_values(self) -> &'static [JointValue] {
        use ConstraintKind as C;
        match self {
            C::Revolute | C::OffsetX => &[JointValue::Angle],
            C::Prismatic | C::InLine => &[JointValue::Travel],
            C::Cylindrical => &[JointValue::Angle, JointValue::Travel],
            _ => &[],
        }
    }

    /// The degrees of freedom the constraint removes when independent of the others, given
    /// its argument kinds (in canonical order) and its value. This is the nominal count that
    /// `gcs check` adds up before the real analysis; a zero distance removes as much as a
    /// coincidence, an angle of 0 or pi as much as parallelism.
    pub fn nominal_dof(self, space: Space, args: &[GeomKind], value: Option<f64>) -> usize {
        use ConstraintKind as C;
        use GeomKind as K;
        let d3 = space == Space::D3;
        let n = space.coords();
        let zero = value.is_some_and(|v| v == 0.0);
        let pair = (args.first().copied(), args.get(1).copied());
        match self {
            C::Coincident | C::Spherical => n,
            // In space a line at a distance from (or tangent to) a circle lies in its plane,
            // and two circles are coplanar: the distance is measured in that plane.
            C::Distance => match pair {
                (_, Some(K::Point | K::Marker)) if zero => n,
                (_, Some(K::Line | K::Segment)) if d3 && zero => 2,
                (_, Some(K::Circle)) if d3 && zero && args[0].is_pointlike() => 2,
                (Some(K::Line | K::Segment), Some(K::Circle)) if d3 => 3,
                (Some(K::Circle), Some(K::Circle)) if d3 => 4,
                _ => 1,
            },
            C::On => match pair {
                (_, Some(K::Line | K::Segment | K::Circle)) if d3 => 2,
                _ => 1,
            },
            C::Tangent => match pair {
                (Some(K::Circle), Some(K::Circle)) if d3 => 4,
                _ if d3 => 3,
                _ => 1,
            },
            C::Angle => {
                let straight = value.is_some_and(|v| {
                    v == 0.0 || (v.abs() - std::f64::consts::PI).abs() < gcs_tol::ANGLE
                });
                if d3 && straight {
                    2
                } else {
                    1
                }
            }
            C::Parallel => {
                if d3 {
                    2
                } else {
                    1
                }
            }
            C::Perpendicular | C::Horizontal | C::Vertical | C::Length | C::Radius => 1,
            // One dimension follows the other.
            C::Equal => 1,
            // A point's position either way: p from s, or one end of s from p and the other.
            C::Midpoint | C::Symmetric => n,
            C::InLine => {
                if d3 {
                    2
                } else {
                    1
                }
            }
            C::InPlane | C::OffsetZ => 1,
            C::ParallelZ => 2,
            C::OffsetX => {
                if d3 {
                    3
                } else {
                    1
                }
            }
            C::Helical => 3,
            C::Revolute => {
                if d3 {
                    5
                } else {
                    2
                }
            }
            C::Prismatic => {
                if d3 {
                    5
                } else {
                    2
                }
            }
            C::Cylindrical => 4,
            C::Planar => 3,
            // Every freedom of one frame relative to the other.
            C::Weld => {
                if d3 {
                    6
                } else {
                    3
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_covers_every_kind_once() {
        use ConstraintKind as C;
        let all = [
            C::Coincident,
            C::Distance,
            C::On,
            C::Tangent,
            C::Angle,
            C::Parallel,
            C::Perpendicular,
            C::Horizontal,
            C::Vertical,
            C::Length,
            C::Radius,
            C::Equal,
            C::Midpoint,
            C::Symmetric,
            C::InLine,
            C::InPlane,
            C::ParallelZ,
            C::OffsetZ,
            C::OffsetX,
            C::Helical,
            C::Revolute,
            C::Prismatic,
            C::Cylindrical,
            C::Spherical,
            C::Planar,
            C::Weld,
        ];
        assert_eq!(all.len(), TABLE.len());
        for k in all {
            assert_eq!(TABLE.iter().filter(|s| s.kind == k).count(), 1, "{k:?}");
            assert_eq!(k.spec().kind, k);
            assert_eq!(lookup(k.name()).map(|s| s.kind), Some(k));
        }
    }

    /// The kinds a joint value belongs to, and the words that list them in diagnostics, say
    /// the same: a joint left out of either would be refused, or listed, wrongly.
    #[test]
    fn joint_values_and_their_words_agree() {
        let mut with_values = 0;
        for spec in TABLE {
            for v in JointValue::ALL {
                let has = spec.kind.joint_values().contains(&v);
                let listed = v.joints_text().contains(&format!("`{}`", spec.name));
                assert_eq!(has, listed, "{} and .{}", spec.name, v.name());
                with_values += usize::from(has);
            }
        }
        assert_eq!(with_values, 6);
        for v in JointValue::ALL {
            assert_eq!(JointValue::named(v.name()), Some(v));
        }
        assert_eq!(JointValue::named("turn"), None);
    }

    #[test]
    fn nominal_dof_follows_kramer() {
        use GeomKind as K;
        let pp = [K::Point, K::Point];
        assert_eq!(
            ConstraintKind::Distance.nominal_dof(Space::D3, &pp, Some(0.0)),
            3
        );
        assert_eq!(
            ConstraintKind::Distance.nominal_dof(Space::D3, &pp, Some(2.0)),
            1
        );
        assert_eq!(
            ConstraintKind::Revolute.nominal_dof(Space::D3, &[K::Marker, K::Marker], None),
            5
        );
        assert_eq!(
            ConstraintKind::Revolute.nominal_dof(Space::D2, &[K::Marker, K::Marker], None),
            2
        );
        let ss = [K::Segment, K::Segment];
        assert_eq!(ConstraintKind::Equal.nominal_dof(Space::D2, &ss, None), 1);
        let ps = [K::Point, K::Segment];
        assert_eq!(
            ConstraintKind::Midpoint.nominal_dof(Space::D2, &ps, None),
            2
        );
        assert_eq!(
            ConstraintKind::Midpoint.nominal_dof(Space::D3, &ps, None),
            3
        );
        let ppl = [K::Point, K::Point, K::Line];
        assert_eq!(
            ConstraintKind::Symmetric.nominal_dof(Space::D2, &ppl, None),
            2
        );
        let ppq = [K::Point, K::Point, K::Plane];
        assert_eq!(
            ConstraintKind::Symmetric.nominal_dof(Space::D3, &ppq, None),
            3
        );
    }

    #[test]
    fn weld_is_a_coincidence_and_offset_x_0_of_two_markers_in_both_spaces() {
        use GeomKind as K;
        let w = ConstraintKind::Weld.spec();
        assert_eq!(lookup("weld").map(|s| s.kind), Some(ConstraintKind::Weld));
        assert_eq!(w.forms, &[&[A::Marker, A::Marker][..]][..]);
        assert!(!w.forms[0].iter().any(|c| c.accepts(K::Point)));
        assert!(w.form_spaces.is_empty() && !w.symmetric);
        assert_eq!(w.value, ValueKind::None);
        assert!(w.form_allows(0, Space::D2) && w.form_allows(0, Space::D3));
        let mm = [K::Marker, K::Marker];
        assert_eq!(ConstraintKind::Weld.nominal_dof(Space::D3, &mm, None), 6);
        assert_eq!(ConstraintKind::Weld.nominal_dof(Space::D2, &mm, None), 3);
        // As much as the coincidence and the offset_x(0) it stands for.
        for space in [Space::D2, Space::D3] {
            assert_eq!(
                ConstraintKind::Weld.nominal_dof(space, &mm, None),
                ConstraintKind::Coincident.nominal_dof(space, &mm, None)
                    + ConstraintKind::OffsetX.nominal_dof(space, &mm, Some(0.0)),
                "{space}"
            );
        }
    }

    #[test]
    fn symmetric_mirrors_across_a_line_in_2d_and_a_plane_in_3d() {
        let s = ConstraintKind::Symmetric.spec();
        assert_eq!(s.form_spaces.len(), s.forms.len());
        assert!(s.form_allows(0, Space::D2) && !s.form_allows(0, Space::D3));
        assert!(s.form_allows(1, Space::D3) && !s.form_allows(1, Space::D2));
        // A table without per-form spaces allows each form wherever the constraint is.
        let h = ConstraintKind::Horizontal.spec();
        assert!(h.form_allows(0, Space::D2) && !h.form_allows(0, Space::D3));
        for spec in TABLE {
            assert!(
                spec.form_spaces.is_empty() || spec.form_spaces.len() == spec.forms.len(),
                "{}: one space per form, or none",
                spec.name
            );
        }
    }
}
