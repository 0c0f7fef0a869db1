//! `gcs draw`: a solved model as a clean, deterministic SVG.
//!
//! The picture is built in three steps, each a plain function of what the one before made:
//!
//! 1. **The scene** ([`Scene::new`]): what to draw, read from the [`Model`] in model order and
//!    named by the dotted names of a [`Solution`], so that the same scene is drawn at any
//!    solution of the model (each sample of a sweep, each frame of an animation).
//! 2. **The geometry** of each element at a solution, projected on the picture's plane by the
//!    [`View`], then fitted to the picture by a [`Fit`]: the drawn solution, the traced curves,
//!    and with `animate` every sample, with a margin.
//! 3. **The text** ([`svg`], written by `picture`): one `<style>` block, shared definitions, then one group a layer,
//!    in this order: `planes`, `curves`, `bodies`, `traces`, `arrows`, `grounds`, `points`,
//!    `labels`; within a layer, model order. Numbers have three decimals at most
//!    ([`svg::num`]); nothing depends on time or on hash order.
//!
//! What is drawn, and how (classes of the style sheet in brackets):
//!
//! - A point (a top-level point, a body's member point or marker) is a dot (`point`) with its
//!   dotted name as a label (`label`); points drawn at one pixel share one label, their names
//!   joined. A segment's ends and a circle's centre are small dots (`end`), unlabelled; the
//!   segment, circle, line or plane has its name as a label. A label right of the middle ends
//!   at its point, and the picture grows where a label would cross its edge.
//! - A body is the links between its member points and markers: a filled, semi-transparent
//!   polygon (`body`) of their convex hull (taken once, in the drawn solution, so that no member
//!   order draws a crossed polygon) for three or more, a bar (`bar`) for two; one colour a
//!   moving body, in model order (`b0`, `b1`, ...). Its member vectors are arrows from its
//!   frame's origin (`vector`); a marker's axes are short arrows from its point (`axis x`,
//!   `axis z`), foreshortened by the view.
//! - A distance between two points of different geoms is a link (`link`): a rod of the linkage.
//! - A segment (`segment`), a circle (`circle`; in space, its projection, an ellipse drawn as a
//!   72-gon), an infinite line (`line`, dashed), clipped to the picture; a plane in space
//!   (`plane`) is a square patch of it centred where the points' centroid projects onto it, as
//!   wide as the drawn points' bounding box's diagonal.
//! - A fixed geom is ground: its points stand on a hatched ground symbol (`ground`), its bodies
//!   are hatched (`fixed`), its curves are drawn black and heavier.
//! - A top-level vector has a direction but no place: it is not drawn.
//! - A traced point's curve over a sweep (`trace`, one colour a trace: `t0`, `t1`, ...) is one
//!   polyline for each run of samples that solved: a failed sample leaves a gap
//!   ([`sweep::runs`]); a run of one sample is a dot (`trace-point`).
//!
//! With `animate`, each element's position attributes get an SMIL `<animate>` over the
//! samples (a failed sample repeats the last position that solved), a tenth of a second a
//! sample, looping; the static attributes are the drawn solution's.
//!
//! Like the rest of the crate, this module does no I/O: it returns the SVG as a `String`.

mod picture;
mod project;
pub mod svg;
pub mod sweep;

pub use picture::draw;
pub use project::{clip_line, Fit, View};
pub use sweep::{runs, Sweep};

use crate::solution::{ByName, Solution};
use gcs_lang::constraints::ConstraintKind;
use gcs_lang::model::{GeomId, GeomKind, Owner, Part, Space};
use gcs_lang::Model;
use std::collections::HashMap;
use std::fmt::Write as _;

/// What to draw beside the model itself.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Options {
    /// The view of a spatial model (a planar one is always seen from above, [`View::Xy`]).
    pub view: View,
    /// The points whose curves over the samples are drawn, by dotted name.
    pub traces: Vec<String>,
    /// Whether the picture plays the samples by itself.
    pub animate: bool,
}

/// A drawing: the SVG and the view transform it was drawn with.
#[derive(Clone, Debug, PartialEq)]
pub struct Drawing {
    /// The SVG document.
    pub svg: String,
    /// The projection on the picture's plane.
    pub view: View,
    /// The projected plane to the picture's pixels.
    pub fit: Fit,
}

impl Drawing {
    /// The pixel where a position of the model (2 or 3 coordinates) is drawn.
    pub fn pixel(&self, p: &[f64]) -> [f64; 2] {
        self.fit.pixel(self.view.project(p))
    }
}

/// Length of an arrow (an axis, a vector) seen face on, in pixels.
pub const ARROW: f64 = 28.0;

