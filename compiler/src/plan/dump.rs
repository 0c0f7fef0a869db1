//! The plan's stable text dump (`gcs plan`): one step a line, with the model's names.

use super::{expr_text, fmt_f64, Op, Plan, PlanarOp, Reg, Residual, RotationAxis, SpatialOp};
use gcs_lang::model::{ConstraintId, GeomId};
use gcs_lang::Model;
use std::fmt::Write as _;

impl Plan {
    /// The stable text dump of the plan, one step a line, with names from the model.
    pub fn dump(&self, model: &Model) -> String {
        let name = |g: &GeomId| model.geoms[*g].name.clone();
        let names = |gs: &[GeomId]| gs.iter().map(name).collect::<Vec<_>>().join(" ");
        let cname = |c: &ConstraintId| model.constraints[*c].name.clone();
        let mut out = String::new();
        if let Some(g) = self.grounded {
            let _ = writeln!(out, "ground {} at its sketch", name(&g));
        }
        if let Some((a, b)) = self.grounded_direction {
            let _ = writeln!(
                out,
                "hold the sketch direction from {} to {}",
                name(&a),
                name(&b)
            );
        }
        if let Some(c) = self.grounded_plane {
            let _ = writeln!(
                out,
                "hold the sketch plane of that direction and {}",
                name(&c)
            );
        }
        for b in &self.branches {
            let _ = writeln!(
                out,
                "branch {} ({} roots, default {}): {}",
                b.name,
                b.count,
                b.default,
                b.meanings.join("; ")
            );
        }
        for d in &self.defaults {
            let _ = writeln!(
                out,
                "default {} (sketch {}): {}",
                d.name,
                fmt_f64(d.sketch),
                d.meaning
            );
        }
        for it in &self.iterations {
            let _ = writeln!(
                out,
                "iterate steps {}..{} over {}{}",
                it.start,
                it.end,
                self.varied(it).join(" "),
                match it.mode {
                    Some(mode) => format!(", sketch's mode {mode:?}"),
                    None => String::new(),
                }
            );
        }
        for s in &self.steps {
            let lhs = match s.out {
                Some((r, ty)) => format!("r{} : {:?} = ", r.0, ty),
                None => String::new(),
            };
            let r = |r: &Reg| format!("r{}", r.0);
            let op = match &s.op {
                Op::Expr(e) => format!("expr {}", expr_text(model, *e)),
                Op::Size { expr, constraint } => format!(
                    "size {} of {}",
                    expr_text(model, *expr),
                    model.constraints[*constraint].name
                ),
                Op::Const(c) => format!("const {}", fmt_f64(*c)),
                Op::Neg(x) => format!("neg {}", r(x)),
                Op::DimOf(g) => format!("dim_of {}", name(g)),
                Op::Sum(terms) => format!(
                    "sum {}",
                    terms
                        .iter()
                        .map(|(s, x)| format!("{}*{}", fmt_f64(*s), r(x)))
                        .collect::<Vec<_>>()
                        .join(" ")
                ),
                Op::Unknown { of, index } => format!("unknown {} of {}", index, r(of)),
                Op::Along { from, dir, to } => format!("along {} {} {}", r(from), r(dir), r(to)),
                Op::DirectionTo { from, to } => format!("direction_to {} {}", r(from), r(to)),
                Op::PointOf(g) => format!("point_of {}", name(g)),
                Op::DirOf(g) => format!("dir_of {}", name(g)),
                Op::Midpoint { a, b } => format!("midpoint {} {}", r(a), r(b)),
                Op::Reflect { point, through } => {
                    format!("reflect {} through {}", r(point), r(through))
                }
                Op::LocusPoint { locus, at } => format!("locus_point {} at {}", r(locus), r(at)),
                Op::Implicit { locus, point } => format!("implicit {} at {}", r(locus), r(point)),
                Op::LocusParam { locus, point } => {
                    format!("locus_param {} of {}", r(locus), r(point))
                }
                Op::Line { point, dir, offset } => match offset {
                    Some(o) => format!("line {} {} offset {}", r(point), r(dir), r(o)),
                    None => format!("line {} {}", r(point), r(dir)),
                },
                Op::ParallelLine { line, through } => {
                    format!("parallel_line {} through {}", r(line), r(through))
                }
                Op::ShiftedCircle { circle, from, to } => {
                    format!("shifted_circle {} {} -> {}", r(circle), r(from), r(to))
                }
                Op::Nearest { locus, point } => format!("nearest {} {}", r(locus), r(point)),
                Op::Onto {
                    locus,
                    point,
                    constraint,
                } => {
                    format!("onto {} {} for {}", r(locus), r(point), cname(constraint))
                }
                Op::Intersect {
                    meet,
                    a,
                    b,
                    branch,
                    constraint,
                    ..
                } => format!(
                    "intersect {:?} {} {} branch {} for {}",
                    meet,
                    r(a),
                    r(b),
                    self.branches
                        .get(branch.0 as usize)
                        .map_or("?", |b| b.name.as_str()),
                    cname(constraint)
                ),
                Op::Translate { geoms, from, to } => {
                    format!("translate [{}] {} -> {}", names(geoms), r(from), r(to))
                }
                Op::RotatePoint {
                    geoms,
                    pivot,
                    axis,
                    from,
                    to,
                } => format!(
                    "rotate [{}] about {}{} {} -> {}",
                    names(geoms),
                    r(pivot),
                    around(axis),
                    r(from),
                    r(to)
                ),
                Op::RotateDir {
                    geoms,
                    pivot,
                    axis,
                    from,
                    to,
                } => format!(
                    "rotate [{}] about {}{} dir {} -> {}",
                    names(geoms),
                    r(pivot),
                    around(axis),
                    r(from),
                    r(to)
                ),
                Op::SetDim { geom, value } => format!("set_dim {} {}", name(geom), r(value)),
                Op::Check {
                    constraint,
                    residual,
                    guard,
                } => format!(
                    "{} {} {}",
                    if *guard { "guard" } else { "check" },
                    cname(constraint),
                    residual_text(residual)
                ),
                Op::Default(id) => format!(
                    "default {}",
                    self.defaults
                        .get(id.0 as usize)
                        .map_or("?", |d| d.name.as_str())
                ),
                Op::Close {
                    constraint,
                    residual,
                } => format!("close {} by {}", cname(constraint), r(residual)),
                Op::Error {
                    residual,
                    component: crate::plan::MAGNITUDE,
                } => format!("error {} magnitude", residual_text(residual)),
                Op::Error {
                    residual,
                    component,
                } => format!("error {} #{component}", residual_text(residual)),
                Op::Planar(op) => self.planar_text(model, op),
                Op::Spatial(op) => self.spatial_text(model, op),
            };
            let sat = if s.satisfies.is_empty() {
                String::new()
            } else {
                format!(
                    "   ; {}",
                    s.satisfies.iter().map(cname).collect::<Vec<_>>().join(", ")
                )
            };
            let _ = writeln!(out, "{lhs}{op}{sat}");
        }
        out
    }

