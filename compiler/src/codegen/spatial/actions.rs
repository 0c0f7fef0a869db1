//! The actions of space: translations and rotations of `Frame3`s, computed here for frames
//! known to the bit (`FrameFacts::literal3`) as the interpreter computes them.

use crate::codegen::facts::Value;
use crate::codegen::sketch3::rotation3;
use crate::codegen::solve::Solve;
use crate::codegen::writer::Writer;
use crate::plan::{Reg, RotationAxis};
use gcs_lang::model::GeomId;

impl Solve<'_> {
    /// Translates `geoms` so that point `from` lands on `to`: computed here for frames known
    /// to the bit when both points are literals, as the interpreter computes it.
    pub(in crate::codegen) fn translate3(
        &mut self,
        w: &mut Writer,
        geoms: &[GeomId],
        from: Reg,
        to: Reg,
    ) {
        let (fv, tv) = (self.facts.value(from).clone(), self.facts.value(to).clone());
        if fv.same(&tv, self.cx) {
            // From a point onto itself: nothing moves.
            return;
        }
        let shift = match (&fv, &tv) {
            (Value::Point3(a), Value::Point3(b)) => {
                Some(nalgebra::Point3::from(*b) - nalgebra::Point3::from(*a))
            }
            _ => None,
        };
        let mut local = None;
        for &g in geoms {
            if let (Some(d), Some(mut f)) = (shift, self.literal_frame3(g)) {
                f.translate(&d);
                self.facts.frames.entry(g).or_default().literal3 = Some(f);
                continue;
            }
            self.materialize(g);
            let shift = match &local {
                Some(name) => name,
                None => {
                    let name = self.names.fresh("shift");
                    let code = format!("{} - {}", self.code(&tv), self.code(&fv));
                    self.let_read(w, &name, &code);
                    local.insert(name)
                }
            };
            let frame = self.frame_local(g);
            w.line(&format!("{frame}.translate(&{shift});"));
            self.frame_writes.insert(g);
        }
    }

    /// Rotates `geoms` about `pivot` by the rotation about `axis` that takes `from` to `to`
    /// (points about the pivot, or directions).
    pub(in crate::codegen) fn rotate3(
        &mut self,
        w: &mut Writer,
        geoms: &[GeomId],
        (pivot, axis): (Reg, RotationAxis),
        (from, to): (Reg, Reg),
        points: bool,
    ) {
        let c = self.r(pivot);
        let (f, t) = if points {
            (
                format!("({} - {c})", self.r(from)),
                format!("({} - {c})", self.r(to)),
            )
        } else {
            (self.r(from), self.r(to))
        };
        let code = match axis {
            RotationAxis::Shortest => {
                format!("frame::rotation_between3(&{f}, &{t}, &frame::perpendicular(&{f}))")
            }
            RotationAxis::Along(a) => {
                let a = self.r(a);
                format!("frame::turn_about_axis(&{a}, &{f}, &{t})")
            }
            RotationAxis::Normal => {
                panic!("bug in gcs: a rotation about the plane's normal reached the spatial code generator")
            }
        };
        // With every operand a literal, the rotation is computed here, as the interpreter
        // computes it, and so are the frames known to the bit.
        if let Some(q) = self.literal_rotation3((pivot, axis), (from, to), points) {
            let c = match self.facts.value(pivot) {
                Value::Point3(c) => nalgebra::Point3::from(*c),
                _ => unreachable!("a literal rotation has a literal pivot"),
            };
            let mut turn = None;
            for &g in geoms {
                if let Some(mut f) = self.literal_frame3(g) {
                    f.rotate_about_by(&c, &q);
                    self.facts.frames.entry(g).or_default().literal3 = Some(f);
                    continue;
                }
                let turn = match &turn {
                    Some(name) => name,
                    None => {
                        let name = self.names.fresh("turn");
                        self.let_read(w, &name, &rotation3(&q));
                        turn.insert(name)
                    }
                };
                let frame = self.frame_local(g);
                w.line(&format!(
                    "{frame}.rotate_about_by(&{c}, &{turn});",
                    c = self.r(pivot)
                ));
                self.frame_writes.insert(g);
            }
            return;
        }
        self.turn_frames(w, geoms, pivot, &code);
    }

    /// Rotates `geoms` by `angle` about the line through `pivot` along the unit `axis`.
    pub(in crate::codegen) fn rotate_by(
        &mut self,
        w: &mut Writer,
        geoms: &[GeomId],
        (pivot, axis): (Reg, Reg),
        angle: Reg,
    ) {
        let code = format!(
            "frame::rotation_about_axis(&{}, {})",
            self.r(axis),
            self.r(angle)
        );
        self.turn_frames(w, geoms, pivot, &code);
    }

    /// Turns the frames of `geoms` about `pivot` by the rotation `code` computes, in a local.
    fn turn_frames(&mut self, w: &mut Writer, geoms: &[GeomId], pivot: Reg, code: &str) {
        let turn = self.names.fresh("turn");
        self.let_read(w, &turn, code);
        let c = self.r(pivot);
        for &g in geoms {
            self.materialize(g);
            let frame = self.frame_local(g);
            w.line(&format!("{frame}.rotate_about_by(&{c}, &{turn});"));
            self.frame_writes.insert(g);
        }
    }

    /// The rotation of [`Solve::rotate3`] when its pivot, points or directions and axis are
    /// all literals: the interpreter's `rotation`, run here.
    fn literal_rotation3(
        &self,
        (pivot, axis): (Reg, RotationAxis),
        (from, to): (Reg, Reg),
        points: bool,
    ) -> Option<nalgebra::UnitQuaternion<f64>> {
        use nalgebra::Vector3 as V;
        let vector = |r: Reg| match self.facts.value(r) {
            Value::Point3(p) | Value::Vector3(p) => Some(V::from(*p)),
            _ => None,
        };
        let c = match self.facts.value(pivot) {
            Value::Point3(c) => V::from(*c),
            _ => return None,
        };
        let (mut f, mut t) = (vector(from)?, vector(to)?);
        if points {
            (f, t) = (f - c, t - c);
        }
        use gcs_runtime::frame as rt;
        Some(match axis {
            RotationAxis::Shortest => rt::rotation_between3(&f, &t, &rt::perpendicular(&f)),
            RotationAxis::Along(a) => {
                let a = vector(a)?;
                rt::turn_about_axis(&a, &f, &t)
            }
            RotationAxis::Normal => return None,
        })
    }
}