/// Where a label sits from the pixel it names, in pixels (right and up; left and up for a
/// label in the right half of the picture, which ends there).
const LABEL_OFFSET: [f64; 2] = [7.0, -7.0];

/// The font size of labels, in pixels (as the style sheet says), and the width of one of
/// their characters the picture makes room for (a little more than a sans-serif font's mean).
const LABEL_FONT: f64 = 12.0;
const LABEL_CHAR: f64 = 7.0;

/// The least room between a label and the picture's edge, in pixels.
const LABEL_PAD: f64 = 4.0;

/// The box a label's text takes, `[left, top, right, bottom]` in pixels, as estimated from
/// its characters: from where it is anchored, at its start or at its end (`end`).
fn label_box(at: [f64; 2], end: bool, text: &str) -> [f64; 4] {
    let width = LABEL_CHAR * text.chars().count() as f64;
    let x0 = if end { at[0] - width } else { at[0] };
    [x0, at[1] - LABEL_FONT, x0 + width, at[1] + 0.3 * LABEL_FONT]
}

/// Seconds of animation a sample.
const SECONDS_A_SAMPLE: f64 = 0.1;

/// Sides of the polygon a circle in space is drawn as.
const CIRCLE_SIDES: usize = 72;

/// The point names `--trace` may take: every point and marker of the model (members and parts
/// included), in model order.
pub fn traceable(model: &Model) -> Vec<&str> {
    (model.geoms.iter())
        .filter(|(_, g)| g.kind.is_pointlike())
        .map(|(_, g)| g.name.as_str())
        .collect()
}

/// Why `name` cannot be traced, in words for the command line; `None` when it can.
pub fn trace_error(model: &Model, name: &str) -> Option<String> {
    match model.geom_named(name) {
        Some(id) if model.geoms[id].kind.is_pointlike() => None,
        Some(id) => Some(format!(
            "`{name}` is {}, not a point",
            model.geoms[id].kind.noun()
        )),
        None => {
            const SHOWN: usize = 12;
            let names = traceable(model);
            let mut list = names
                .iter()
                .take(SHOWN)
                .copied()
                .collect::<Vec<_>>()
                .join(", ");
            if names.len() > SHOWN {
                let _ = write!(list, ", and {} more", names.len() - SHOWN);
            }
            Some(format!(
                "no point `{name}`; the points are: {}",
                if names.is_empty() { "(none)" } else { &list }
            ))
        }
    }
}

/// The layers of the picture, bottom to top.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Layer {
    Planes,
    Curves,
    Bodies,
    Traces,
    Arrows,
    Grounds,
    Points,
    Labels,
}

impl Layer {
    const ALL: [Layer; 8] = [
        Layer::Planes,
        Layer::Curves,
        Layer::Bodies,
        Layer::Traces,
        Layer::Arrows,
        Layer::Grounds,
        Layer::Points,
        Layer::Labels,
    ];

    /// The id of its group.
    fn name(self) -> &'static str {
        match self {
            Layer::Planes => "planes",
            Layer::Curves => "curves",
            Layer::Bodies => "bodies",
            Layer::Traces => "traces",
            Layer::Arrows => "arrows",
            Layer::Grounds => "grounds",
            Layer::Points => "points",
            Layer::Labels => "labels",
        }
    }
}

/// Where something is, by the names of a solution.
#[derive(Clone, Debug, PartialEq)]
enum At {
    /// A point.
    Point(String),
    /// A body's frame's origin.
    Origin(String),
    /// The midpoint of two points.
    Mid(String, String),
    /// The first corner of a plane's patch ([`Item::Plane`]).
    Corner {
        normal: String,
        offset: String,
        half: f64,
    },
}

/// What an element draws, by the names of a solution.
#[derive(Clone, Debug, PartialEq)]
enum Item {
    /// A dot of this radius (pixels) at a point.
    Dot { at: String, radius: f64 },
    /// The ground symbol under a point.
    Ground { at: String },
    /// A label (its text is the element's name, or merged with others).
    Label { at: At },
    /// A line between two points: a body's bar, a link, a segment.
    Bar { ends: [String; 2] },
    /// A polygon through points, in this order.
    Polygon { corners: Vec<String> },
    /// An arrow from a place along a direction.
    Arrow { from: At, dir: String },
    /// A circle: its centre, radius and, in space, normal.
    Circle {
        center: String,
        radius: String,
        normal: Option<String>,
    },
    /// An infinite line through a point along a direction.
    Line { point: String, dir: String },
    /// A plane's patch; `half` is half its side, in model units.
    Plane {
        normal: String,
        offset: String,
        half: f64,
    },
}

