//! Rigid frames and Kramer's three actions: translate, rotate and scale (paper 000, section 4).
//!
//! Every geom is a rigid frame (a position and an orientation) plus optional dimensions (a
//! radius, a length). Its member points and vectors are stored in the frame's *local*
//! coordinates; [`Frame2::point_to_global`] and [`Frame3::point_to_global`] give their global
//! position, and the `*_to_local` methods go back. A plan fragment moves a geom only through the
//! actions:
//!
//! - **translate** by a vector ([`Frame2::translate`], [`Frame3::translate`]);
//! - **rotate** about a point (2d) or about a point and an axis (3d) by an angle
//!   ([`Frame2::rotate_about`], [`Frame3::rotate_about`], [`Frame3::rotate_about_by`]);
//! - **scale** the dimensions about a point ([`Frame2::scale_about`], [`Frame3::scale_about`],
//!   with the free functions [`scale_point2_about`] and [`scale_point3_about`]).
//!
//! Measurements used to build actions live here too: [`signed_angle2`], [`signed_angle3`] and
//! [`rotation_between3`] (rotate one vector onto another, the identity when their cross product
//! vanishes, paper 000 footnote 6); and those a solved joint's value is read by
//! ([`joint_angle3`], [`joint_travel3`] and their planar twins), which the interpreter and
//! generated solvers share.
//!
//! Nothing here allocates or panics. Non-finite input (NaN, infinity) is not detected here: it
//! propagates into the resulting frame as NaN or infinite components, which the solver's input
//! validation ([`crate::error::check_finite`]) is meant to prevent. A zero rotation axis yields
//! the identity rotation, never NaN.

use nalgebra::{Point2, Point3, Unit, UnitComplex, UnitQuaternion, Vector2, Vector3};

use crate::num::is_finite;
use crate::tol;

/// A rigid frame in the plane: the global position of its local origin and the rotation that
/// takes local directions to global ones.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame2 {
    /// Global position of the local origin.
    pub origin: Point2<f64>,
    /// Rotation from local to global directions.
    pub rotation: UnitComplex<f64>,
}

impl Default for Frame2 {
    fn default() -> Self {
        Self::identity()
    }
}

impl Frame2 {
    /// The global frame itself.
    #[inline]
    pub fn identity() -> Self {
        Self {
            origin: Point2::origin(),
            rotation: UnitComplex::identity(),
        }
    }

    /// A frame at `origin`, rotated counter-clockwise by `angle` radians.
    #[inline]
    pub fn new(origin: Point2<f64>, angle: f64) -> Self {
        Self {
            origin,
            rotation: UnitComplex::new(angle),
        }
    }

    /// A frame at `origin`, not rotated. No trigonometry: what a generated solver uses for a
    /// sketch with no rotation.
    #[inline]
    pub fn at(origin: Point2<f64>) -> Self {
        Self {
            origin,
            rotation: UnitComplex::identity(),
        }
    }

    /// A frame at `origin` whose x axis points along `dir` (normalised here; a zero or
    /// non-finite `dir` gives no rotation). No trigonometry.
    #[inline]
    pub fn along(origin: Point2<f64>, dir: Vector2<f64>) -> Self {
        Self {
            origin,
            rotation: rotation_between2(&Vector2::x(), &dir),
        }
    }

    /// A frame at `origin` rotated by the angle whose cosine and sine are given (a unit pair,
    /// as computed once when the solver was generated).
    #[inline]
    pub fn from_cos_sin(origin: Point2<f64>, cos: f64, sin: f64) -> Self {
        Self {
            origin,
            rotation: UnitComplex::from_cos_sin_unchecked(cos, sin),
        }
    }

    /// The counter-clockwise angle of the local x axis, in `(-pi, pi]`.
    #[inline]
    pub fn angle(&self) -> f64 {
        self.rotation.angle()
    }

    /// The global direction of the local x axis.
    #[inline]
    pub fn x_axis(&self) -> Vector2<f64> {
        // The rotation's cosine and sine: what `rotation * x` gives, without multiplying by
        // the zero component (which the compiler may not fold away: NaN times zero is NaN).
        Vector2::new(self.rotation.re, self.rotation.im)
    }

    /// The global direction of the local y axis.
    #[inline]
    pub fn y_axis(&self) -> Vector2<f64> {
        Vector2::new(-self.rotation.im, self.rotation.re)
    }

    /// Whether two frames place a body alike: origins within `length_tol` and rotations
    /// within [`tol::SAME_ASSEMBLY_REL`], componentwise. The duplicate test of a
    /// generated `solve_all`: a body's frame in place of all its markers' points and axes.
    #[inline]
    pub fn same_placement(&self, other: &Frame2, length_tol: f64) -> bool {
        let near = |a: f64, b: f64| (a - b).abs() <= tol::SAME_ASSEMBLY_REL;
        (self.origin - other.origin).amax() <= length_tol
            && near(self.rotation.re, other.rotation.re)
            && near(self.rotation.im, other.rotation.im)
    }

    /// The sum of what [`Frame2::same_placement`] compares: two frames it calls alike differ
    /// here by at most 4 times its largest tolerance.
    #[inline]
    pub fn placement_sum(&self) -> f64 {
        self.origin.coords.sum() + self.rotation.re + self.rotation.im
    }

    /// Global position of a member point given in local coordinates.
    #[inline]
    pub fn point_to_global(&self, local: &Point2<f64>) -> Point2<f64> {
        self.origin + self.rotation * local.coords
    }

    /// Local coordinates of a global point.
    #[inline]
    pub fn point_to_local(&self, global: &Point2<f64>) -> Point2<f64> {
        Point2::from(self.rotation.inverse() * (global - self.origin))
    }

    /// Global direction of a member vector given in local coordinates.
    #[inline]
    pub fn vector_to_global(&self, local: &Vector2<f64>) -> Vector2<f64> {
        self.rotation * local
    }

    /// Local coordinates of a global vector.
    #[inline]
    pub fn vector_to_local(&self, global: &Vector2<f64>) -> Vector2<f64> {
        self.rotation.inverse() * global
    }

    /// Action **translate**: moves the frame by `v`.
    #[inline]
    pub fn translate(&mut self, v: &Vector2<f64>) {
        self.origin += v;
    }

    /// Action **rotate**: turns the frame counter-clockwise by `angle` radians about the global
    /// point `center`, which stays fixed (as does every member point located there).
    #[inline]
    pub fn rotate_about(&mut self, center: &Point2<f64>, angle: f64) {
        self.rotate_about_by(center, &UnitComplex::new(angle));
    }

    /// Action **translate**, when the point brought to `at` is the frame's origin: it lands
    /// there exactly, where adding the shift `at - origin` could miss by a rounding.
    #[inline]
    pub fn place_origin(&mut self, at: &Point2<f64>) {
        self.origin = *at;
    }

    /// Action **rotate** about the frame's own origin, which stays where it is:
    /// [`Frame2::rotate_about_by`] with the origin as centre, without the arithmetic on it.
    #[inline]
    pub fn turn_by(&mut self, rotation: &UnitComplex<f64>) {
        self.rotation = rotation * self.rotation;
    }

    /// Action **rotate** about the frame's own origin, when its rotation is still the
    /// identity: the frame's rotation becomes `rotation`, to the bit what
    /// [`Frame2::turn_by`] gives, without multiplying by the identity.
    #[inline]
    pub fn set_rotation(&mut self, rotation: &UnitComplex<f64>) {
        self.rotation = *rotation;
    }

    /// Action **rotate** by a given rotation about the global point `center`.
    #[inline]
    pub fn rotate_about_by(&mut self, center: &Point2<f64>, rotation: &UnitComplex<f64>) {
        self.origin = center + rotation * (self.origin - center);
        self.rotation = rotation * self.rotation;
    }

    /// Action **scale**: scales the geom about the global point `center` by `factor`.
    ///
    /// The origin moves to `center + factor * (origin - center)`, the orientation is unchanged,
    /// and every dimension in `dims` (a radius, a length) is multiplied by `factor`. Member points
    /// whose local coordinates are defined by those dimensions (a circle's rim point, a segment's
    /// end) therefore scale with them, and `center` stays fixed. `factor` should be positive; a
    /// negative factor would mirror the geom and is applied to the dimensions as given (the
    /// caller must not pass one), a zero factor collapses it.
    #[inline]
    pub fn scale_about(&mut self, center: &Point2<f64>, factor: f64, dims: &mut [f64]) {
        self.origin = scale_point2_about(&self.origin, center, factor);
        for d in dims.iter_mut() {
            *d *= factor;
        }
    }
}

