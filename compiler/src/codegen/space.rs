//! What the plane's generated code and space's differ in, said once per space (as
//! `interp::Space` and `config::Frames` do for the interpreter): the runtime's types and
//! imports, the sketch's readers, and the steps that write values, move frames and check.
//! The rest of codegen asks the model's [`Space`] and never which space it is.

use super::api::Ty as ApiTy;
use super::context::Context;
use super::facts::FrameFacts;
use super::sketch::ParamLocal;
use super::solve::Solve;
use super::writer::Writer;
use crate::config::{Config, SketchFault, D3};
use crate::plan::{Op, Reg, Residual, RotationAxis};
use gcs_lang::expr::ExprId;
use gcs_lang::model::GeomId;
use gcs_lang::Model;

/// The plane's generated code (`Frame2`, `locus2d`; `sketch.rs`, `steps.rs`).
pub(super) struct Planar;

/// Space's generated code (`Frame3`, `locus3d`; `sketch3.rs`, `spatial.rs`).
pub(super) struct Spatial;

/// The space of `model`'s generated code.
pub(super) fn of(model: &Model) -> &'static dyn Space {
    match model.space {
        gcs_lang::model::Space::D2 => &Planar,
        gcs_lang::model::Space::D3 => &Spatial,
    }
}

impl Context<'_> {
    /// The sketches that some params make unusable, in the model's order (the order the
    /// interpreter reads them in): each geom with the code of the test that its sketch is
    /// unusable, and how. A constant sketch was checked when the model was; a coordinate that
    /// is a param (or its negation) is finite, params being checked on entry.
    pub(super) fn sketch_checks(&self) -> Vec<(GeomId, String, SketchFault)> {
        self.space.sketch_checks(self)
    }

    /// The local coordinates params set among the members of top-level geom `g`: a member's,
    /// and after a marker's its x axis's.
    pub(super) fn param_locals(&self, g: GeomId) -> Vec<ParamLocal> {
        self.space.param_locals(self, g)
    }

    /// The sketch value of a segment's length or a circle's radius, as code.
    pub(super) fn sketch_dim(&self, g: GeomId) -> Option<String> {
        self.space.sketch_dim(self, g)
    }

    /// The declared value of a segment's length or a circle's radius where the sketch puts it:
    /// a literal when the sketch is constant.
    pub(super) fn sketch_dim_declared(&self, g: GeomId) -> String {
        self.space.sketch_dim_declared(self, g)
    }

    /// The constructor of top-level geom `g`'s frame where the sketch puts it, and what is
    /// known of the frame then: the same construction as the interpreter's configuration, so
    /// that both agree to the last bits.
    pub(super) fn sketch_frame(&self, g: GeomId) -> (String, FrameFacts) {
        self.space.sketch_frame(self, g)
    }

    /// The code of a point of the sketch at coordinates `c` (a missing one as the
    /// interpreter's configuration reads it).
    pub(super) fn point_code(&self, c: &[ExprId]) -> String {
        self.space.point_code(self, c)
    }
}