/// One element of the picture: its layer, classes, the name it draws (`data-name`) and what
/// it draws.
#[derive(Clone, Debug, PartialEq)]
struct Element {
    layer: Layer,
    class: String,
    name: String,
    item: Item,
    /// The marker at the end of an arrow.
    marker: Option<&'static str>,
}

/// What a model draws, in model order.
#[derive(Clone, Debug, Default)]
struct Scene {
    elements: Vec<Element>,
}

impl Scene {
    /// The scene of `model`; `shown` decides what needs a solution to choose (a body's hull,
    /// a plane's patch's size), seen through `view`.
    fn new(model: &Model, shown: &Solution, view: View) -> Scene {
        let by = shown.by_name();
        let mut scene = Scene::default();
        let name = |id: GeomId| model.geoms[id].name.clone();
        let part = |id: GeomId, p: Part| model.part(id, p).map(name);
        let mut bodies = 0;
        // Half the side of a plane's patch: half the diagonal of the points' box.
        let half = {
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for (_, p) in &shown.points {
                for k in 0..p.len().min(3) {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            let d2: f64 = (0..3)
                .map(|k| hi[k] - lo[k])
                .filter(|d| d.is_finite())
                .map(|d| d * d)
                .sum();
            if d2 > 0.0 {
                d2.sqrt() / 2.0
            } else {
                1.0
            }
        };
        for (id, g) in model.geoms.iter() {
            let fixed = if g.fixed { " fixed" } else { "" };
            match (g.kind, g.owner) {
                (GeomKind::Point | GeomKind::Marker, Owner::TopLevel | Owner::Member(_)) => {
                    scene.point(&g.name, g.fixed);
                }
                (GeomKind::Point, Owner::Part(_, Part::Start | Part::End | Part::Center)) => {
                    scene.push(
                        Layer::Points,
                        "end",
                        &g.name,
                        Item::Dot {
                            at: g.name.clone(),
                            radius: svg::END_RADIUS,
                        },
                    );
                }
                (GeomKind::Vector, Owner::Member(body)) => {
                    scene.arrow("vector", &g.name, At::Origin(name(body)), "arrow");
                }
                (GeomKind::Vector, Owner::Part(marker, p @ (Part::AxisX | Part::AxisZ))) => {
                    let (class, arrow) = match p {
                        Part::AxisX => ("axis x", "arrow-x"),
                        _ => ("axis z", "arrow-z"),
                    };
                    scene.arrow(class, &g.name, At::Point(name(marker)), arrow);
                }
                (GeomKind::Segment, _) => {
                    let (Some(a), Some(b)) = (part(id, Part::Start), part(id, Part::End)) else {
                        continue;
                    };
                    scene.push(
                        Layer::Curves,
                        &format!("segment{fixed}"),
                        &g.name,
                        Item::Bar {
                            ends: [a.clone(), b.clone()],
                        },
                    );
                    scene.label(&g.name, At::Mid(a, b));
                }
                (GeomKind::Circle, _) => {
                    let Some(center) = part(id, Part::Center) else {
                        continue;
                    };
                    let normal = match model.space {
                        Space::D2 => None,
                        Space::D3 => part(id, Part::Normal),
                    };
                    scene.push(
                        Layer::Curves,
                        &format!("circle{fixed}"),
                        &g.name,
                        Item::Circle {
                            center: center.clone(),
                            radius: format!("{}.radius", g.name),
                            normal,
                        },
                    );
                    scene.label(&g.name, At::Point(center));
                }
                (GeomKind::Line, _) => {
                    let (Some(point), Some(dir)) = (part(id, Part::BasePoint), part(id, Part::Dir))
                    else {
                        continue;
                    };
                    scene.push(
                        Layer::Curves,
                        &format!("line{fixed}"),
                        &g.name,
                        Item::Line {
                            point: point.clone(),
                            dir,
                        },
                    );
                    scene.label(&g.name, At::Point(point));
                }
                (GeomKind::Plane, _) => {
                    let Some(normal) = part(id, Part::Normal) else {
                        continue;
                    };
                    let offset = format!("{}.offset", g.name);
                    scene.push(
                        Layer::Planes,
                        &format!("plane{fixed}"),
                        &g.name,
                        Item::Plane {
                            normal: normal.clone(),
                            offset: offset.clone(),
                            half,
                        },
                    );
                    scene.label(
                        &g.name,
                        At::Corner {
                            normal,
                            offset,
                            half,
                        },
                    );
                }
                (GeomKind::Body, _) => {
                    let members: Vec<String> = (g.parts.iter())
                        .filter(|&&m| {
                            let m = &model.geoms[m];
                            m.kind.is_pointlike() && m.owner == Owner::Member(id)
                        })
                        .map(|&m| name(m))
                        .collect();
                    let projected: Vec<[f64; 2]> = (members.iter())
                        .map(|m| by.point(m).map_or([f64::NAN; 2], |p| view.project(p)))
                        .collect();
                    let corners: Vec<String> = (hull(&projected).into_iter())
                        .map(|k| members[k].clone())
                        .collect();
                    let colour = if g.fixed {
                        "fixed".to_string()
                    } else {
                        bodies += 1;
                        format!("b{}", (bodies - 1) % svg::BODY_COLOURS.len())
                    };
                    match corners.len() {
                        0 | 1 => {}
                        2 => scene.push(
                            Layer::Bodies,
                            &format!("bar {colour}"),
                            &g.name,
                            Item::Bar {
                                ends: [corners[0].clone(), corners[1].clone()],
                            },
                        ),
                        _ => scene.push(
                            Layer::Bodies,
                            &format!("body {colour}"),
                            &g.name,
                            Item::Polygon { corners },
                        ),
                    }
                }
                _ => {}
            }
        }
        // A distance between two points of different geoms: a rod.
        for (_, c) in model.constraints.iter() {
            let [a, b] = c.args[..] else {
                continue;
            };
            let pointlike = |g: GeomId| model.geoms[g].kind.is_pointlike();
            if c.kind == ConstraintKind::Distance
                && pointlike(a)
                && pointlike(b)
                && model.top_level_of(a) != model.top_level_of(b)
            {
                scene.push(
                    Layer::Curves,
                    "link",
                    &c.name,
                    Item::Bar {
                        ends: [name(a), name(b)],
                    },
                );
            }
        }
        scene.elements.sort_by_key(|e| e.layer);
        scene
    }

    fn push(&mut self, layer: Layer, class: &str, name: &str, item: Item) {
        self.elements.push(Element {
            layer,
            class: class.to_string(),
            name: name.to_string(),
            item,
            marker: None,
        });
    }

    /// A point: its dot, its label and, when fixed, its ground symbol.
    fn point(&mut self, name: &str, fixed: bool) {
        if fixed {
            self.push(
                Layer::Grounds,
                "ground-point",
                name,
                Item::Ground {
                    at: name.to_string(),
                },
            );
        }
        self.push(
            Layer::Points,
            "point",
            name,
            Item::Dot {
                at: name.to_string(),
                radius: svg::POINT_RADIUS,
            },
        );
        self.label(name, At::Point(name.to_string()));
    }

    fn label(&mut self, name: &str, at: At) {
        self.push(Layer::Labels, "label", name, Item::Label { at });
    }

    fn arrow(&mut self, class: &str, name: &str, from: At, marker: &'static str) {
        self.push(
            Layer::Arrows,
            class,
            name,
            Item::Arrow {
                from,
                dir: name.to_string(),
            },
        );
        if let Some(e) = self.elements.last_mut() {
            e.marker = Some(marker);
        }
    }
}

/// A solution as the scene reads it.
struct Frame<'a> {
    by: ByName<'a>,
    origins: HashMap<&'a str, &'a [f64]>,
    /// The centroid of its points (in 3d; a planar one at z = 0).
    centroid: [f64; 3],
}

impl<'a> Frame<'a> {
    fn of(s: &'a Solution) -> Frame<'a> {
        let mut sum = [0.0; 3];
        let mut n = 0.0;
        for (_, p) in &s.points {
            if p.iter().all(|x| x.is_finite()) {
                for (k, x) in p.iter().take(3).enumerate() {
                    sum[k] += x;
                }
                n += 1.0;
            }
        }
        let centroid = if n > 0.0 { sum.map(|x| x / n) } else { sum };
        Frame {
            by: s.by_name(),
            origins: (s.frames.iter())
                .map(|(n, o, _)| (n.as_str(), o.as_slice()))
                .collect(),
            centroid,
        }
    }

    fn at(&self, at: &At, view: View) -> Option<[f64; 2]> {
        let p = match at {
            At::Point(p) => view.project(self.by.point(p)?),
            At::Origin(b) => view.project(self.origins.get(b.as_str())?),
            At::Mid(a, b) => {
                let (a, b) = (self.by.point(a)?, self.by.point(b)?);
                let m: Vec<f64> = a.iter().zip(b).map(|(x, y)| (x + y) / 2.0).collect();
                view.project(&m)
            }
            At::Corner {
                normal,
                offset,
                half,
            } => *self.patch(normal, offset, *half, view)?.first()?,
        };
        finite(p)
    }

    /// The corners of a plane's square patch of half side `half`, centred where the centroid
    /// projects onto the plane, projected; `None` when the solution lacks the plane or has
    /// it non-finite.
    fn patch(&self, normal: &str, offset: &str, half: f64, view: View) -> Option<Vec<[f64; 2]>> {
        let n = three(self.by.vector(normal)?);
        let d = self.by.scalar(offset)?;
        let c = self.centroid;
        let above = n[0] * c[0] + n[1] * c[1] + n[2] * c[2] - d;
        let centre: Vec<f64> = (0..3).map(|i| c[i] - above * n[i]).collect();
        let (u, v) = basis(n);
        [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)]
            .iter()
            .map(|(a, b)| {
                let p: Vec<f64> = (0..3)
                    .map(|i| centre[i] + half * (a * u[i] + b * v[i]))
                    .collect();
                finite(view.project(&p))
            })
            .collect()
    }
}

/// `p` if its coordinates are finite.
fn finite(p: [f64; 2]) -> Option<[f64; 2]> {
    (p[0].is_finite() && p[1].is_finite()).then_some(p)
}

/// Three coordinates of a position or direction (a planar one at z = 0).
fn three(p: &[f64]) -> [f64; 3] {
    [
        p.first().copied().unwrap_or(0.0),
        p.get(1).copied().unwrap_or(0.0),
        p.get(2).copied().unwrap_or(0.0),
    ]
}

/// Two unit vectors that make, with the unit `n`, a right-handed orthonormal frame: the first
/// normal to `n` and to the world axis least aligned with it (the first such in x, y, z).
fn basis(n: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let mut axis = [0.0; 3];
    let k = (0..3)
        .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(0);
    axis[k] = 1.0;
    let u = cross(n, axis);
    let len = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    let u = u.map(|x| x / len);
    (u, cross(n, u))
}

/// An element's geometry at one solution, projected on the picture's plane (model units).
#[derive(Clone, Debug, PartialEq)]
enum Geo {
    /// A place: a dot, a ground symbol, a label.
    At([f64; 2]),
    /// A line between two places.
    Bar([f64; 2], [f64; 2]),
    /// A closed polygon.
    Polygon(Vec<[f64; 2]>),
    /// A circle in the plane: centre and radius.
    Circle([f64; 2], f64),
    /// An arrow: where it starts and the projected unit direction.
    Arrow([f64; 2], [f64; 2]),
    /// An infinite line: a point of it and its projected direction.
    Line([f64; 2], [f64; 2]),
}

impl Geo {
    /// The places a fit must show.
    fn extent(&self, out: &mut Vec<[f64; 2]>) {
        match self {
            Geo::At(p) | Geo::Arrow(p, _) | Geo::Line(p, _) => out.push(*p),
            Geo::Bar(a, b) => out.extend([*a, *b]),
            Geo::Polygon(ps) => out.extend(ps),
            Geo::Circle(c, r) => out.extend([[c[0] - r, c[1] - r], [c[0] + r, c[1] + r]]),
        }
    }
}

/// An element's shape in pixels.
#[derive(Clone, Debug, PartialEq)]
enum Shape {
    /// `<circle>`: centre and radius.
    Circle([f64; 2], f64),
    /// `<use>` of the ground symbol at a pixel.
    Use([f64; 2]),
    /// `<text>` at a pixel; anchored at its end (to the pixel's left) when `true`.
    Text([f64; 2], bool),
    /// `<line>` between two pixels.
    Line([f64; 2], [f64; 2]),
    /// `<polygon>` through pixels.
    Polygon(Vec<[f64; 2]>),
}

impl Shape {
    /// Its element's tag.
    fn tag(&self) -> &'static str {
        match self {
            Shape::Circle(..) => "circle",
            Shape::Use(_) => "use",
            Shape::Text(..) => "text",
            Shape::Line(..) => "line",
            Shape::Polygon(_) => "polygon",
        }
    }