/// A rigid frame in space: the global position of its local origin and the rotation that takes
/// local directions to global ones.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame3 {
    /// Global position of the local origin.
    pub origin: Point3<f64>,
    /// Rotation from local to global directions.
    pub rotation: UnitQuaternion<f64>,
}

impl Default for Frame3 {
    fn default() -> Self {
        Self::identity()
    }
}

impl Frame3 {
    /// The global frame itself.
    #[inline]
    pub fn identity() -> Self {
        Self {
            origin: Point3::origin(),
            rotation: UnitQuaternion::identity(),
        }
    }

    /// A frame at `origin` with orientation `rotation`.
    #[inline]
    pub fn new(origin: Point3<f64>, rotation: UnitQuaternion<f64>) -> Self {
        Self { origin, rotation }
    }

    /// The global direction of the local x axis.
    #[inline]
    pub fn x_axis(&self) -> Vector3<f64> {
        self.rotation * Vector3::x()
    }

    /// The global direction of the local y axis.
    #[inline]
    pub fn y_axis(&self) -> Vector3<f64> {
        self.rotation * Vector3::y()
    }

    /// The global direction of the local z axis.
    #[inline]
    pub fn z_axis(&self) -> Vector3<f64> {
        self.rotation * Vector3::z()
    }

    /// Whether two frames place a body alike: origins within `length_tol` and rotations
    /// within [`tol::SAME_ASSEMBLY_REL`], componentwise, a quaternion and its
    /// negative being one rotation. The duplicate test of a generated `solve_all`: a body's
    /// frame in place of all its markers' points and axes (a turn by `d` moves a quaternion
    /// by at most `d / 2`, and a unit axis by at most `d`).
    #[inline]
    pub fn same_placement(&self, other: &Frame3, length_tol: f64) -> bool {
        let (p, q) = (self.rotation.coords, other.rotation.coords);
        (self.origin - other.origin).amax() <= length_tol
            && ((p - q).amax() <= tol::SAME_ASSEMBLY_REL
                || (p + q).amax() <= tol::SAME_ASSEMBLY_REL)
    }

    /// The sum of what [`Frame3::same_placement`] compares, the rotation's by the absolute
    /// values of its components (which a quaternion and its negative share): two frames it
    /// calls alike differ here by at most 7 times its largest tolerance.
    #[inline]
    pub fn placement_sum(&self) -> f64 {
        self.origin.coords.sum() + self.rotation.coords.abs().sum()
    }

    /// Global position of a member point given in local coordinates.
    #[inline]
    pub fn point_to_global(&self, local: &Point3<f64>) -> Point3<f64> {
        self.origin + self.rotation * local.coords
    }

    /// Local coordinates of a global point.
    #[inline]
    pub fn point_to_local(&self, global: &Point3<f64>) -> Point3<f64> {
        Point3::from(
            self.rotation
                .inverse_transform_vector(&(global - self.origin)),
        )
    }

    /// Global direction of a member vector given in local coordinates.
    #[inline]
    pub fn vector_to_global(&self, local: &Vector3<f64>) -> Vector3<f64> {
        self.rotation * local
    }

    /// Local coordinates of a global vector.
    #[inline]
    pub fn vector_to_local(&self, global: &Vector3<f64>) -> Vector3<f64> {
        self.rotation.inverse_transform_vector(global)
    }

    /// Action **translate**: moves the frame by `v`.
    #[inline]
    pub fn translate(&mut self, v: &Vector3<f64>) {
        self.origin += v;
    }

    /// Action **rotate**: turns the frame by `angle` radians about the line through the global
    /// point `center` with direction `axis` (right-handed: counter-clockwise seen from the tip
    /// of `axis`). Every point on that line stays fixed.
    ///
    /// `axis` need not be a unit vector. A zero (or sub-normal) `axis` is the case of
    /// footnote 6 of paper 000: the action does nothing.
    #[inline]
    pub fn rotate_about(&mut self, center: &Point3<f64>, axis: &Vector3<f64>, angle: f64) {
        self.rotate_about_by(center, &rotation_about_axis(axis, angle));
    }

    /// Action **rotate** by a given rotation about the global point `center`, which stays fixed.
    #[inline]
    pub fn rotate_about_by(&mut self, center: &Point3<f64>, rotation: &UnitQuaternion<f64>) {
        self.origin = center + rotation * (self.origin - center);
        self.rotation = rotation * self.rotation;
    }

    /// Action **scale**: scales the geom about the global point `center` by `factor`.
    ///
    /// The origin moves to `center + factor * (origin - center)`, the orientation is unchanged,
    /// and every dimension in `dims` (a radius, a length) is multiplied by `factor`. Member points
    /// whose local coordinates are defined by those dimensions scale with them, and `center`
    /// stays fixed. `factor` should be positive (see [`Frame2::scale_about`]).
    #[inline]
    pub fn scale_about(&mut self, center: &Point3<f64>, factor: f64, dims: &mut [f64]) {
        self.origin = scale_point3_about(&self.origin, center, factor);
        for d in dims.iter_mut() {
            *d *= factor;
        }
    }
}

/// The point `center + factor * (p - center)`: `p` scaled about `center` (2d).
#[inline]
pub fn scale_point2_about(p: &Point2<f64>, center: &Point2<f64>, factor: f64) -> Point2<f64> {
    center + (p - center) * factor
}

/// The point `center + factor * (p - center)`: `p` scaled about `center` (3d).
#[inline]
pub fn scale_point3_about(p: &Point3<f64>, center: &Point3<f64>, factor: f64) -> Point3<f64> {
    center + (p - center) * factor
}

/// The scale factor that takes a dimension from `current` to `target` (`target / current`), for
/// the **scale** action. `None` when `current` is zero relative to `target`
/// ([`tol::LENGTH_REL`]) or either is not finite: no factor can then grow the dimension.
#[inline]
pub fn scale_factor(current: f64, target: f64) -> Option<f64> {
    let s = tol::scale(&[current, target]);
    if !is_finite(current) || !is_finite(target) || tol::is_zero(current, s, tol::LENGTH_REL) {
        None
    } else {
        Some(target / current)
    }
}

/// The rotation by `angle` radians about `axis` (right-handed), or the identity when `axis` is
/// zero (footnote 6 of paper 000). A NaN in `axis` or `angle` yields a NaN quaternion.
#[inline]
pub fn rotation_about_axis(axis: &Vector3<f64>, angle: f64) -> UnitQuaternion<f64> {
    match Unit::try_new(*axis, 0.0) {
        Some(a) => UnitQuaternion::from_axis_angle(&a, angle),
        None => UnitQuaternion::identity(),
    }
}

/// The rotation about `axis` that turns the projection of `u` across it onto the direction of
/// the projection of `v`: `rotation_about_axis(axis, signed_angle3(u, v, axis))` to rounding,
/// without the angle (no `atan2`, no `sin_cos`). The identity when `axis` or a projection is
/// zero; a NaN quaternion when an input has a NaN.
#[inline]
pub fn turn_about_axis(
    axis: &Vector3<f64>,
    u: &Vector3<f64>,
    v: &Vector3<f64>,
) -> UnitQuaternion<f64> {
    let n = axis.norm();
    if n.is_nan() {
        return nan_rotation();
    }
    if n <= 0.0 {
        return UnitQuaternion::identity();
    }
    let a = axis / n;
    let (sin, cos) = turn_across(&a, u, v);
    rotation_by_sin_cos(&a, sin, cos)
}

/// The rotation about the unit `a` by the angle whose sine and cosine are `sin` and `cos`
/// times one positive factor. The half angle's cosine and sine are, to a common factor,
/// `(r + cos, sin)` on the near half turn and `(sin, r - cos)` on the far one (`r` the
/// factor): each form adds numbers of one sign, so neither cancels, and no angle is taken.
/// The scalar part is kept non-negative, as `from_axis_angle` has it for angles in
/// `[-pi, pi]`. The identity when both are zero (`atan2(0, 0)`); NaN when either is.
#[inline]
fn rotation_by_sin_cos(a: &Vector3<f64>, sin: f64, cos: f64) -> UnitQuaternion<f64> {
    let m = sin.abs().max(cos.abs());
    if sin.is_nan() || cos.is_nan() {
        return nan_rotation();
    }
    if m <= 0.0 {
        return UnitQuaternion::identity();
    }
    // Scaled to at most one, so that the squares cannot overflow.
    let (s, c) = (sin / m, cos / m);
    let r = (s * s + c * c).sqrt();
    let (mut w, mut k) = if c >= 0.0 { (r + c, s) } else { (s, r - c) };
    if w < 0.0 {
        (w, k) = (-w, -k);
    }
    let h = (w * w + k * k).sqrt();
    let (w, k) = (w / h, k / h);
    UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(w, a.x * k, a.y * k, a.z * k))
}