    /// The text of an operation of the plane.
    fn planar_text(&self, model: &Model, op: &PlanarOp) -> String {
        let r = |r: &Reg| format!("r{}", r.0);
        let cname = |c: &ConstraintId| model.constraints[*c].name.clone();
        match op {
            PlanarOp::Reversed(x) => format!("reversed {}", r(x)),
            PlanarOp::LineDir(x) => format!("line_dir {}", r(x)),
            PlanarOp::Linear(system) => {
                use crate::plan::Coef;
                let coef = |c: &Coef| match c {
                    Coef::One => "1".to_string(),
                    Coef::X(v) => format!("x({})", r(v)),
                    Coef::Y(v) => format!("y({})", r(v)),
                    Coef::Dot(a, b) => format!("dot({}, {})", r(a), r(b)),
                    Coef::Cross(a, b) => format!("cross({}, {})", r(a), r(b)),
                };
                let rows: Vec<String> = (system.rows.iter())
                    .map(|row| {
                        let terms: Vec<String> = (row.terms.iter())
                            .map(|t| {
                                format!(
                                    "{} {} x{}",
                                    crate::plan::fmt_f64(t.scale),
                                    coef(&t.coef),
                                    t.unknown
                                )
                            })
                            .collect();
                        format!(
                            "[{}: {} = -{}]",
                            cname(&row.constraint),
                            terms.join(" + "),
                            r(&row.error)
                        )
                    })
                    .collect();
                format!(
                    "linear {} unknowns {} tears {:?} pivots {:?} closures {:?}",
                    system.unknowns,
                    rows.join(" "),
                    system.tears,
                    system.pivots,
                    system.closures
                )
            }
            PlanarOp::OffsetLine { line, by } => format!("offset_line {} by {}", r(line), r(by)),
            PlanarOp::CentresLineLine { l1, a1, l2, a2 } => {
                format!("centres_line_line {} {} {} {}", r(l1), r(a1), r(l2), r(a2))
            }
            PlanarOp::CentresLinePoint {
                line,
                a,
                at,
                b,
                plus,
            } => format!(
                "centres_line_point {} {} {} {} {}",
                r(line),
                r(a),
                r(at),
                r(b),
                if *plus { "plus" } else { "minus" }
            ),
            PlanarOp::CentresPointPoint {
                c1,
                b1,
                p1,
                c2,
                b2,
                p2,
            } => format!(
                "centres_point_point {} {} {} {} {} {}",
                r(c1),
                r(b1),
                if *p1 { "plus" } else { "minus" },
                r(c2),
                r(b2),
                if *p2 { "plus" } else { "minus" }
            ),
            PlanarOp::RadiusFromLine { line, a, centre } => {
                format!("radius_from_line {} {} {}", r(line), r(a), r(centre))
            }
            PlanarOp::RadiusFromPoint {
                at,
                b,
                plus,
                centre,
            } => format!(
                "radius_from_point {} {} {} {}",
                r(at),
                r(b),
                if *plus { "plus" } else { "minus" },
                r(centre)
            ),
            PlanarOp::Axis(x, y) => format!("axis ({x}, {y})"),
            PlanarOp::Rotated { dir, angle } => format!("rotated {} by {}", r(dir), r(angle)),
            PlanarOp::AngleOf(dir) => format!("angle_of {}", r(dir)),
            PlanarOp::PointXY { x, y } => format!("point ({}, {})", r(x), r(y)),
            PlanarOp::Mirror { point, line } => format!("mirror {} across {}", r(point), r(line)),
            PlanarOp::Circle { center, radius } => format!("circle {} {}", r(center), r(radius)),
            PlanarOp::CircleThrough {
                center, through, ..
            } => {
                format!("circle_through {} {}", r(center), r(through))
            }
            PlanarOp::PassingDir {
                pivot,
                base,
                dir,
                point,
                offset,
                branch,
                constraint,
            } => format!(
                "passing_dir about {} of {} {} past {}{} branch {} for {}",
                r(pivot),
                r(base),
                r(dir),
                r(point),
                offset.map_or(String::new(), |o| format!(" at {}", r(&o))),
                self.branches
                    .get(branch.0 as usize)
                    .map_or("?", |b| b.name.as_str()),
                cname(constraint)
            ),
        }
    }