/// What a space's generated code is written with.
pub(super) trait Space: Sync {
    /// The Rust type of a value the API exposes.
    fn rust(&self, ty: ApiTy) -> &'static str;
    /// The Rust types of a line and a circle.
    fn line_circle(&self) -> (&'static str, &'static str);
    /// A value of `ty` for an accessor past the end of its table.
    fn zero(&self, ty: ApiTy) -> &'static str;
    /// The imports of the generated module after the shared ones.
    fn imports(&self) -> &'static [&'static str];
    /// The coordinates of a point (`x`, `y`, and `z` in space).
    fn coordinates(&self) -> &'static [&'static str];
    /// How the doc of a body's accessor describes its frame.
    fn body_frame_doc(&self, name: &str) -> String;
    /// Whether every reported geom is read from its frame, even one whose constant sketch
    /// nothing moves (in space every reported geom has its frame in the solution).
    fn reports_every_frame(&self) -> bool;

    /// The sketch evaluated once, for the values of constant sketches where the space's
    /// writers read them (`Context::sketch3`: space's; the plane's compute their own).
    fn sketch_config(&self, model: &Model) -> Option<Config<D3>>;
    /// See [`Context::sketch_frame`].
    fn sketch_frame(&self, cx: &Context<'_>, g: GeomId) -> (String, FrameFacts);
    /// See [`Context::sketch_checks`].
    fn sketch_checks(&self, cx: &Context<'_>) -> Vec<(GeomId, String, SketchFault)>;
    /// Whether a member's local coordinates depend on params (then the solution stores them).
    fn local_is_param(&self, cx: &Context<'_>, g: GeomId) -> bool;
    /// See [`Context::param_locals`].
    fn param_locals(&self, cx: &Context<'_>, g: GeomId) -> Vec<ParamLocal>;
    /// See [`Context::sketch_dim`].
    fn sketch_dim(&self, cx: &Context<'_>, g: GeomId) -> Option<String>;
    /// See [`Context::sketch_dim_declared`].
    fn sketch_dim_declared(&self, cx: &Context<'_>, g: GeomId) -> String;
    /// See [`Context::point_code`].
    fn point_code(&self, cx: &Context<'_>, c: &[ExprId]) -> String;
    /// The global position of member `f` of the frame in `frame` (at `origin`), from its
    /// constant local coordinates.
    fn member_point(&self, cx: &Context<'_>, frame: &str, origin: &str, f: GeomId) -> String;
    /// The global direction of member `f` of the frame in `frame`, from its constant local
    /// coordinates.
    fn member_dir(&self, cx: &Context<'_>, frame: &str, f: GeomId) -> String;

    /// Writes the value of register `r`, which step `i` computes with `op` (not a scalar's).
    fn value(&self, s: &mut Solve<'_>, w: &mut Writer, i: usize, r: Reg, op: &Op);
    /// Translates `geoms` so that point `from` lands on `to`.
    fn translate(&self, s: &mut Solve<'_>, w: &mut Writer, geoms: &[GeomId], from: Reg, to: Reg);
    /// Rotates `geoms` about `pivot` around `axis` so that `from` (a point, or a direction
    /// when not `points`) turns onto `to`.
    fn rotate(
        &self,
        s: &mut Solve<'_>,
        w: &mut Writer,
        geoms: &[GeomId],
        pivot_axis: (Reg, RotationAxis),
        from_to: (Reg, Reg),
        points: bool,
    );
    /// The code of a check's residual.
    fn residual_code(&self, s: &Solve<'_>, residual: &Residual) -> String;
}

impl Space for Planar {
    fn rust(&self, ty: ApiTy) -> &'static str {
        match ty {
            ApiTy::Frame => "Frame2",
            ApiTy::Scalar => "f64",
            ApiTy::Point => "Point2<f64>",
            ApiTy::Vector => "Vector2<f64>",
        }
    }
    fn line_circle(&self) -> (&'static str, &'static str) {
        ("Line", "Circle")
    }
    fn zero(&self, ty: ApiTy) -> &'static str {
        match ty {
            ApiTy::Scalar => "0.0",
            ApiTy::Frame => "Frame2::default()",
            ApiTy::Point => "Point2::origin()",
            ApiTy::Vector => "Vector2::zeros()",
        }
    }
    fn imports(&self) -> &'static [&'static str] {
        &[
            "use gcs_runtime::frame::{direction_at, rotation_between2, rotation_between_units, rotation_from_x, rotation_from_x_unit, rotation_on_circle, rotation_on_circle_from, DirectionsNear, Frame2};",
            "use gcs_runtime::intersect2d;",
            "use gcs_runtime::locus2d::{self, Circle, Conic, Line, Sense};",
            "use gcs_runtime::nalgebra::{Point2, UnitComplex, Vector2};",
        ]
    }
    fn coordinates(&self) -> &'static [&'static str] {
        &["x", "y"]
    }
    fn body_frame_doc(&self, name: &str) -> String {
        format!("The frame of body `{name}`.")
    }
    fn reports_every_frame(&self) -> bool {
        false
    }

    fn sketch_config(&self, _: &Model) -> Option<Config<D3>> {
        None
    }
    fn sketch_frame(&self, cx: &Context<'_>, g: GeomId) -> (String, FrameFacts) {
        cx.sketch_frame2(g)
    }
    fn sketch_checks(&self, cx: &Context<'_>) -> Vec<(GeomId, String, SketchFault)> {
        cx.sketch_checks2()
    }
    fn local_is_param(&self, cx: &Context<'_>, g: GeomId) -> bool {
        cx.local_is_param2(g)
    }
    fn param_locals(&self, cx: &Context<'_>, g: GeomId) -> Vec<ParamLocal> {
        cx.param_locals2(g)
    }
    fn sketch_dim(&self, cx: &Context<'_>, g: GeomId) -> Option<String> {
        cx.sketch_dim2(g)
    }
    fn sketch_dim_declared(&self, cx: &Context<'_>, g: GeomId) -> String {
        cx.sketch_dim_declared2(g)
    }
    fn point_code(&self, cx: &Context<'_>, c: &[ExprId]) -> String {
        cx.point_lit(c)
    }
    fn member_point(&self, cx: &Context<'_>, frame: &str, origin: &str, f: GeomId) -> String {
        let origin = super::facts::Value::Expr(origin.to_string());
        let frame = || frame.to_string();
        super::facts::point_in(frame, &origin, cx.literal_coords(f, true)).code()
    }
    fn member_dir(&self, cx: &Context<'_>, frame: &str, f: GeomId) -> String {
        super::facts::direction_in(frame, cx.literal_coords(f, false))
    }

    fn value(&self, s: &mut Solve<'_>, w: &mut Writer, i: usize, r: Reg, op: &Op) {
        s.value2(w, i, r, op)
    }
    fn translate(&self, s: &mut Solve<'_>, w: &mut Writer, geoms: &[GeomId], from: Reg, to: Reg) {
        s.translate(w, geoms, from, to)
    }
    fn rotate(
        &self,
        s: &mut Solve<'_>,
        w: &mut Writer,
        geoms: &[GeomId],
        (pivot, axis): (Reg, RotationAxis),
        (from, to): (Reg, Reg),
        points: bool,
    ) {
        if axis != RotationAxis::Normal {
            panic!("bug in gcs: a rotation about {axis:?} reached the planar code generator");
        }
        match points {
            true => s.rotate_point(w, geoms, pivot, from, to),
            false => s.rotate_dir(w, geoms, pivot, from, to),
        }
    }
    fn residual_code(&self, s: &Solve<'_>, residual: &Residual) -> String {
        s.residual_code(residual)
    }
}

impl Space for Spatial {
    fn rust(&self, ty: ApiTy) -> &'static str {
        match ty {
            ApiTy::Frame => "Frame3",
            ApiTy::Scalar => "f64",
            ApiTy::Point => "Point3<f64>",
            ApiTy::Vector => "Vector3<f64>",
        }
    }
    fn line_circle(&self) -> (&'static str, &'static str) {
        ("Line3", "Circle3")
    }
    fn zero(&self, ty: ApiTy) -> &'static str {
        match ty {
            ApiTy::Scalar => "0.0",
            ApiTy::Frame => "Frame3::default()",
            ApiTy::Point => "Point3::origin()",
            ApiTy::Vector => "Vector3::zeros()",
        }
    }
    fn imports(&self) -> &'static [&'static str] {
        // Space's types and functions; nothing of the plane's.
        &[
            "use gcs_runtime::fragment3;",
            "use gcs_runtime::frame::{self, Frame3};",
            "use gcs_runtime::intersect3d;",
            "use gcs_runtime::locus3d::{self, Circle3, Cylinder, Line3, Locus3, Plane, Shift, Sphere, Surface, Torus};",
            "use gcs_runtime::nalgebra::{Point3, Quaternion, UnitQuaternion, Vector3};",
        ]
    }
    fn coordinates(&self) -> &'static [&'static str] {
        &["x", "y", "z"]
    }
    fn body_frame_doc(&self, name: &str) -> String {
        format!("The frame of body `{name}`: its origin and its axes.")
    }
    fn reports_every_frame(&self) -> bool {
        true
    }

    fn sketch_config(&self, model: &Model) -> Option<Config<D3>> {
        Config::from_sketch(model, &model.default_params()).ok()
    }
    fn sketch_frame(&self, cx: &Context<'_>, g: GeomId) -> (String, FrameFacts) {
        cx.sketch_frame3(g)
    }
    fn sketch_checks(&self, cx: &Context<'_>) -> Vec<(GeomId, String, SketchFault)> {
        cx.sketch_checks3()
    }
    fn local_is_param(&self, cx: &Context<'_>, g: GeomId) -> bool {
        cx.local_is_param3(g)
    }
    fn param_locals(&self, cx: &Context<'_>, g: GeomId) -> Vec<ParamLocal> {
        cx.param_locals3(g)
    }
    fn sketch_dim(&self, cx: &Context<'_>, g: GeomId) -> Option<String> {
        cx.sketch_dim3(g)
    }
    fn sketch_dim_declared(&self, cx: &Context<'_>, g: GeomId) -> String {
        cx.sketch_dim3(g).unwrap_or_else(|| "0.0".into())
    }
    fn point_code(&self, cx: &Context<'_>, c: &[ExprId]) -> String {
        cx.point_lit3(c)
    }
    fn member_point(&self, cx: &Context<'_>, frame: &str, _: &str, f: GeomId) -> String {
        format!("{frame}.point_to_global(&{})", cx.local_point3(f))
    }
    fn member_dir(&self, cx: &Context<'_>, frame: &str, f: GeomId) -> String {
        format!("{frame}.vector_to_global(&{})", cx.local_dir3(f))
    }

    fn value(&self, s: &mut Solve<'_>, w: &mut Writer, i: usize, r: Reg, op: &Op) {
        s.value3(w, i, r, op)
    }
    fn translate(&self, s: &mut Solve<'_>, w: &mut Writer, geoms: &[GeomId], from: Reg, to: Reg) {
        s.translate3(w, geoms, from, to)
    }
    fn rotate(
        &self,
        s: &mut Solve<'_>,
        w: &mut Writer,
        geoms: &[GeomId],
        pivot_axis: (Reg, RotationAxis),
        from_to: (Reg, Reg),
        points: bool,
    ) {
        s.rotate3(w, geoms, pivot_axis, from_to, points)
    }
    fn residual_code(&self, s: &Solve<'_>, residual: &Residual) -> String {
        s.residual_code3(residual)
    }
}