/// The rotation of a NaN input: every component NaN, as `from_axis_angle` gives for a NaN
/// angle, so that it reaches the solution's checks instead of passing as a turn.
#[cold]
fn nan_rotation() -> UnitQuaternion<f64> {
    UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(
        f64::NAN,
        f64::NAN,
        f64::NAN,
        f64::NAN,
    ))
}

/// The signed counter-clockwise angle from `u` to `v`, in `[-pi, pi]`. Zero when either vector
/// is zero; NaN when either has a NaN component.
#[inline]
pub fn signed_angle2(u: &Vector2<f64>, v: &Vector2<f64>) -> f64 {
    (u.x * v.y - u.y * v.x).atan2(u.dot(v))
}

/// The signed angle from `u` to `v` measured about `axis`, in `[-pi, pi]`: the angle by which
/// [`Frame3::rotate_about`] with this `axis` turns the projection of `u` onto the plane
/// perpendicular to `axis` onto the projection of `v`.
///
/// `axis` need not be a unit vector. Zero when `axis`, or a projection, is zero. Paper 000's
/// brick measures the angle from v1 to v2 about `v1 x v2`, which this returns in `[0, pi]`.
#[inline]
pub fn signed_angle3(u: &Vector3<f64>, v: &Vector3<f64>, axis: &Vector3<f64>) -> f64 {
    let n = axis.norm();
    if n.is_nan() || n <= 0.0 {
        return 0.0;
    }
    let (sin, cos) = turn_across(&(axis / n), u, v);
    sin.atan2(cos)
}

/// The sine and cosine parts, times the lengths of the projections, of the turn from `u` to
/// `v` about the unit axis `a`. Across the axis first: a direction nearly along it keeps its
/// few significant bits there, which the products of the whole vectors would cancel.
#[inline]
pub(crate) fn turn_across(a: &Vector3<f64>, u: &Vector3<f64>, v: &Vector3<f64>) -> (f64, f64) {
    let up = u - a * a.dot(u);
    let vp = v - a * a.dot(v);
    (a.dot(&up.cross(&vp)), up.dot(&vp))
}

/// The angle about `axis` that turns `u[0]` onto `v[0]` and `u[1]` onto `v[1]` together: the
/// argument of the sum of the two turns, each as the complex product of its projections across
/// the axis, so that each pair weighs by how far across the axis it lies. When both pairs turn
/// by the same angle it is that angle, as [`signed_angle3`] gives for either; but a pair nearly
/// along the axis, whose own angle rounding fixes only to `eps` over its distance from it, no
/// longer decides it alone (a marker whose z axis lies 1e-6 rad off the axis, and whose x axis
/// is then across it). In `[-pi, pi]`; zero when `axis` is zero.
#[inline]
pub fn signed_angle3_both(
    u: [&Vector3<f64>; 2],
    v: [&Vector3<f64>; 2],
    axis: &Vector3<f64>,
) -> f64 {
    let n = axis.norm();
    if n.is_nan() || n <= 0.0 {
        return 0.0;
    }
    let a = axis / n;
    let (s0, c0) = turn_across(&a, u[0], v[0]);
    let (s1, c1) = turn_across(&a, u[1], v[1]);
    (s0 + s1).atan2(c0 + c1)
}

/// The rotation that turns the direction of `u` onto the direction of `v` about the axis
/// `u x v` (the rotate step of paper 000's brick).
///
/// - When `u` and `v` point the same way, the turn is about their cross product however
///   small: a turn of 1e-13 rad is made, not left out (its axis is then known only to
///   rounding over the sine, but it turns by so little that the result is still exact to
///   rounding). When the cross product vanishes (footnote 6 of paper 000), or either vector
///   is zero, the result is the identity, never NaN.
/// - When they are anti-parallel, any axis perpendicular to `u` works and the cross product
///   cannot choose one: the result is the half turn about `fallback_axis` with its component
///   along `u` removed (pass the axis the geom is allowed to rotate about). If that leaves
///   nothing (`fallback_axis` zero or parallel to `u`), the half turn is about the
///   deterministic axis `u x e_k`, `e_k` the coordinate axis least aligned with `u`.
///
/// "Anti-parallel" means that the sine of the angle is below [`tol::ANGLE`] and the cosine
/// negative.
pub fn rotation_between3(
    u: &Vector3<f64>,
    v: &Vector3<f64>,
    fallback_axis: &Vector3<f64>,
) -> UnitQuaternion<f64> {
    let nu = u.norm();
    let nv = v.norm();
    if nu.is_nan() || nv.is_nan() || nu <= 0.0 || nv <= 0.0 {
        return UnitQuaternion::identity();
    }
    let uh = u / nu;
    let vh = v / nv;
    let cross = uh.cross(&vh);
    let sin = cross.norm();
    let cos = uh.dot(&vh);
    if sin > tol::ANGLE || (sin > 0.0 && cos > 0.0) {
        return rotation_by_sin_cos(&(cross / sin), sin, cos);
    }
    if cos.is_nan() || cos >= 0.0 {
        // Parallel to the last bit, or NaN: identity (footnote 6).
        return UnitQuaternion::identity();
    }
    // Anti-parallel: half turn about an axis perpendicular to u.
    let f = fallback_axis - uh * uh.dot(fallback_axis);
    let fn_ = f.norm();
    let axis = if fn_ > tol::ANGLE * fallback_axis.norm() && fn_ > 0.0 {
        f / fn_
    } else {
        let p = perpendicular(&uh);
        p / p.norm()
    };
    UnitQuaternion::from_axis_angle(&Unit::new_unchecked(axis), std::f64::consts::PI)
}

/// A non-zero vector perpendicular to `u` (for a non-zero `u`): `u x e_k`, with `e_k` the
/// coordinate axis along which `u` has its smallest absolute component. Deterministic.
#[inline]
pub fn perpendicular(u: &Vector3<f64>) -> Vector3<f64> {
    let (ax, ay, az) = (u.x.abs(), u.y.abs(), u.z.abs());
    let e = if ax <= ay && ax <= az {
        Vector3::x()
    } else if ay <= az {
        Vector3::y()
    } else {
        Vector3::z()
    };
    u.cross(&e)
}

/// The rotation that turns the direction of `a` onto the direction of `b`, computed without
/// trigonometry (a normalised complex number `(a . b, a x b)`). When either vector is zero or
/// not finite, or the two are exactly opposite with a zero cross product, the result is
/// well-defined: the identity for a zero vector (paper 000, footnote 6), a half turn for
/// opposite directions.
#[inline]
pub fn rotation_between2(a: &Vector2<f64>, b: &Vector2<f64>) -> UnitComplex<f64> {
    let c = a.dot(b);
    let s = a.x * b.y - a.y * b.x;
    // The plan's case: a point turned onto a target at its own distance from the pivot, so
    // `|a| = |b|` to rounding and `|a| |b|` is their mean square, `(|a|^2 + |b|^2) / 2`, to
    // second order in the difference: one division and no square root. One Newton step on the
    // norm makes the pair unit to rounding; when the lengths differ by more than about 1e-4
    // (relative), the exact path below takes over.
    let mean = 0.5 * (a.norm_squared() + b.norm_squared());
    if mean > 1e-250 && mean < 1e250 {
        let inv = 1.0 / mean;
        let (c1, s1) = (c * inv, s * inv);
        let n1 = c1 * c1 + s1 * s1;
        if (n1 - 1.0).abs() < tol::NEWTON_UNIT {
            let k = 1.5 - 0.5 * n1;
            return UnitComplex::from_cos_sin_unchecked(c1 * k, s1 * k);
        }
    }
    // Lengths that differ: one square root and one division.
    let n2 = c * c + s * s;
    if n2 > 1e-250 && n2 < 1e250 {
        let inv = 1.0 / n2.sqrt();
        return UnitComplex::from_cos_sin_unchecked(c * inv, s * inv);
    }
    // Tiny or huge: scaled by the larger component first, so that the square root neither
    // overflows nor underflows.
    let m = c.abs().max(s.abs());
    if !(m > 0.0 && m.is_finite()) {
        return UnitComplex::identity();
    }
    let (c, s) = (c / m, s / m);
    let n = (c * c + s * s).sqrt();
    UnitComplex::from_cos_sin_unchecked(c / n, s / n)
}

