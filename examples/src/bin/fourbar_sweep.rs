//! The coupler curve of a crank-rocker four-bar (`crank_rocker.gcs`), traced by its generated
//! solver.
//!
//! Usage: `cargo run -p gcs-examples --bin fourbar_sweep [-- OUT.svg] > curve.csv`
//!
//! Turns the crank angle `theta` through a full turn in 1-degree steps on the default branch
//! (`elbow`, the sketch's assembly), prints the coupler point `coupler.p` as CSV on stdout
//! (`theta_deg,x,y`), and writes an SVG drawing of the mechanism (ground pivots, crank, coupler
//! triangle and rocker at a few crank angles) with the coupler curve to `OUT.svg`
//! (default `coupler_curve.svg`).

use gcs_examples::crank_rocker::{solve, Branches, Defaults, Params, Solution};
use gcs_runtime::nalgebra::Point2;
use std::fmt::Write as _;
use std::process::ExitCode;

/// The crank angles, in degrees, at which the mechanism is drawn.
const DRAWN: [u32; 4] = [0, 90, 180, 270];

/// The joints of the mechanism at one crank angle.
struct Pose {
    /// Ground pivot of the crank.
    a: Point2<f64>,
    /// Crank-coupler joint.
    b: Point2<f64>,
    /// Coupler-rocker joint.
    c: Point2<f64>,
    /// Ground pivot of the rocker.
    d: Point2<f64>,
    /// The coupler's tracing point.
    p: Point2<f64>,
}

impl Pose {
    fn of(s: &Solution) -> Pose {
        Pose {
            a: s.crank_a(),
            b: s.coupler_b(),
            c: s.coupler_c(),
            d: s.d(),
            p: s.coupler_p(),
        }
    }
}