    /// Its position attributes, as written: what an animation varies.
    fn attributes(&self) -> Vec<(&'static str, String)> {
        let n = svg::num;
        match self {
            Shape::Circle(c, r) => vec![("cx", n(c[0])), ("cy", n(c[1])), ("r", n(*r))],
            Shape::Use(p) | Shape::Text(p, _) => vec![("x", n(p[0])), ("y", n(p[1]))],
            Shape::Line(a, b) => vec![
                ("x1", n(a[0])),
                ("y1", n(a[1])),
                ("x2", n(b[0])),
                ("y2", n(b[1])),
            ],
            Shape::Polygon(ps) => vec![("points", svg::points(ps))],
        }
    }
}

impl Item {
    /// Its geometry at a solution, projected by `view`; `None` when the solution lacks what it
    /// needs or has it degenerate (an arrow seen end on).
    fn geo(&self, f: &Frame<'_>, view: View) -> Option<Geo> {
        let point = |p: &str| finite(view.project(f.by.point(p)?));
        match self {
            Item::Dot { at, .. } | Item::Ground { at } => Some(Geo::At(point(at)?)),
            Item::Label { at } => Some(Geo::At(f.at(at, view)?)),
            Item::Bar { ends: [a, b] } => Some(Geo::Bar(point(a)?, point(b)?)),
            Item::Polygon { corners } => {
                let ps = (corners.iter())
                    .map(|c| point(c))
                    .collect::<Option<Vec<_>>>()?;
                Some(Geo::Polygon(ps))
            }
            Item::Arrow { from, dir } => {
                let d = finite(view.project(f.by.vector(dir)?))?;
                (d[0].hypot(d[1]) > gcs_runtime::tol::END_ON)
                    .then_some(Geo::Arrow(f.at(from, view)?, d))
            }
            Item::Circle {
                center,
                radius,
                normal,
            } => {
                let r = f.by.scalar(radius).filter(|r| r.is_finite())?;
                match normal {
                    None => Some(Geo::Circle(point(center)?, r)),
                    Some(n) => {
                        let c = three(f.by.point(center)?);
                        let (u, v) = basis(three(f.by.vector(n)?));
                        let ps = (0..CIRCLE_SIDES)
                            .map(|k| {
                                let t = std::f64::consts::TAU * k as f64 / CIRCLE_SIDES as f64;
                                let (s, co) = t.sin_cos();
                                let p: Vec<f64> =
                                    (0..3).map(|i| c[i] + r * (co * u[i] + s * v[i])).collect();
                                finite(view.project(&p))
                            })
                            .collect::<Option<Vec<_>>>()?;
                        Some(Geo::Polygon(ps))
                    }
                }
            }
            Item::Line { point: p, dir } => {
                let d = finite(view.project(f.by.vector(dir)?))?;
                (d[0].hypot(d[1]) > gcs_runtime::tol::END_ON).then_some(Geo::Line(point(p)?, d))
            }
            Item::Plane {
                normal,
                offset,
                half,
            } => Some(Geo::Polygon(f.patch(normal, offset, *half, view)?)),
        }
    }