/// The rotation about a circle's centre that turns `a` onto `b`, two radii of the circle:
/// both of length `radius` to rounding, as the plan knows when it turns a point of a rigid
/// geom onto a target on that point's circle. The result of [`rotation_between2`] to
/// rounding (unit to a few ulps, the direction exact), by a shorter fast path: with the
/// radius known (a constant in generated code), the division is by `radius^2`, which the
/// compiler folds. When the lengths differ from the radius by more than about 5e-9 (relative,
/// the two together: `c² + s²` more than 1e-8 from 1), it is [`rotation_between2`].
#[inline]
pub fn rotation_on_circle(a: &Vector2<f64>, b: &Vector2<f64>, radius: f64) -> UnitComplex<f64> {
    let inv = 1.0 / (radius * radius);
    rotation_on_circle_from(a.dot(b) * inv, (a.x * b.y - a.y * b.x) * inv, a, b)
}

/// [`rotation_on_circle`] from its cosine and sine as the caller computed them,
/// `(a . b, a x b) / radius²`: generated code that knows the arm `a` as constants writes them
/// with constant coefficients, and no product by a zero coordinate.
///
/// - Unit to rounding (`|c² + s² - 1|` at most 4 ulps), as they are when `b` lies on
///   the circle: they are the rotation as they are, with nothing on the solve's critical path.
/// - Within 1e-8 of unit: one Newton step makes them unit (to about `(3/8) 1e-16`, rounding).
/// - Otherwise (and for NaN) the lengths disagree with the radius, and the rotation is
///   [`rotation_between2`] of `a` and `b`.
#[inline]
pub fn rotation_on_circle_from(
    c: f64,
    s: f64,
    a: &Vector2<f64>,
    b: &Vector2<f64>,
) -> UnitComplex<f64> {
    let n = c * c + s * s;
    let off = (n - 1.0).abs();
    if off <= tol::UNIT_ROUNDING {
        return UnitComplex::from_cos_sin_unchecked(c, s);
    }
    if off < tol::NEWTON_UNIT {
        let k = 1.5 - 0.5 * n;
        return UnitComplex::from_cos_sin_unchecked(c * k, s * k);
    }
    rotation_between2(a, b)
}

/// The rotation that turns the x axis onto unit vector `b`: [`rotation_between_units`] from
/// `(1, 0)`, which is `b` itself read as a rotation. Non-finite input gives the identity.
#[inline]
pub fn rotation_from_x(b: &Vector2<f64>) -> UnitComplex<f64> {
    if is_finite(b.x) && is_finite(b.y) && (b.x != 0.0 || b.y != 0.0) {
        rotation_from_x_unit(b)
    } else {
        UnitComplex::identity()
    }
}

/// The rotation that turns the x axis onto `b`, a unit vector known to be finite (such as
/// [`direction_at`] of a finite angle): `b` itself read as a rotation, with no test. For a
/// direction that may not be finite, [`rotation_from_x`].
#[inline]
pub fn rotation_from_x_unit(b: &Vector2<f64>) -> UnitComplex<f64> {
    UnitComplex::from_cos_sin_unchecked(b.x, b.y)
}

/// The unit vector at `angle` radians counter-clockwise from the x axis: the x axis turned
/// by `angle`, `(cos, sin)`.
#[inline]
pub fn direction_at(angle: f64) -> Vector2<f64> {
    let (sin, cos) = crate::num::sin_cos(angle);
    Vector2::new(cos, sin)
}

/// The directions of angles near one angle, the start of an outer iteration over an angle
/// default: its trials stay within a small turn of their start (a sweep's last answer, one
/// step on), and each trial's direction is the start's turned by the difference, whose sine
/// and cosine are short polynomials ([`crate::num::sin_cos_small`]) where [`direction_at`]
/// would reduce the angle and evaluate its kernels at every trial. Within a few ulps of
/// [`direction_at`] (property-tested); angles farther than [`DirectionsNear::REACH`] from the
/// start are [`direction_at`]'s.
#[derive(Clone, Copy, Debug)]
pub struct DirectionsNear {
    angle: f64,
    direction: Vector2<f64>,
}

impl DirectionsNear {
    /// The largest difference from the start turned by polynomials: the domain of
    /// [`crate::num::sin_cos_small`].
    pub const REACH: f64 = crate::num::SMALL_ANGLE;

    /// The directions near `angle`.
    #[inline]
    pub fn new(angle: f64) -> Self {
        Self {
            angle,
            direction: direction_at(angle),
        }
    }

    /// The unit vector at `angle`, as [`direction_at`] to a few ulps.
    #[inline]
    pub fn at(&self, angle: f64) -> Vector2<f64> {
        let turn = angle - self.angle;
        if turn.abs() <= Self::REACH {
            let (sin, cos) = crate::num::sin_cos_small(turn);
            let d = self.direction;
            Vector2::new(d.x * cos - d.y * sin, d.x * sin + d.y * cos)
        } else {
            direction_at(angle)
        }
    }
}

/// The rotation that turns unit vector `a` onto unit vector `b`: `(a . b, a x b)` with no
/// square root or division. The plan's directions are unit by construction; their products
/// stay unit to rounding. Non-finite input gives the identity.
#[inline]
pub fn rotation_between_units(a: &Vector2<f64>, b: &Vector2<f64>) -> UnitComplex<f64> {
    let (c, s) = (a.dot(b), a.x * b.y - a.y * b.x);
    if is_finite(c) && is_finite(s) && (c != 0.0 || s != 0.0) {
        UnitComplex::from_cos_sin_unchecked(c, s)
    } else {
        UnitComplex::identity()
    }
}

/// The directions `v` may turn to about unit `axis` (its cone about the axis) that make the
/// unsigned angle `angle` with unit `u`: the turns `phi` about `axis` solving
/// `u . v(phi) = cos(angle)`.
///
/// - **Branch:** with `phi0` the turn that brings `v` nearest `u`, branch 0 is `phi0 + delta`
///   (counter-clockwise about `axis` from there), branch 1 `phi0 - delta`, `delta` in
///   `[0, pi]`: a fixed branch moves continuously until the two meet (a tangency).
/// - `Crossing`: two directions. `Tangent` (the angle is the cone's nearest or farthest from
///   `u` within [`tol::ANGLE`]): the double root in both slots.
/// - `Disjoint { gap }`: no turn reaches the angle; `gap` is how far (radians) the nearest
///   reachable angle is from it.
/// - `ZeroRadius`: `v` or `u` is along the axis (every turn keeps the angle: no turn is
///   determined), or a vector is zero.
pub fn turns_to_angle(
    u: &Vector3<f64>,
    v: &Vector3<f64>,
    axis: &Vector3<f64>,
    angle: f64,
) -> crate::Intersection<Vector3<f64>, 2> {
    use crate::{Contact, Intersection, Roots};
    // Each vector's test written out: a chain of iterators is not optimised to it.
    let finite = |w: &Vector3<f64>| w.x.is_finite() && w.y.is_finite() && w.z.is_finite();
    if !(finite(u) && finite(v) && finite(axis) && angle.is_finite()) {
        return Intersection::none(Contact::Disjoint { gap: f64::NAN });
    }
    let along = axis * axis.dot(v);
    let across = v - along;
    let side = axis.cross(&across);
    let (a, b) = (u.dot(&across), u.dot(&side));
    let r = a.hypot(b);
    if across.norm() <= tol::ANGLE || r <= tol::ANGLE {
        return Intersection::none(Contact::ZeroRadius);
    }
    let c = angle.cos() - u.dot(&along);
    // Well inside the reachable angles (an angle is at least as far from another as its
    // cosine is), the two crossings need no angle: `phi0 +- delta` from the cosines and sines
    // of `phi0` (`(a, b) / r`) and of `delta` (`c / r`), without `atan2`, `acos` or `sin_cos`.
    let (base, ratio) = (u.dot(&along), c / r);
    let inside = base.abs() + r <= 1.0
        && r * (1.0 - ratio) > 2.0 * tol::ANGLE
        && r * (1.0 + ratio) > 2.0 * tol::ANGLE;
    if inside && (0.0..=std::f64::consts::PI).contains(&angle) {
        let (cos0, sin0) = (a / r, b / r);
        let sin_delta = ((1.0 - ratio) * (1.0 + ratio)).sqrt();
        let (cc, ss) = (cos0 * ratio, sin0 * sin_delta);
        let (sc, cs) = (sin0 * ratio, cos0 * sin_delta);
        return Intersection {
            roots: Roots::from_slice(&[
                along + across * (cc - ss) + side * (sc + cs),
                along + across * (cc + ss) + side * (sc - cs),
            ]),
            contact: Contact::Crossing,
        };
    }
    let at = |phi: f64| -> Vector3<f64> {
        let (s, co) = phi.sin_cos();
        along + across * co + side * s
    };
    let phi0 = b.atan2(a);
    // The reachable angles run from the nearest (cosine base + r) to the farthest (base - r).
    let (nearest, farthest) = (
        (base + r).clamp(-1.0, 1.0).acos(),
        (base - r).clamp(-1.0, 1.0).acos(),
    );
    let target = angle.clamp(0.0, std::f64::consts::PI);
    if target < nearest - tol::ANGLE || target > farthest + tol::ANGLE {
        let gap = (nearest - target).max(target - farthest);
        return Intersection::none(Contact::Disjoint { gap });
    }
    if ratio >= 1.0
        || ratio <= -1.0
        || (target - nearest).abs() <= tol::ANGLE
        || (farthest - target).abs() <= tol::ANGLE
    {
        let phi = if ratio >= 0.0 {
            phi0
        } else {
            phi0 + std::f64::consts::PI
        };
        let x = at(phi);
        return Intersection {
            roots: Roots::from_slice(&[x, x]),
            contact: Contact::Tangent,
        };
    }
    let delta = ratio.acos();
    Intersection {
        roots: Roots::from_slice(&[at(phi0 + delta), at(phi0 - delta)]),
        contact: Contact::Crossing,
    }
}