    /// The text of an operation of space.
    fn spatial_text(&self, model: &Model, op: &SpatialOp) -> String {
        let r = |r: &Reg| format!("r{}", r.0);
        let name = |g: &GeomId| model.geoms[*g].name.clone();
        let names = |gs: &[GeomId]| gs.iter().map(name).collect::<Vec<_>>().join(" ");
        let cname = |c: &ConstraintId| model.constraints[*c].name.clone();
        match op {
            SpatialOp::MirrorPlane {
                point,
                base,
                normal,
            } => format!("mirror {} across plane {} {}", r(point), r(base), r(normal)),
            SpatialOp::SurfacePoint { locus, u, v } => {
                format!("surface_point {} at {} {}", r(locus), r(u), r(v))
            }
            SpatialOp::SurfaceParam {
                locus,
                point,
                component,
            } => format!("surface_param {} of {} {component}", r(locus), r(point)),
            SpatialOp::Plane {
                point,
                normal,
                offset,
            } => match offset {
                Some(o) => format!("plane {} {} offset {}", r(point), r(normal), r(o)),
                None => format!("plane {} {}", r(point), r(normal)),
            },
            SpatialOp::ParallelPlane { plane, through } => {
                format!("parallel_plane {} through {}", r(plane), r(through))
            }
            SpatialOp::Sphere { center, radius } => format!("sphere {} {}", r(center), r(radius)),
            SpatialOp::Cylinder { point, dir, radius } => {
                format!("cylinder {} {} {}", r(point), r(dir), r(radius))
            }
            SpatialOp::ShiftedCylinder { cylinder, from, to } => {
                format!("shifted_cylinder {} {} -> {}", r(cylinder), r(from), r(to))
            }
            SpatialOp::Torus { circle, tube } => format!("torus {} {}", r(circle), r(tube)),
            SpatialOp::ShiftedTorus { torus, from, to } => {
                format!("shifted_torus {} {} -> {}", r(torus), r(from), r(to))
            }
            SpatialOp::Circle3 {
                center,
                normal,
                radius,
            } => format!(
                "circle {} normal {} radius {}",
                r(center),
                r(normal),
                r(radius)
            ),
            SpatialOp::SphereThrough {
                center,
                through,
                radius,
            } => match radius {
                Some(k) => format!(
                    "sphere_through {} {} radius {}",
                    r(center),
                    r(through),
                    fmt_f64(*k)
                ),
                None => format!("sphere_through {} {}", r(center), r(through)),
            },
            SpatialOp::ShiftedSphere { sphere, from, to } => {
                format!("shifted_sphere {} {} -> {}", r(sphere), r(from), r(to))
            }
            SpatialOp::Orbit {
                pivot,
                axis,
                through,
            } => format!("orbit {} {} {}", r(pivot), r(axis), r(through)),
            SpatialOp::Opposite(d) => format!("opposite {}", r(d)),
            SpatialOp::Across(d) => format!("across {}", r(d)),
            SpatialOp::AngleAbout { u, v, axis } => {
                format!("angle {} -> {} about {}", r(u), r(v), r(axis))
            }
            SpatialOp::AngleAboutBoth { u, v, axis } => format!(
                "angle {} -> {} and {} -> {} about {}",
                r(&u[0]),
                r(&v[0]),
                r(&u[1]),
                r(&v[1]),
                r(axis)
            ),
            SpatialOp::TurnReaching {
                u,
                v,
                axis,
                pivot,
                reach,
                screw,
            } => {
                let helix = |h: &crate::plan::HelixRegs| {
                    format!(
                        "helix {} {} from {} of {} at {} pitch {}",
                        r(&h.axis),
                        r(&h.x_from),
                        r(&h.origin),
                        r(&h.x),
                        r(&h.point),
                        r(&h.pitch)
                    )
                };
                let reach = match reach {
                    crate::plan::Reach::Point { point, locus } => {
                        format!("taking {} onto {}", r(point), r(locus))
                    }
                    crate::plan::Reach::Helix(h) => format!("meeting {}", helix(h)),
                };
                format!(
                    "angle {} -> {} about {} at {} {reach}{}",
                    r(u),
                    r(v),
                    r(axis),
                    r(pivot),
                    screw.map_or(String::new(), |s| format!(
                        " riding {} along {}",
                        helix(&s.helix),
                        r(&s.slide)
                    ))
                )
            }
            SpatialOp::HelixAdvance { now, turn, pitch } => {
                format!(
                    "helix_advance from {} for turn {} pitch {}",
                    r(now),
                    r(turn),
                    r(pitch)
                )
            }
            SpatialOp::HelixTurn { advance, pitch } => {
                format!("helix_turn {} pitch {}", r(advance), r(pitch))
            }
            SpatialOp::WorldAxis(i) => format!("world_axis {i}"),
            SpatialOp::PlaneNormal { a, b, c } => {
                format!("plane_normal {} {} {}", r(a), r(b), r(c))
            }
            SpatialOp::PlaneTurn {
                base,
                normal,
                pivot,
                point,
                d,
                constraint,
            } => format!(
                "plane_turn {} {} about {} to {} from {} for {}",
                r(base),
                r(normal),
                r(pivot),
                r(d),
                r(point),
                cname(constraint)
            ),
            SpatialOp::PlaneAxisTurn {
                base,
                normal,
                pivot,
                point,
                d,
                axis,
                branch,
                constraint,
            } => format!(
                "plane_axis_turn {} {} about {} along {} to {} from {} branch {} for {}",
                r(base),
                r(normal),
                r(pivot),
                r(axis),
                r(d),
                r(point),
                self.branches[branch.0 as usize].name,
                cname(constraint)
            ),
            SpatialOp::Aligned { dir, near } => format!("aligned {} near {}", r(dir), r(near)),
            SpatialOp::ConeTurn { axis, angle, dir } => {
                format!("cone_turn {} about {} to {}", r(dir), r(axis), r(angle))
            }
            SpatialOp::PassingAngle {
                from,
                to,
                d,
                now,
                constraint,
            } => format!(
                "passing_angle {} from {} to {} at {} for {}",
                r(now),
                r(from),
                r(to),
                r(d),
                cname(constraint)
            ),
            SpatialOp::TiltToDistance {
                centre,
                point,
                radius,
                d,
                now,
                constraint,
            } => format!(
                "tilt_to_distance {} about {} radius {} at {} from {} for {}",
                r(now),
                r(centre),
                r(radius),
                r(d),
                r(point),
                cname(constraint)
            ),
            SpatialOp::AngleTurn {
                u,
                v,
                axis,
                angle,
                branch,
                constraint,
            } => format!(
                "angle_turn {} about {} to {} from {} branch {} for {}",
                r(v),
                r(axis),
                r(angle),
                r(u),
                self.branches[branch.0 as usize].name,
                cname(constraint)
            ),
            SpatialOp::Coordinate { point, axis } => format!("coordinate {axis} of {}", r(point)),
            SpatialOp::PointAt { x, y, z } => format!("point {} {} {}", r(x), r(y), r(z)),
            SpatialOp::TurnedAbout { dir, axis, angle } => {
                format!("turned {} about {} by {}", r(dir), r(axis), r(angle))
            }
            SpatialOp::ThreeCircles {
                first,
                a,
                second,
                third,
                b,
                near,
                branch,
                constraint,
            } => format!(
                "three_circles {} about {} {} meets {} about {} {} then {} {} near {} branch {} for {}",
                r(a),
                r(&first[0]),
                r(&first[1]),
                r(b),
                r(&third[0]),
                r(&third[1]),
                r(&second[0]),
                r(&second[1]),
                r(near),
                self.branches[branch.0 as usize].name,
                cname(constraint)
            ),
            SpatialOp::PlanarChainEnds {
                first,
                h,
                base,
                joint,
                far,
                last,
                offset,
                sense,
                branch,
                constraint,
            } => format!(
                "planar_chain_ends {} {} about {} {} to {} about {} {} then {} {} offset {} sense {} branch {} for {}",
                r(h),
                r(base),
                r(&first[0]),
                r(&first[1]),
                r(far),
                r(&joint[0]),
                r(&joint[1]),
                r(&last[0]),
                r(&last[1]),
                r(offset),
                fmt_f64(*sense),
                self.branches[branch.0 as usize].name,
                cname(constraint)
            ),
            SpatialOp::RotateBy {
                geoms,
                pivot,
                axis,
                angle,
            } => format!(
                "rotate [{}] about {} around {} by {}",
                names(geoms),
                r(pivot),
                r(axis),
                r(angle)
            ),
        }
    }
}

