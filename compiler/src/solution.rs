//! A solved configuration read by the model's names: every point, vector and dimension of every
//! geom, the frame of every body, and the value of every joint the outputs name (`q1.angle`,
//! measured on its solved markers by the runtime's `frame::joint_*`, as generated code measures
//! it), as `gcs solve --json` prints them (DESIGN.md's contract).

use crate::config::{Config, D3};
use gcs_lang::constraints::JointValue;
use gcs_lang::model::{ConstraintId, GeomId, GeomKind, Owner, Part};
use gcs_lang::Model;
use gcs_runtime::frame;
use std::collections::HashMap;
use std::fmt::Write as _;

/// A solution: global values by dotted name, in model order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Solution {
    /// Points: point geoms, members, markers, `S.start`, `S.end`, `C.center`, `L.point`.
    pub points: Vec<(String, Vec<f64>)>,
    /// Unit vectors: vector geoms, members, `L.dir`, `S.dir`, marker axes.
    pub vectors: Vec<(String, Vec<f64>)>,
    /// Dimensions: `G.radius`, `S.length`, `Q.offset`; then the joint values the outputs name
    /// (`q1.angle`, `slide.travel`), in the order first named.
    pub scalars: Vec<(String, f64)>,
    /// Body frames: origin and axes.
    pub frames: Vec<(String, Vec<f64>, Vec<Vec<f64>>)>,
    /// The index of every branch variable.
    pub branches: Vec<(String, usize)>,
    /// The branch variables whose index is not the sketch's (the plan's default), in branch
    /// order: those a solve had to change because the constraints cannot be met on the
    /// sketch's branches ([`crate::solve::solve_near_sketch`]), or, in a list of every
    /// assembly, those on which that assembly differs from the sketch's. Empty when none.
    pub branches_changed: Vec<BranchChange>,
    /// Where the sketch's assembly, followed from the model's params to those solved, ended
    /// on the way (a fold: [`crate::all::sketch_assembly`]): every param (by name) at the
    /// last point it reached. The solution is then another assembly, the one nearest the
    /// sketch in the sketch's mode. `None` where it did not end, or was not followed.
    pub sketch_assembly_ended: Option<Vec<(String, f64)>>,
    /// The value of every default: as given, or as the outer iteration converged to.
    pub defaults: Vec<(String, f64)>,
    /// The steps the outer iterations took (0 for a closed-form plan).
    pub iterations: u32,
    /// The geom grounded at its sketch, if nothing was fixed.
    pub grounded: Option<String>,
    /// The largest constraint violation, measured by [`crate::verify`].
    pub max_residual: f64,
}

/// The joint values the outputs name whose two markers are both solved (their top-level geoms in
/// `scope`): each one's name as written, its constraint and which value.
fn joints<'m>(
    model: &'m Model,
    scope: &std::collections::BTreeSet<GeomId>,
) -> Vec<(&'m str, ConstraintId, JointValue)> {
    let mut joints = model.joint_outputs();
    joints.retain(|&(_, c, _)| {
        (model.constraints[c].args.iter()).all(|&a| scope.contains(&model.top_level_of(a)))
    });
    joints
}

/// A joint constraint's two arguments (markers; for `in_line`, a point or a marker first).
fn marker_pair(model: &Model, c: ConstraintId) -> (GeomId, GeomId) {
    let args = &model.constraints[c].args;
    (args[0], args[1])
}

/// A branch variable on another index than the sketch's.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BranchChange {
    /// The branch variable's name.
    pub name: String,
    /// Its default: the sketch's index (0 where the sketch does not reach its intersection).
    pub sketch: usize,
    /// The index used.
    pub used: usize,
    /// The geometric meaning of the index used.
    pub meaning: String,
}

impl BranchChange {
    /// Every branch of `plan` whose index in `used` is not the one in `asked` (both by the
    /// plan's branch order), in branch order, against its default.
    pub fn of(plan: &crate::plan::Plan, asked: &[usize], used: &[usize]) -> Vec<BranchChange> {
        (plan.branches.iter().zip(asked).zip(used))
            .filter(|((_, a), u)| a != u)
            .map(|((b, _), &i)| BranchChange {
                name: b.name.clone(),
                sketch: b.default,
                used: i,
                meaning: b.meanings.get(i).cloned().unwrap_or_default(),
            })
            .collect()
    }
}