    /// Its shape in pixels, given its geometry; `None` for a line that misses the picture.
    fn shape(&self, geo: &Geo, fit: &Fit) -> Option<Shape> {
        let px = |p: &[f64; 2]| fit.pixel(*p);
        Some(match (self, geo) {
            (Item::Dot { radius, .. }, Geo::At(p)) => Shape::Circle(px(p), *radius),
            (Item::Ground { .. }, Geo::At(p)) => Shape::Use(px(p)),
            (Item::Label { .. }, Geo::At(p)) => {
                // Toward the middle of the picture, so that it stays inside.
                let q = px(p);
                let end = q[0] > fit.pixel(fit.mid)[0];
                let dx = if end {
                    -LABEL_OFFSET[0]
                } else {
                    LABEL_OFFSET[0]
                };
                Shape::Text([q[0] + dx, q[1] + LABEL_OFFSET[1]], end)
            }
            (_, Geo::Bar(a, b)) => Shape::Line(px(a), px(b)),
            (_, Geo::Polygon(ps)) => Shape::Polygon(ps.iter().map(px).collect()),
            (_, Geo::Circle(c, r)) => Shape::Circle(px(c), r * fit.scale),
            (_, Geo::Arrow(p, d)) => {
                let (a, t) = (px(p), fit.turn(*d));
                Shape::Line(a, [a[0] + ARROW * t[0], a[1] + ARROW * t[1]])
            }
            (_, Geo::Line(p, d)) => {
                let (a, b) = clip_line(px(p), fit.turn(*d), fit.size)?;
                Shape::Line(a, b)
            }
            (_, Geo::At(_)) => return None,
        })
    }
}