/// How a rotation's axis reads in the dump: nothing for the plane's normal.
fn around(axis: &RotationAxis) -> String {
    match axis {
        RotationAxis::Normal => String::new(),
        RotationAxis::Along(a) => format!(" around r{}", a.0),
        RotationAxis::Shortest => " around the shortest axis".into(),
    }
}

/// A check's relation and registers.
fn residual_text(residual: &Residual) -> String {
    let r = |r: &Reg| format!("r{}", r.0);
    let opt = |x: &Option<Reg>| x.as_ref().map_or_else(|| "0".to_string(), r);
    match residual {
        Residual::PointPoint { a, b, d } => format!("point_point {} {} {}", r(a), r(b), opt(d)),
        Residual::PointLine { p, base, dir, d } => {
            format!("point_line {} {} {} {}", r(p), r(base), r(dir), opt(d))
        }
        Residual::Angle { u, v, angle } => format!("angle {} {} {}", r(u), r(v), r(angle)),
        Residual::CircleLine {
            centre,
            radius,
            base,
            dir,
            gap,
            side,
        } => format!(
            "circle_line {} {} {} {} {} side {}",
            r(centre),
            r(radius),
            r(base),
            r(dir),
            opt(gap),
            fmt_f64(*side)
        ),
        Residual::PointCircle {
            p,
            centre,
            radius,
            gap,
            outside,
        } => format!(
            "point_circle {} {} {} {} {}",
            r(p),
            r(centre),
            r(radius),
            opt(gap),
            if *outside { "outside" } else { "inside" }
        ),
        Residual::CircleCircle {
            c1,
            r1,
            c2,
            r2,
            gap,
            nesting,
        } => format!(
            "circle_circle {} {} {} {} {} {nesting:?}",
            r(c1),
            r(r1),
            r(c2),
            r(r2),
            opt(gap)
        ),
        Residual::Dim { value, target } => format!("dim {} {}", r(value), r(target)),
        Residual::Midpoint { p, a, b } => format!("midpoint {} {} {}", r(p), r(a), r(b)),
        Residual::Mirror { p, q, base, dir } => {
            format!("mirror {} {} {} {}", r(p), r(q), r(base), r(dir))
        }
        Residual::MirrorPlane { p, q, base, normal } => {
            format!("mirror_plane {} {} {} {}", r(p), r(q), r(base), r(normal))
        }
        Residual::PointPlane { p, base, normal, d } => {
            format!("point_plane {} {} {} {}", r(p), r(base), r(normal), opt(d))
        }
        Residual::OnCircle {
            p,
            centre,
            normal,
            radius,
            d,
        } => format!(
            "on_circle {} {} {} {}{}",
            r(p),
            r(centre),
            r(normal),
            r(radius),
            d.map_or(String::new(), |d| format!(" at {}", r(&d)))
        ),
        Residual::AngleBetween { u, v, angle } => {
            format!("angle_between {} {} {}", r(u), r(v), r(angle))
        }
        Residual::Parallel { u, v, sense } => {
            format!("parallel {} {} sense {}", r(u), r(v), fmt_f64(*sense))
        }
        Residual::Helix {
            axis,
            u,
            v,
            p,
            q,
            pitch,
        } => format!(
            "helix {} {} about {} advance {} -> {} pitch {}",
            r(u),
            r(v),
            r(axis),
            r(p),
            r(q),
            r(pitch)
        ),
        Residual::Twist { axis, u, v, angle } => {
            format!("twist {} {} {} about {}", r(u), r(v), r(angle), r(axis))
        }
        Residual::Cone { axis, u, v } => format!("cone {} {} about {}", r(u), r(v), r(axis)),
    }
}