/// An orthonormal pair across unit `n`: [`perpendicular`] of it, normalised, and `n` across
/// that. Where a circle's angles start, and the two ways off a line.
#[inline]
pub fn across(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let e1 = perpendicular(n).normalize();
    (e1, n.cross(&e1))
}

/// `v` over its length; `None` for a zero or not-a-number length, where no direction is.
#[inline]
pub fn unit3(v: &Vector3<f64>) -> Option<Vector3<f64>> {
    let n = v.norm();
    if n.is_nan() || n <= 0.0 {
        return None;
    }
    Some(v / n)
}

/// The rotation of a sketch whose x axis is `x` (a vector's, a line's, a segment's): the
/// shortest turn from the global x axis; `None` for a zero `x`.
pub fn rotation_onto_x(x: &Vector3<f64>) -> Option<UnitQuaternion<f64>> {
    let x = x.try_normalize(0.0)?;
    Some(rotation_between3(&Vector3::x(), &x, &Vector3::z()))
}

/// The rotation of a sketch whose z axis is `z` (a circle's or a plane's normal): the shortest
/// turn from the global z axis; `None` for a zero `z`.
pub fn rotation_onto_z(z: &Vector3<f64>) -> Option<UnitQuaternion<f64>> {
    let z = z.try_normalize(0.0)?;
    Some(rotation_between3(&Vector3::z(), &z, &Vector3::x()))
}

/// The rotation of a marker whose z axis is `z` and whose x axis is `x` made perpendicular to
/// it (the language checks that a marker's axes are orthogonal, up to rounding); `None` for a
/// zero axis, or an `x` along `z`.
pub fn rotation_zx(z: &Vector3<f64>, x: &Vector3<f64>) -> Option<UnitQuaternion<f64>> {
    let z = z.try_normalize(0.0)?;
    let x = (x - z * z.dot(x)).try_normalize(0.0)?;
    let y = z.cross(&x);
    Some(UnitQuaternion::from_rotation_matrix(
        &nalgebra::Rotation3::from_basis_unchecked(&[x, y, z]),
    ))
}

/// The rotation of a body placed `rotated angle about axis`: none for a zero angle, whatever
/// the axis; `None` for a turn about a zero axis.
pub fn rotation_sketched(axis: &Vector3<f64>, angle: f64) -> Option<UnitQuaternion<f64>> {
    if angle == 0.0 {
        return Some(UnitQuaternion::identity());
    }
    let u = Unit::try_new(*axis, 0.0)?;
    Some(UnitQuaternion::from_axis_angle(&u, angle))
}

/// A plane through `base` with unit normal `normal`, turning about `pivot` until it is at
/// signed distance `d` from `point`: the vector from the pivot to the point, and the cosine
/// its direction must make with the new normal (the turn keeps the pivot's distance).
pub fn plane_cone(
    base: &Point3<f64>,
    normal: &Vector3<f64>,
    pivot: &Point3<f64>,
    point: &Point3<f64>,
    d: f64,
) -> (Vector3<f64>, f64) {
    let w = point - pivot;
    let sd0 = normal.dot(&(pivot - base));
    (w, (d - sd0) / w.norm())
}

/// The normal of least turn from `normal` that makes the cosine `c` (in [-1, 1]) with the unit
/// direction `w`: on the great circle through `w` and `normal`, or about any axis across `w`
/// when `normal` is along it.
pub fn plane_turn(w: &Vector3<f64>, c: f64, normal: &Vector3<f64>) -> Vector3<f64> {
    let across = normal - w * normal.dot(w);
    let e = match across.try_normalize(0.0) {
        Some(e) => e,
        None => perpendicular(w).normalize(),
    };
    w * c + e * (1.0 - c * c).max(0.0).sqrt()
}

/// `dir` or its opposite, whichever is nearer `near` (the opposite only when their dot product
/// is negative): the sense a directed line keeps when turned onto an undirected one.
#[inline]
pub fn aligned(dir: &Vector3<f64>, near: &Vector3<f64>) -> Vector3<f64> {
    if dir.dot(near) < 0.0 {
        -dir
    } else {
        *dir
    }
}

/// The angle of a joint in space (`J.angle` of `revolute`, `cylindrical` or `offset_x`): from
/// the first marker's x axis `x1` to the second's `x2`, counter-clockwise about the first's z
/// axis `z1` (the value `offset_x(m1, m2)` has), in (-pi, pi]. The axes are the markers' global
/// unit axes; zero when `z1` is zero or an x axis lies along it.
#[inline]
pub fn joint_angle3(z1: Vector3<f64>, x1: Vector3<f64>, x2: Vector3<f64>) -> f64 {
    crate::num::wrap_angle(signed_angle3(&x1, &x2, &z1))
}

/// The angle of a joint in the plane (`J.angle` of `revolute` or `offset_x`): from the first
/// marker's x axis `x1` to the second's `x2`, counter-clockwise, in (-pi, pi].
#[inline]
pub fn joint_angle2(x1: Vector2<f64>, x2: Vector2<f64>) -> f64 {
    crate::num::wrap_angle(signed_angle2(&x1, &x2))
}

/// The travel of a joint in space (`J.travel` of `prismatic`, `cylindrical` or `in_line`): the
/// signed distance from the second marker's point `p2` to the first's `p1` along the second
/// marker's unit z axis `z2`, the axis the joint slides along.
#[inline]
pub fn joint_travel3(p1: Point3<f64>, p2: Point3<f64>, z2: Vector3<f64>) -> f64 {
    (p1 - p2).dot(&z2)
}

/// The travel of a joint in the plane (`J.travel` of `prismatic` or `in_line`): the signed
/// distance from the second marker's point `p2` to the first's `p1` along the second marker's
/// unit x axis `x2`, the axis the joint slides along in 2d.
#[inline]
pub fn joint_travel2(p1: Point2<f64>, p2: Point2<f64>, x2: Vector2<f64>) -> f64 {
    (p1 - p2).dot(&x2)
}

/// The advance of a screw of `pitch` (per turn) whose turn is `turn` radians, the one nearest
/// `now`: a turn and a whole number of turns more give the same screw, so the advance nearest
/// where the screw is keeps it from jumping a pitch.
pub fn helix_advance(now: f64, turn: f64, pitch: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let off = crate::num::wrap_angle(turn - tau * now / pitch);
    now + pitch / tau * off
}