impl Solution {
    /// Reads every geom of the model from a configuration.
    pub fn read(
        model: &Model,
        cfg: &Config,
        scope: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
    ) -> Solution {
        let mut s = Solution::default();
        for (id, g) in model.geoms.iter() {
            if !scope.contains(&model.top_level_of(id)) {
                continue;
            }
            let v2 = |p: nalgebra::Point2<f64>| vec![p.x, p.y];
            match (g.kind, g.owner) {
                (GeomKind::Point | GeomKind::Marker, _) => {
                    s.points.push((g.name.clone(), v2(cfg.point(model, id))))
                }
                (GeomKind::Vector, _) => {
                    let d = cfg.dir(model, id);
                    s.vectors.push((g.name.clone(), vec![d.x, d.y]));
                }
                _ => {}
            }
            if let Owner::Part(owner, Part::BasePoint) = g.owner {
                // `L.point` reads the solved line, not a frame origin.
                if let Some(last) = s.points.last_mut() {
                    let p = cfg.line_point(owner);
                    last.1 = vec![p.x, p.y];
                }
            }
            match g.kind {
                GeomKind::Circle => s.scalars.push((format!("{}.radius", g.name), cfg.dim(id))),
                GeomKind::Segment => s.scalars.push((format!("{}.length", g.name), cfg.dim(id))),
                GeomKind::Body => {
                    if let Some(f) = cfg.frames.get(&id) {
                        let (x, y) = (f.x_axis(), f.y_axis());
                        s.frames.push((
                            g.name.clone(),
                            vec![f.origin.x, f.origin.y],
                            vec![vec![x.x, x.y], vec![y.x, y.y]],
                        ));
                    }
                }
                _ => {}
            }
        }
        for (name, c, value) in joints(model, scope) {
            let (m1, m2) = marker_pair(model, c);
            let x = |m: GeomId| model.part(m, Part::AxisX).map(|a| cfg.dir(model, a));
            let v = match value {
                JointValue::Angle => match (x(m1), x(m2)) {
                    (Some(x1), Some(x2)) => frame::joint_angle2(x1, x2),
                    _ => f64::NAN,
                },
                JointValue::Travel => x(m2).map_or(f64::NAN, |x2| {
                    frame::joint_travel2(cfg.point(model, m1), cfg.point(model, m2), x2)
                }),
            };
            s.scalars.push((name.to_string(), v));
        }
        s
    }

    /// The sketch itself read as a solution (in the model's space), with `params`; `None`
    /// when the sketch is unusable.
    pub fn of_sketch(
        model: &Model,
        params: &[f64],
        scope: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
    ) -> Option<Solution> {
        match model.space {
            gcs_lang::model::Space::D2 => Config::from_sketch(model, params)
                .ok()
                .map(|c| Solution::read(model, &c, scope)),
            gcs_lang::model::Space::D3 => Config::<D3>::from_sketch(model, params)
                .ok()
                .map(|c| Solution::read_space(model, &c, scope)),
        }
    }

    /// Reads every geom of a 3d model from its configuration: as [`Solution::read`], with
    /// three coordinates, a circle's and plane's normal, a plane's signed offset, and body
    /// frames with their three axes.
    pub fn read_space(
        model: &Model,
        cfg: &Config<D3>,
        scope: &std::collections::BTreeSet<gcs_lang::model::GeomId>,
    ) -> Solution {
        let mut s = Solution::default();
        let v3 = |v: nalgebra::Vector3<f64>| vec![v.x, v.y, v.z];
        for (id, g) in model.geoms.iter() {
            if !scope.contains(&model.top_level_of(id)) {
                continue;
            }
            match g.kind {
                GeomKind::Point | GeomKind::Marker => {
                    let p = match g.owner {
                        // `L.point` reads the solved line, not a frame origin.
                        Owner::Part(owner, Part::BasePoint) => cfg.line_point(owner),
                        _ => cfg.point(model, id),
                    };
                    s.points.push((g.name.clone(), v3(p.coords)));
                }
                GeomKind::Vector => s.vectors.push((g.name.clone(), v3(cfg.dir(model, id)))),
                _ => {}
            }
            match g.kind {
                GeomKind::Circle => s.scalars.push((format!("{}.radius", g.name), cfg.dim(id))),
                GeomKind::Segment => s.scalars.push((format!("{}.length", g.name), cfg.dim(id))),
                GeomKind::Plane => s
                    .scalars
                    .push((format!("{}.offset", g.name), cfg.plane_offset(id))),
                GeomKind::Body => {
                    if let Some(f) = cfg.frames.get(&id) {
                        s.frames.push((
                            g.name.clone(),
                            v3(f.origin.coords),
                            vec![v3(f.x_axis()), v3(f.y_axis()), v3(f.z_axis())],
                        ));
                    }
                }
                _ => {}
            }
        }
        for (name, c, value) in joints(model, scope) {
            let (m1, m2) = marker_pair(model, c);
            let axis = |m: GeomId, p: Part| model.part(m, p).map(|a| cfg.dir(model, a));
            let v = match value {
                JointValue::Angle => {
                    match (
                        axis(m1, Part::AxisZ),
                        axis(m1, Part::AxisX),
                        axis(m2, Part::AxisX),
                    ) {
                        (Some(z1), Some(x1), Some(x2)) => frame::joint_angle3(z1, x1, x2),
                        _ => f64::NAN,
                    }
                }
                JointValue::Travel => axis(m2, Part::AxisZ).map_or(f64::NAN, |z2| {
                    frame::joint_travel3(cfg.point(model, m1), cfg.point(model, m2), z2)
                }),
            };
            s.scalars.push((name.to_string(), v));
        }
        s
    }