fn main() -> ExitCode {
    let svg_path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "coupler_curve.svg".to_string());
    let branches = Branches::default();
    let defaults = Defaults::default();
    let mut csv = String::from("theta_deg,x,y\n");
    let mut poses = Vec::with_capacity(360);
    let mut params = Params::default();
    for deg in 0..360u32 {
        params.theta = f64::from(deg).to_radians();
        match solve(&params, &branches, &defaults) {
            Ok(s) => {
                let pose = Pose::of(&s);
                let _ = writeln!(csv, "{deg},{:.9},{:.9}", pose.p.x, pose.p.y);
                poses.push((deg, pose));
            }
            Err(e) => {
                eprintln!("error: theta = {deg} deg: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    print!("{csv}");
    if let Err(e) = std::fs::write(&svg_path, svg(&poses)) {
        eprintln!("error: cannot write `{svg_path}`: {e}");
        return ExitCode::FAILURE;
    }
    eprintln!("wrote {svg_path}");
    ExitCode::SUCCESS
}

/// Maps model coordinates (y up) to SVG user units (y down), with a margin.
struct View {
    min: Point2<f64>,
    max: Point2<f64>,
    scale: f64,
    margin: f64,
}

impl View {
    fn fit(points: impl Iterator<Item = Point2<f64>>, width: f64) -> View {
        let mut min = Point2::new(f64::INFINITY, f64::INFINITY);
        let mut max = Point2::new(f64::NEG_INFINITY, f64::NEG_INFINITY);
        for p in points {
            min = Point2::new(min.x.min(p.x), min.y.min(p.y));
            max = Point2::new(max.x.max(p.x), max.y.max(p.y));
        }
        let margin = 40.0;
        let span = (max.x - min.x).max(max.y - min.y).max(1e-9);
        View {
            min,
            max,
            scale: (width - 2.0 * margin) / span,
            margin,
        }
    }

    fn width(&self) -> f64 {
        (self.max.x - self.min.x) * self.scale + 2.0 * self.margin
    }

    fn height(&self) -> f64 {
        (self.max.y - self.min.y) * self.scale + 2.0 * self.margin
    }

    fn at(&self, p: Point2<f64>) -> (f64, f64) {
        (
            self.margin + (p.x - self.min.x) * self.scale,
            self.margin + (self.max.y - p.y) * self.scale,
        )
    }

    /// `x,y` of a point, for `points` attributes.
    fn xy(&self, p: Point2<f64>) -> String {
        let (x, y) = self.at(p);
        format!("{x:.2},{y:.2}")
    }
}

/// The SVG drawing: the coupler curve, the mechanism at the crank angles of [`DRAWN`] (the
/// first solid, the others faded), and the ground pivots.
fn svg(poses: &[(u32, Pose)]) -> String {
    let view = View::fit(
        poses.iter().flat_map(|(_, q)| [q.a, q.b, q.c, q.d, q.p]),
        800.0,
    );
    let mut out = String::new();
    let (w, h) = (view.width(), view.height());
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.2} {h:.2}" font-family="sans-serif" font-size="14">"#
    );
    let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        out,
        r#"<text x="10" y="20">crank_rocker.gcs: coupler curve of coupler.p, theta 0..359 deg</text>"#
    );

    let curve: Vec<String> = poses.iter().map(|(_, q)| view.xy(q.p)).collect();
    let _ = writeln!(
        out,
        r##"<polygon points="{}" fill="none" stroke="#d62728" stroke-width="2"/>"##,
        curve.join(" ")
    );

    // The fixed link between the ground pivots.
    if let Some((_, q)) = poses.first() {
        let _ = writeln!(
            out,
            r#"<polyline points="{} {}" stroke="black" stroke-width="1.5" stroke-dasharray="6 4"/>"#,
            view.xy(q.a),
            view.xy(q.d)
        );
    }

    let drawn: Vec<&(u32, Pose)> = poses
        .iter()
        .filter(|(deg, _)| DRAWN.contains(deg))
        .collect();
    // Faded poses first, so that the solid one is on top.
    for (i, (deg, q)) in drawn.iter().enumerate().rev() {
        let opacity = if i == 0 { 1.0 } else { 0.3 };
        let _ = writeln!(out, r#"<g opacity="{opacity}">"#);
        let _ = writeln!(
            out,
            r##"<polygon points="{} {} {}" fill="#1f77b4" fill-opacity="0.25" stroke="#1f77b4" stroke-width="3" stroke-linejoin="round"/>"##,
            view.xy(q.b),
            view.xy(q.c),
            view.xy(q.p)
        );
        for (from, to, colour) in [(q.a, q.b, "#2ca02c"), (q.d, q.c, "#9467bd")] {
            let _ = writeln!(
                out,
                r#"<polyline points="{} {}" stroke="{colour}" stroke-width="5" stroke-linecap="round"/>"#,
                view.xy(from),
                view.xy(to)
            );
        }
        for joint in [q.b, q.c, q.p] {
            let (x, y) = view.at(joint);
            let _ = writeln!(
                out,
                r#"<circle cx="{x:.2}" cy="{y:.2}" r="4" fill="white" stroke="black" stroke-width="1.5"/>"#
            );
        }
        let (x, y) = view.at(q.p);
        let _ = writeln!(
            out,
            r#"<text x="{:.2}" y="{:.2}">{deg}°</text>"#,
            x + 8.0,
            y - 8.0
        );
        let _ = writeln!(out, "</g>");
    }

    // Ground pivots: a triangle under each, with its name.
    if let Some((_, q)) = poses.first() {
        for (pivot, name) in [(q.a, "A"), (q.d, "D")] {
            let (x, y) = view.at(pivot);
            let _ = writeln!(
                out,
                r##"<polygon points="{x:.2},{y:.2} {:.2},{:.2} {:.2},{:.2}" fill="#7f7f7f" stroke="black"/>"##,
                x - 10.0,
                y + 16.0,
                x + 10.0,
                y + 16.0
            );
            let _ = writeln!(
                out,
                r#"<circle cx="{x:.2}" cy="{y:.2}" r="5" fill="white" stroke="black" stroke-width="2"/>"#
            );
            let _ = writeln!(
                out,
                r#"<text x="{:.2}" y="{:.2}" font-weight="bold">{name}</text>"#,
                x - 5.0,
                y + 34.0
            );
        }
    }
    out.push_str("</svg>\n");
    out
}