/// The turn, in radians, of a screw of `pitch` (per turn) advanced by `advance`.
#[inline]
pub fn helix_turn(advance: f64, pitch: f64) -> f64 {
    std::f64::consts::TAU * advance / pitch
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A joint's angle is counter-clockwise about the first marker's z axis, in (-pi, pi]
    /// (a half turn is pi, never -pi); its travel is signed along the second marker's axis.
    #[test]
    fn joint_values_keep_their_sense_and_range() {
        use std::f64::consts::{FRAC_PI_2, PI};
        let (x, y, z) = (Vector3::x(), Vector3::y(), Vector3::z());
        assert_eq!(joint_angle3(z, x, y), FRAC_PI_2);
        assert_eq!(joint_angle3(-z, x, y), -FRAC_PI_2);
        // The component of an x axis along z1 does not count.
        assert!((joint_angle3(z, x, (y + z * 5.0).normalize()) - FRAC_PI_2).abs() < 1e-15);
        assert_eq!(joint_angle3(z, x, -x), PI);
        // A half turn whose sine is -0 is pi, not -pi.
        let (u, v) = (Vector2::new(1.0, -0.0), Vector2::new(-1.0, -0.0));
        assert_eq!(signed_angle2(&u, &v), -PI);
        assert_eq!(joint_angle2(u, v), PI);
        assert_eq!(
            joint_angle2(Vector2::x(), Vector2::new(0.0, -1.0)),
            -FRAC_PI_2
        );
        let (p1, p2) = (Point3::new(1.0, 2.0, 3.0), Point3::new(1.0, 7.0, 0.0));
        assert_eq!(joint_travel3(p1, p2, y), -5.0);
        assert_eq!(joint_travel3(p1, p2, -y), 5.0);
        let (q1, q2) = (Point2::new(4.0, 1.0), Point2::new(1.0, 1.0));
        assert_eq!(joint_travel2(q1, q2, Vector2::x()), 3.0);
    }

    /// A turn far below the parallel tolerance is still made: each of a chain's rockers that
    /// barely moves must still take its joint exactly onto its target.
    #[test]
    fn a_tiny_turn_is_made_to_rounding() {
        for angle in [1e-13, 3e-15, 1e-16] {
            let u = Vector3::new(0.3, -1.2, 4.0);
            let v = rotation_about_axis(&Vector3::new(1.0, 2.0, 0.5), angle) * u;
            let w = rotation_between3(&u, &v, &Vector3::z()) * u;
            assert!(
                (w - v).norm() <= 4.0 * f64::EPSILON * v.norm(),
                "{angle}: {w:?} vs {v:?}"
            );
        }
    }
    use std::f64::consts::PI;

    proptest::proptest! {
        /// A turn from its sine and cosine is the turn by its angle, to rounding: random
        /// vectors, and turns near none and near a half turn either way, the vectors nearly
        /// along the axis.
        #[test]
        fn a_turn_about_an_axis_needs_no_angle(
            axis in proptest::array::uniform3(-2.0f64..2.0),
            u in proptest::array::uniform3(-3.0f64..3.0),
            angle in proptest::prop_oneof![
                -PI..PI,
                -1e-9f64..1e-9,
                (PI - 1e-9)..PI,
                -PI..(-PI + 1e-9),
            ],
            along in proptest::prop_oneof![0.0f64..1.0, (1.0 - 1e-9)..1.0],
        ) {
            let axis = Vector3::from(axis);
            proptest::prop_assume!(axis.norm() > 1e-3);
            let a = axis.normalize();
            let across = Vector3::from(u) - a * a.dot(&Vector3::from(u));
            proptest::prop_assume!(across.norm() > 1e-3);
            // `u` as far along the axis as `along` says, its part across turned by `angle`.
            let u = a * along * 3.0 + across.normalize() * (1.0 - along);
            let v = rotation_about_axis(&a, angle) * u * 1.7;
            let by_angle = rotation_about_axis(&axis, signed_angle3(&u, &v, &axis));
            let by_sin_cos = turn_about_axis(&axis, &u, &v);
            let w = Vector3::new(0.4, -1.1, 2.3);
            let (p, q) = (by_angle * w, by_sin_cos * w);
            proptest::prop_assert!((p - q).norm() <= 8.0 * f64::EPSILON * w.norm(), "{p:?} vs {q:?}");
            proptest::prop_assert!(by_sin_cos.w >= 0.0);
            proptest::prop_assert!((by_sin_cos.into_inner().norm() - 1.0).abs() <= 4.0 * f64::EPSILON);
        }
    }

    proptest::proptest! {
        /// Two frames are one placement exactly when their points and axes agree: a frame
        /// and itself with its quaternion negated (one rotation) are alike; moved by a turn
        /// or a shift of rounding size they stay alike, by a thousand times the tolerance they
        /// do not; and the sum `keep` screens by differs between alike frames by no more than
        /// its bound.
        #[test]
        fn same_placement_is_one_placement_whatever_the_quaternion_sign(
            origin in proptest::array::uniform3(-5.0f64..5.0),
            axis in proptest::array::uniform3(-1.0f64..1.0),
            angle in -PI..PI,
            nudge in proptest::array::uniform3(-1.0f64..1.0),
            flip in proptest::bool::ANY,
        ) {
            let axis = Vector3::from(axis);
            proptest::prop_assume!(axis.norm() > 1e-3);
            let rotation = rotation_about_axis(&axis, angle);
            let a = Frame3::new(Point3::from(origin), rotation);
            let q = if flip { -rotation.into_inner() } else { rotation.into_inner() };
            let b = Frame3::new(a.origin, UnitQuaternion::new_unchecked(q));
            let tol = tol::SAME_ASSEMBLY_REL * (1.0 + a.origin.coords.amax());
            proptest::prop_assert!(a.same_placement(&b, tol));
            proptest::prop_assert!((a.placement_sum() - b.placement_sum()).abs() <= 1e-15 * 8.0);
            let nudge = Vector3::from(nudge);
            proptest::prop_assume!(nudge.norm() > 1e-3);
            for (size, alike) in [(1e-13, true), (1e-6, false)] {
                let turned = rotation_about_axis(&nudge, size) * rotation;
                let near = Frame3::new(a.origin + nudge * size, turned);
                proptest::prop_assert_eq!(a.same_placement(&near, tol), alike, "{}", size);
                if alike {
                    proptest::prop_assert!((a.placement_sum() - near.placement_sum()).abs() <= 7.0 * tol);
                }
                // A turn alone, and a shift alone, are each told apart.
                let shifted = Frame3::new(a.origin + nudge.normalize() * size, rotation);
                proptest::prop_assert_eq!(a.same_placement(&shifted, tol), alike);
                let turned_only = Frame3::new(a.origin, rotation_about_axis(&nudge, size) * rotation);
                proptest::prop_assert_eq!(a.same_placement(&turned_only, tol), alike);
            }
        }
    }

    /// In the plane a frame's rotation has one form: alike to rounding, told apart past it.
    #[test]
    fn same_placement_in_the_plane() {
        let a = Frame2::new(Point2::new(1.0, -2.0), 2.5);
        let tol = tol::SAME_ASSEMBLY_REL * 3.0;
        assert!(a.same_placement(&Frame2::new(a.origin, 2.5 + 1e-14), tol));
        assert!(!a.same_placement(&Frame2::new(a.origin, 2.5 + 1e-6), tol));
        assert!(!a.same_placement(&Frame2::new(a.origin + Vector2::new(0.0, 1e-6), 2.5), tol));
        assert!(!a.same_placement(&Frame2::new(a.origin, 2.5 - 2.0 * PI + 1e-6), tol));
        assert!(a.same_placement(&Frame2::new(a.origin, 2.5 - 2.0 * PI), tol));
    }

    /// The cases `signed_angle3` makes zero are the identity, and a NaN is a NaN rotation.
    #[test]
    fn a_turn_about_a_zero_axis_or_of_a_vector_along_it_is_none() {
        let (x, z) = (Vector3::x(), Vector3::z());
        assert_eq!(
            turn_about_axis(&Vector3::zeros(), &x, &z),
            UnitQuaternion::identity()
        );
        assert_eq!(turn_about_axis(&z, &z, &x), UnitQuaternion::identity());
        assert!(turn_about_axis(&z, &Vector3::new(f64::NAN, 0.0, 0.0), &x)
            .w
            .is_nan());
        assert!(turn_about_axis(&Vector3::new(0.0, f64::NAN, 1.0), &x, &x)
            .w
            .is_nan());
        // A half turn, either way: the rotation by pi.
        let half = turn_about_axis(&z, &x, &-x);
        assert!((half * x + x).norm() <= 4.0 * f64::EPSILON);
        // Huge vectors do not overflow the turn.
        let big = turn_about_axis(&z, &(x * 1e150), &(Vector3::y() * 1e150));
        assert!((big * x - Vector3::y()).norm() <= 4.0 * f64::EPSILON);
    }

    fn close3(a: &Point3<f64>, b: &Point3<f64>, eps: f64) -> bool {
        (a - b).norm() <= eps
    }

    #[test]
    fn frame2_round_trips_and_actions() {
        let mut f = Frame2::new(Point2::new(1.0, 2.0), 0.5);
        let p = Point2::new(3.0, -1.0);
        let g = f.point_to_global(&p);
        assert!((f.point_to_local(&g) - p).norm() < 1e-15);
        let v = Vector2::new(0.3, 0.7);
        assert!((f.vector_to_local(&f.vector_to_global(&v)) - v).norm() < 1e-15);
        // Rotation about a global point keeps that point fixed and preserves distances.
        let c = Point2::new(-2.0, 5.0);
        let local_c = f.point_to_local(&c);
        let q = Point2::new(7.0, 1.0);
        let before = (f.point_to_global(&q) - f.point_to_global(&p)).norm();
        f.rotate_about(&c, 1.3);
        assert!((f.point_to_global(&local_c) - c).norm() < 1e-14);
        let after = (f.point_to_global(&q) - f.point_to_global(&p)).norm();
        assert!((before - after).abs() < 1e-14);
        assert!((f.angle() - 1.8).abs() < 1e-15);
        f.translate(&Vector2::new(1.0, 1.0));
        assert!((f.point_to_global(&local_c) - (c + Vector2::new(1.0, 1.0))).norm() < 1e-14);
        assert!((f.x_axis() - Vector2::new(1.8f64.cos(), 1.8f64.sin())).norm() < 1e-15);
        assert!((f.y_axis() - Vector2::new(-(1.8f64.sin()), 1.8f64.cos())).norm() < 1e-15);
    }

    #[test]
    fn scale_moves_origin_and_dimensions_about_a_fixed_centre() {
        let mut f = Frame2::new(Point2::new(2.0, 0.0), 0.0);
        let mut dims = [1.5];
        f.scale_about(&Point2::new(0.0, 0.0), 2.0, &mut dims);
        assert_eq!(f.origin, Point2::new(4.0, 0.0));
        assert_eq!(dims, [3.0]);
        // A circle centred at the scaling centre only changes radius.
        let mut c = Frame3::new(Point3::new(1.0, 2.0, 3.0), UnitQuaternion::identity());
        let mut r = [2.0];
        c.scale_about(&Point3::new(1.0, 2.0, 3.0), 0.25, &mut r);
        assert_eq!(c.origin, Point3::new(1.0, 2.0, 3.0));
        assert_eq!(r, [0.5]);
        assert_eq!(scale_factor(2.0, 5.0), Some(2.5));
        assert_eq!(scale_factor(0.0, 5.0), None);
        assert_eq!(scale_factor(f64::NAN, 5.0), None);
        let p = scale_point3_about(
            &Point3::new(1.0, 1.0, 1.0),
            &Point3::new(0.0, 0.0, 1.0),
            3.0,
        );
        assert_eq!(p, Point3::new(3.0, 3.0, 1.0));
    }

    #[test]
    fn frame3_round_trips_and_rotation_keeps_the_axis_fixed() {
        let axis = Vector3::new(1.0, 1.0, 0.0);
        let mut f = Frame3::new(
            Point3::new(10.0, 5.0, 2.0),
            rotation_about_axis(&axis, 40f64.to_radians()),
        );
        let p = Point3::new(1.0, -2.0, 0.5);
        assert!(close3(&f.point_to_local(&f.point_to_global(&p)), &p, 1e-14));
        let v = Vector3::new(0.1, 0.2, 0.3);
        assert!((f.vector_to_local(&f.vector_to_global(&v)) - v).norm() < 1e-15);
        let c = Point3::new(1.0, 2.0, 3.0);
        let dir = Vector3::new(0.0, 0.0, 2.0);
        let on_axis = [f.point_to_local(&c), f.point_to_local(&(c + dir * 1.7))];
        f.rotate_about(&c, &dir, 0.9);
        assert!(close3(&f.point_to_global(&on_axis[0]), &c, 1e-14));
        assert!(close3(
            &f.point_to_global(&on_axis[1]),
            &(c + dir * 1.7),
            1e-14
        ));
        assert!((f.x_axis().cross(&f.y_axis()) - f.z_axis()).norm() < 1e-15);
    }

    #[test]
    fn zero_axis_rotation_is_identity_not_nan() {
        let mut f = Frame3::new(Point3::new(1.0, 2.0, 3.0), UnitQuaternion::identity());
        f.rotate_about(&Point3::origin(), &Vector3::zeros(), 1.0);
        assert_eq!(
            f,
            Frame3::new(Point3::new(1.0, 2.0, 3.0), UnitQuaternion::identity())
        );
        let q = rotation_between3(&Vector3::x(), &(Vector3::x() * 3.0), &Vector3::z());
        assert_eq!(q, UnitQuaternion::identity());
        let q = rotation_between3(&Vector3::zeros(), &Vector3::x(), &Vector3::z());
        assert_eq!(q, UnitQuaternion::identity());
        assert_eq!(
            signed_angle3(&Vector3::x(), &Vector3::y(), &Vector3::zeros()),
            0.0
        );
    }

    #[test]
    fn rotation_between_general_and_antiparallel() {
        let u = Vector3::new(1.0, 2.0, 3.0);
        let v = Vector3::new(-2.0, 0.5, 1.0);
        let q = rotation_between3(&u, &v, &Vector3::z());
        assert!(((q * u).normalize() - v.normalize()).norm() < 1e-15);
        // Anti-parallel: half turn about the fallback axis (made perpendicular to u).
        let q = rotation_between3(&Vector3::x(), &-Vector3::x(), &Vector3::new(1.0, 0.0, 1.0));
        assert!(((q * Vector3::x()) + Vector3::x()).norm() < 1e-15);
        assert!(((q * Vector3::z()) - Vector3::z()).norm() < 1e-15);
        // Unusable fallback: still a half turn, deterministic, no NaN.
        let q = rotation_between3(&Vector3::y(), &-Vector3::y(), &Vector3::y());
        assert!(((q * Vector3::y()) + Vector3::y()).norm() < 1e-15);
        assert_eq!(perpendicular(&Vector3::y()).dot(&Vector3::y()), 0.0);
        // NaN input gives NaN or identity, never a panic.
        let _ = rotation_between3(&Vector3::new(f64::NAN, 0.0, 0.0), &v, &Vector3::z());
    }

    #[test]
    fn signed_angles() {
        assert!((signed_angle2(&Vector2::x(), &Vector2::y()) - PI / 2.0).abs() < 1e-15);
        assert!((signed_angle2(&Vector2::y(), &Vector2::x()) + PI / 2.0).abs() < 1e-15);
        let a = signed_angle3(&Vector3::x(), &Vector3::y(), &Vector3::z());
        assert!((a - PI / 2.0).abs() < 1e-15);
        let a = signed_angle3(&Vector3::x(), &Vector3::y(), &-Vector3::z());
        assert!((a + PI / 2.0).abs() < 1e-15);
        // Components along the axis are ignored.
        let a = signed_angle3(
            &Vector3::new(1.0, 0.0, 5.0),
            &Vector3::new(0.0, -1.0, -3.0),
            &Vector3::z(),
        );
        assert!((a + PI / 2.0).abs() < 1e-15);
        assert_eq!(signed_angle2(&Vector2::zeros(), &Vector2::x()), 0.0);
    }

    /// Kramer's brick (paper 000, section 4.1, figure 3).
    #[test]
    fn kramer_brick() {
        let b = [
            Point3::new(0.0, 0.0, 0.0),
            Point3::new(4.0, 0.0, 0.0),
            Point3::new(0.0, 3.0, 0.0),
        ];
        let g = b;
        let mut brick = Frame3::new(
            Point3::new(10.0, 5.0, 2.0),
            rotation_about_axis(&Vector3::new(1.0, 1.0, 0.0), 40f64.to_radians()),
        );
        let d01 = (b[1] - b[0]).norm();
        let d02 = (b[2] - b[0]).norm();
        let d12 = (b[2] - b[1]).norm();
        let rigid = |f: &Frame3| {
            let p: [Point3<f64>; 3] = [
                f.point_to_global(&b[0]),
                f.point_to_global(&b[1]),
                f.point_to_global(&b[2]),
            ];
            ((p[1] - p[0]).norm() - d01).abs() < 1e-13
                && ((p[2] - p[0]).norm() - d02).abs() < 1e-13
                && ((p[2] - p[1]).norm() - d12).abs() < 1e-13
        };
        // Step 1: translate by the vector from b1 to g1.
        let t = g[0] - brick.point_to_global(&b[0]);
        brick.translate(&t);
        assert!(close3(&brick.point_to_global(&b[0]), &g[0], 1e-14));
        assert!(rigid(&brick));
        // Step 2: rotate about b1 around cp = v1 x v2, where v1 = g3 - g1 and v2 = b3' - g1, by
        // the angle between them; measured about cp, turning v2 onto v1 is a negative angle.
        let v1 = g[2] - g[0];
        let v2 = brick.point_to_global(&b[2]) - g[0];
        let cp = v1.cross(&v2);
        let angle = signed_angle3(&v2, &v1, &cp);
        assert!(angle < 0.0);
        let center = brick.point_to_global(&b[0]);
        brick.rotate_about(&center, &cp, angle);
        assert!(
            close3(&brick.point_to_global(&b[0]), &g[0], 1e-14),
            "b1 kept"
        );
        assert!(
            close3(&brick.point_to_global(&b[2]), &g[2], 1e-14),
            "b3 on g3"
        );
        assert!(rigid(&brick));
        // Step 3: rotate about the line g1-g3 to bring b2 onto g2. The circle of b2 about that
        // line has its centre at the foot of the perpendicular from b2.
        let axis = (g[2] - g[0]).normalize();
        let b2 = brick.point_to_global(&b[1]);
        let foot = g[0] + axis * axis.dot(&(b2 - g[0]));
        let angle = signed_angle3(&(b2 - foot), &(g[1] - foot), &axis);
        brick.rotate_about(&g[0], &axis, angle);
        for i in 0..3 {
            assert!(
                close3(&brick.point_to_global(&b[i]), &g[i], 1e-14),
                "b{} on g{}",
                i + 1,
                i + 1
            );
        }
        assert!(rigid(&brick));
        // The brick's frame is now the global one.
        assert!((brick.origin - Point3::origin()).norm() < 1e-14);
        assert!(brick.rotation.angle() < 1e-14);
    }

    #[test]
    fn brick_step_two_through_rotation_between() {
        let mut f = Frame3::new(
            Point3::new(10.0, 5.0, 2.0),
            rotation_about_axis(&Vector3::new(1.0, 1.0, 0.0), 40f64.to_radians()),
        );
        let b3 = Point3::new(0.0, 3.0, 0.0);
        let t = -f.origin.coords;
        f.translate(&t);
        let q = rotation_between3(&(f.point_to_global(&b3).coords), &b3.coords, &Vector3::z());
        f.rotate_about_by(&Point3::origin(), &q);
        assert!(close3(&f.point_to_global(&b3), &b3, 1e-14));
        assert!(close3(
            &f.point_to_global(&Point3::origin()),
            &Point3::origin(),
            1e-14
        ));
    }

    #[test]
    fn non_finite_input_never_panics() {
        let mut f = Frame3::identity();
        f.rotate_about(
            &Point3::new(f64::NAN, 0.0, 0.0),
            &Vector3::new(f64::INFINITY, 0.0, 0.0),
            1.0,
        );
        f.translate(&Vector3::new(f64::NAN, 0.0, 0.0));
        f.scale_about(&Point3::origin(), f64::INFINITY, &mut [1.0]);
        assert!(f.origin.x.is_nan());
        let mut g = Frame2::identity();
        g.rotate_about(&Point2::origin(), f64::NAN);
        assert!(g.angle().is_nan() || g.angle().is_finite());
        let _ = signed_angle3(
            &Vector3::x(),
            &Vector3::y(),
            &Vector3::new(f64::NAN, 0.0, 0.0),
        );
    }

    mod rotation_between2 {
        use super::super::*;

        #[test]
        fn turns_a_onto_b_without_trigonometry() {
            for (a, b) in [
                (Vector2::new(1.0, 0.0), Vector2::new(0.0, 2.0)),
                (Vector2::new(3.0, -1.0), Vector2::new(-2.0, 0.5)),
                (Vector2::new(1.0, 1.0), Vector2::new(-1.0, -1.0)),
            ] {
                let r = rotation_between2(&a, &b);
                let turned = r * a.normalize();
                assert!((turned - b.normalize()).norm() < 1e-15, "{a} {b}");
            }
            assert_eq!(
                rotation_between2(&Vector2::zeros(), &Vector2::x()),
                UnitComplex::identity()
            );
            let f = Frame2::along(Point2::new(1.0, 2.0), Vector2::new(0.0, 3.0));
            assert!((f.x_axis() - Vector2::y()).norm() < 1e-15);
        }
    }

    mod cone {
        use super::super::*;
        use crate::Contact;

        #[test]
        fn a_turn_about_an_axis_reaches_the_angle_on_both_sides() {
            // v = x turns about z; u in the x-z plane at 60 degrees from z: the reachable angles
            // with u run from 30 to 150 degrees.
            let u = Vector3::new(3f64.sqrt() / 2.0, 0.0, 0.5);
            let (v, z) = (Vector3::x(), Vector3::z());
            let i = turns_to_angle(&u, &v, &z, std::f64::consts::FRAC_PI_2);
            assert_eq!(i.contact, Contact::Crossing);
            for k in 0..2 {
                let w = i.roots.get(k).expect("root");
                assert!(u.dot(&w).abs() < 1e-15, "{w:?}");
                assert!(w.z.abs() < 1e-15 && (w.norm() - 1.0).abs() < 1e-15);
            }
            // Branch 0 is counter-clockwise about z from the nearest turn (phi0 = 0): +y side.
            assert!(i.roots.get(0).expect("root").y > 0.0);
            let gap = turns_to_angle(&u, &v, &z, 0.2);
            assert!(
                matches!(gap.contact, Contact::Disjoint { gap } if (gap - (std::f64::consts::FRAC_PI_6 - 0.2)).abs() < 1e-12)
            );
            let touch = turns_to_angle(&u, &v, &z, std::f64::consts::FRAC_PI_6);
            assert_eq!(touch.contact, Contact::Tangent);
            assert!(turns_to_angle(&u, &z, &z, 1.0).contact == Contact::ZeroRadius);
        }

        proptest::proptest! {
            /// The crossings well inside the reachable angles (taken without an angle) are
            /// the turns by `phi0 +- delta`, to rounding, on their branches: random cones, and
            /// angles near either end of the reach.
            #[test]
            fn crossings_inside_the_reach_are_the_turns_by_their_angles(
                axis in proptest::array::uniform3(-1.0f64..1.0),
                u in proptest::array::uniform3(-1.0f64..1.0),
                v in proptest::array::uniform3(-1.0f64..1.0),
                t in proptest::prop_oneof![0.0f64..1.0, 0.0f64..1e-9, (1.0 - 1e-9)..1.0],
            ) {
                let (axis, u, v) = (Vector3::from(axis), Vector3::from(u), Vector3::from(v));
                proptest::prop_assume!(axis.norm() > 1e-2 && u.norm() > 1e-2 && v.norm() > 1e-2);
                let (axis, u, v) = (axis.normalize(), u.normalize(), v.normalize());
                let along = axis * axis.dot(&v);
                let (across, side) = (v - along, axis.cross(&(v - along)));
                let (a, b) = (u.dot(&across), u.dot(&side));
                let r = a.hypot(b);
                proptest::prop_assume!(across.norm() > 1e-2 && r > 1e-2);
                let base = u.dot(&along);
                let (lo, hi) = ((base + r).clamp(-1.0, 1.0).acos(), (base - r).clamp(-1.0, 1.0).acos());
                let angle = lo + (hi - lo) * t;
                let i = turns_to_angle(&u, &v, &axis, angle);
                let delta = ((angle.cos() - base) / r).clamp(-1.0, 1.0).acos();
                let phi0 = b.atan2(a);
                if i.contact == Contact::Crossing {
                    for (k, phi) in [phi0 + delta, phi0 - delta].into_iter().enumerate() {
                        let (s, c) = phi.sin_cos();
                        let expected = along + across * c + side * s;
                        let root = i.roots.get(k).expect("a crossing has two roots");
                        // `acos` near either end of its range loses digits the sines keep.
                        let slack = 1e-12 / (1.0 - (delta / std::f64::consts::PI - 0.5).abs() * 2.0).max(1e-4);
                        proptest::prop_assert!((root - expected).norm() <= slack, "{k}: {root:?} vs {expected:?}");
                        proptest::prop_assert!((u.dot(&root) - angle.cos()).abs() <= 1e-14);
                    }
                } else {
                    proptest::prop_assert_eq!(i.contact, Contact::Tangent);
                }
            }
        }
    }
}