/// The indices of the convex hull of `points`, counter-clockwise (Andrew's monotone chain),
/// without collinear points or repeats; the non-finite points are left out. Two distinct
/// points are their own hull, in index order; a single one too.
fn hull(points: &[[f64; 2]]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..points.len())
        .filter(|&i| points[i][0].is_finite() && points[i][1].is_finite())
        .collect();
    order.sort_by(|&i, &j| {
        (points[i][0].total_cmp(&points[j][0]))
            .then(points[i][1].total_cmp(&points[j][1]))
            .then(i.cmp(&j))
    });
    order.dedup_by(|i, j| points[*i] == points[*j]);
    if order.len() <= 2 {
        order.sort_unstable();
        return order;
    }
    let cross = |o: usize, a: usize, b: usize| {
        let (o, a, b) = (points[o], points[a], points[b]);
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut h: Vec<usize> = Vec::with_capacity(2 * order.len());
    for pass in [order.clone(), order.iter().rev().copied().collect()] {
        let floor = h.len();
        for &i in &pass {
            while h.len() >= floor + 2 && cross(h[h.len() - 2], h[h.len() - 1], i) <= 0.0 {
                h.pop();
            }
            h.push(i);
        }
        h.pop();
    }
    if h.len() <= 2 {
        // Collinear: the two ends.
        h.sort_unstable();
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hull_is_counter_clockwise_without_inner_or_collinear_points() {
        let square = [
            [0.0, 0.0],
            [1.0, 1.0],
            [1.0, 0.0],
            [0.5, 0.5],
            [0.0, 1.0],
            [0.5, 0.0],
        ];
        assert_eq!(hull(&square), vec![0, 2, 1, 4]);
        // Collinear: its two ends; repeats and non-finite points left out.
        assert_eq!(hull(&[[2.0, 2.0], [0.0, 0.0], [1.0, 1.0]]), vec![0, 1]);
        assert_eq!(hull(&[[1.0, 1.0], [1.0, 1.0], [f64::NAN, 0.0]]), vec![0]);
        assert_eq!(hull(&[[3.0, 0.0], [0.0, 0.0]]), vec![0, 1]);
    }

    /// The four-bar of examples/fourbar.gcs (without its output), solved at `theta`s: `None`
    /// where the loop does not close.
    fn fourbar(crank: f64, thetas: &[f64]) -> (Model, Vec<Option<Solution>>) {
        let text = "space 2d; param theta = 30 deg; param crank_len = 1.5;
            fixed point A = (0, 0); fixed point D = (4, 0); fixed vector X = (1, 0);
            body crank at (0, 0) { point a = (0, 0); point b = (crank_len, 0); vector u = (1, 0); }
            body coupler at (1.5, 0) { point b = (0, 0); point c = (4, 0); }
            body rocker at (4, 0) { point d = (0, 0); point c = (0, 3); }
            coincident(crank.a, A); drive: angle(X, crank.u) = theta;
            coincident(crank.b, coupler.b); elbow: coincident(coupler.c, rocker.c);
            coincident(rocker.d, D);";
        let c = crate::compile("fourbar.gcs", text.as_bytes()).expect("compiles");
        let analysis = c.analysis;
        let model = c.model;
        let solutions = (thetas.iter())
            .map(|t| {
                let mut p = model.default_params();
                (p[0], p[1]) = (*t, crank);
                let branches: Vec<usize> =
                    analysis.plan.branches.iter().map(|b| b.default).collect();
                crate::solve(&model, &analysis, &p, &branches).ok()
            })
            .collect();
        (model, solutions)
    }

    #[test]
    fn a_failed_sample_leaves_a_gap_in_a_traced_curve() {
        // With a crank of 6, the loop closes near theta = 0 and not near pi.
        let thetas: Vec<f64> = (0..=12)
            .map(|k| k as f64 * std::f64::consts::TAU / 12.0)
            .collect();
        let (model, samples) = fourbar(6.0, &thetas);
        let solved: Vec<bool> = samples.iter().map(Option::is_some).collect();
        assert!(solved[0] && solved[12] && !solved[6], "{solved:?}");
        let shown = samples[0].clone().expect("solved");
        let options = Options {
            traces: vec!["coupler.c".to_string()],
            ..Options::default()
        };
        let d = draw(&model, &shown, &samples, &options).expect("draws");
        let traces = &d.svg[d.svg.find("<g id=\"traces\">").expect("traces")..];
        let traces = &traces[..traces.find("\n</g>").expect("closed")];
        assert_eq!(traces.matches("<polyline").count(), 2, "{traces}");
        // Each polyline is a run of samples that solved, in order, and ends at its run's ends.
        let runs = runs(&samples);
        assert_eq!(runs.len(), 2);
        for (run, line) in runs.iter().zip(traces.split("<polyline").skip(1)) {
            let point = |s: &Solution| {
                let p = &s
                    .points
                    .iter()
                    .find(|(n, _)| n == "coupler.c")
                    .expect("c")
                    .1;
                svg::pair(d.pixel(p))
            };
            let first = point(&run[0]);
            let last = point(run.last().expect("a run"));
            assert!(line.starts_with(&format!(" points=\"{first} ")), "{line}");
            assert!(line.contains(&format!(" {last}\"/>")), "{line}");
            assert_eq!(line.matches(',').count(), run.len());
        }
        // An unknown point is no trace.
        let options = Options {
            traces: vec!["coupler.z".to_string()],
            ..Options::default()
        };
        let e = draw(&model, &shown, &samples, &options).expect_err("no such point");
        assert!(
            e.starts_with("no point `coupler.z`; the points are: A, D, crank.a"),
            "{e}"
        );
    }

    #[test]
    fn coincident_points_share_a_label_and_the_drawing_is_deterministic() {
        let (model, samples) = fourbar(1.5, &[0.5]);
        let shown = samples[0].clone().expect("solved");
        let d = draw(&model, &shown, &[], &Options::default()).expect("draws");
        assert!(d.svg.contains(">crank.b, coupler.b</text>"), "{}", d.svg);
        assert!(d.svg.contains(">coupler.c, rocker.c</text>"), "{}", d.svg);
        assert_eq!(d.svg.matches("<text ").count(), 4);
        assert_eq!(draw(&model, &shown, &[], &Options::default()), Ok(d));
    }

    #[test]
    fn an_animation_has_one_value_a_sample_and_repeats_a_failed_one() {
        let thetas = [0.0, 0.3, std::f64::consts::PI, 0.6];
        let (model, samples) = fourbar(6.0, &thetas);
        assert!(samples[2].is_none() && samples[3].is_some());
        let shown = samples[0].clone().expect("solved");
        let options = Options {
            animate: true,
            ..Options::default()
        };
        let d = draw(&model, &shown, &samples, &options).expect("draws");
        let dot = &d.svg[d.svg.find("data-name=\"coupler.c\" cx").expect("the dot")..];
        let cx = &dot[dot.find("attributeName=\"cx\"").expect("animated")..];
        let values = &cx[cx.find("values=\"").expect("values") + 8..];
        let values: Vec<&str> = values[..values.find('"').expect("end")]
            .split(';')
            .collect();
        assert_eq!(values.len(), 4);
        assert_eq!(
            values[2], values[1],
            "a failed sample repeats the last that solved"
        );
        assert_ne!(values[3], values[1]);
        assert!(cx.contains("dur=\"0.4s\" repeatCount=\"indefinite\""));
        // Fixed points do not move: no animation.
        let a = &d.svg[d
            .svg
            .find("<circle class=\"point\" data-name=\"A\"")
            .expect("A")..];
        assert!(
            a.starts_with("<circle class=\"point\" data-name=\"A\" cx=") && a.contains("r=\"4\"/>")
        );
        assert!(!a[..a.find('\n').expect("line")].contains("<animate"));
        assert!(a[..a.find('\n').expect("line")].ends_with("/>"));
    }

    #[test]
    fn the_picture_grows_to_hold_its_labels() {
        let text =
            "space 2d; fixed point a_point_with_a_long_name = (0, 0); fixed point B = (0, 10);";
        let c = crate::compile("tall.gcs", text.as_bytes()).expect("compiles");
        let shown = crate::solve(&c.model, &c.analysis, &[], &[]).expect("solves");
        let d = draw(&c.model, &shown, &[], &Options::default()).expect("draws");
        // The geometry alone is a picture 96 pixels wide; the long label starts at its point.
        let label = 7.0 + LABEL_CHAR * 24.0 + LABEL_PAD;
        assert_eq!(d.fit.size, [(48.0 + label).ceil(), 800.0]);
        assert!(d.svg.starts_with(&format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:xlink=\"http://www.w3.org/1999/xlink\" width=\"{}\" height=\"800\"",
            (48.0 + label).ceil()
        )));
        assert_eq!(d.pixel(&[0.0, 0.0]), [48.0, 752.0]);
    }

    #[test]
    fn a_basis_is_orthonormal_and_right_handed() {
        for n in [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 0.0],
            [0.6, 0.0, 0.8],
            [0.0, -1.0, 0.0],
        ] {
            let (u, v) = basis(n);
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            assert!(dot(u, n).abs() < 1e-15 && dot(v, n).abs() < 1e-15);
            assert!(dot(u, v).abs() < 1e-15);
            assert!((dot(u, u) - 1.0).abs() < 1e-15 && (dot(v, v) - 1.0).abs() < 1e-15);
            // u × v = n.
            let w = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            assert!((dot(w, n) - 1.0).abs() < 1e-15);
        }
    }
}