    /// The solution's values indexed by name, for looking them up: built in one pass, so that
    /// reading every constraint's arguments (as [`crate::verify`] does) stays linear.
    pub fn by_name(&self) -> ByName<'_> {
        fn index<'a, T>(items: impl Iterator<Item = (&'a String, T)>) -> HashMap<&'a str, T> {
            let mut map = HashMap::new();
            for (name, value) in items {
                // Of two values with one name, the first, as a scan would find.
                map.entry(name.as_str()).or_insert(value);
            }
            map
        }
        ByName {
            points: index(self.points.iter().map(|(n, v)| (n, v.as_slice()))),
            vectors: index(self.vectors.iter().map(|(n, v)| (n, v.as_slice()))),
            scalars: index(self.scalars.iter().map(|(n, v)| (n, *v))),
        }
    }

    /// The JSON object of DESIGN.md, with numbers in shortest round-trip form.
    pub fn to_json(&self) -> String {
        let num = |x: f64| {
            if x.is_finite() {
                format!("{x:?}")
            } else {
                "null".to_string()
            }
        };
        let arr = |v: &[f64]| {
            format!(
                "[{}]",
                v.iter().map(|x| num(*x)).collect::<Vec<_>>().join(", ")
            )
        };
        let key = |k: &str| format!("\"{}\"", k.replace('\\', "\\\\").replace('"', "\\\""));
        let mut o = String::from("{\n");
        let section = |o: &mut String, name: &str, items: Vec<String>, last: bool| {
            let _ = write!(o, "  \"{name}\": {{");
            if items.is_empty() {
                o.push('}');
            } else {
                o.push('\n');
                o.push_str(&items.join(",\n"));
                o.push_str("\n  }");
            }
            o.push_str(if last { "\n" } else { ",\n" });
        };
        section(
            &mut o,
            "points",
            self.points
                .iter()
                .map(|(k, v)| format!("    {}: {}", key(k), arr(v)))
                .collect(),
            false,
        );
        section(
            &mut o,
            "vectors",
            self.vectors
                .iter()
                .map(|(k, v)| format!("    {}: {}", key(k), arr(v)))
                .collect(),
            false,
        );
        section(
            &mut o,
            "scalars",
            self.scalars
                .iter()
                .map(|(k, v)| format!("    {}: {}", key(k), num(*v)))
                .collect(),
            false,
        );
        section(
            &mut o,
            "frames",
            self.frames
                .iter()
                .map(|(k, origin, axes)| {
                    let axes = axes.iter().map(|a| arr(a)).collect::<Vec<_>>().join(", ");
                    format!(
                        "    {}: {{\"origin\": {}, \"axes\": [{}]}}",
                        key(k),
                        arr(origin),
                        axes
                    )
                })
                .collect(),
            false,
        );
        section(
            &mut o,
            "branches",
            self.branches
                .iter()
                .map(|(k, v)| format!("    {}: {v}", key(k)))
                .collect(),
            false,
        );
        if self.branches_changed.is_empty() {
            o.push_str("  \"branches_changed\": [],\n");
        } else {
            let items: Vec<String> = (self.branches_changed.iter())
                .map(|c| {
                    format!(
                        "    {{\"name\": {}, \"sketch\": {}, \"used\": {}, \"meaning\": {}}}",
                        key(&c.name),
                        c.sketch,
                        c.used,
                        key(&c.meaning)
                    )
                })
                .collect();
            let _ = writeln!(o, "  \"branches_changed\": [\n{}\n  ],", items.join(",\n"));
        }
        match &self.sketch_assembly_ended {
            None => o.push_str("  \"sketch_assembly_ended\": null,\n"),
            Some(at) => {
                let items: Vec<String> = (at.iter())
                    .map(|(k, v)| format!("{}: {}", key(k), num(*v)))
                    .collect();
                let _ = writeln!(o, "  \"sketch_assembly_ended\": {{{}}},", items.join(", "));
            }
        }
        section(
            &mut o,
            "defaults",
            self.defaults
                .iter()
                .map(|(k, v)| format!("    {}: {}", key(k), num(*v)))
                .collect(),
            false,
        );
        let _ = writeln!(o, "  \"iterations\": {},", self.iterations);
        let _ = writeln!(
            o,
            "  \"grounded\": {},",
            self.grounded.as_deref().map_or("null".to_string(), key)
        );
        let _ = writeln!(o, "  \"max_residual\": {}", num(self.max_residual));
        o.push('}');
        o
    }
}

/// A [`Solution`]'s points, vectors and scalars by dotted name ([`Solution::by_name`]).
#[derive(Clone, Debug)]
pub struct ByName<'a> {
    points: HashMap<&'a str, &'a [f64]>,
    vectors: HashMap<&'a str, &'a [f64]>,
    scalars: HashMap<&'a str, f64>,
}

impl<'a> ByName<'a> {
    /// The point called `name`.
    pub fn point(&self, name: &str) -> Option<&'a [f64]> {
        self.points.get(name).copied()
    }

    /// The vector called `name`.
    pub fn vector(&self, name: &str) -> Option<&'a [f64]> {
        self.vectors.get(name).copied()
    }

    /// The scalar called `name`.
    pub fn scalar(&self, name: &str) -> Option<f64> {
        self.scalars.get(name).copied()
    }
}
