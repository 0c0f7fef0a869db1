//! A circle of free radius tangent to a known line at a known point of it: through the point
//! and tangent to the line, its centre is on the parabola of those two fixed distances, whose
//! focus here lies on its directrix. That parabola degenerates into the normal to the line at
//! the point, which the analysis must use as the centre's locus (SolveSpace's arc tangent to a
//! line at an end they share). Random instances, the point an end of the tangent segment, an
//! end of it through a coincidence, or a point put on a line by `on`; the centre is then put on
//! a fixed line crossing the normal, before or after the tangency (the constraints' names
//! order the analysis). Each solve is judged by `verify` and by the centre and radius computed
//! here from the instance's numbers, never from the compiler's.

use gcs_compiler::{analyse, solve};

type V = [f64; 2];

/// A tiny deterministic generator (xorshift), so the random instances are the same each run.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn point(&mut self, r: f64) -> V {
        [self.range(-r, r), self.range(-r, r)]
    }
}

fn point(s: &gcs_compiler::solution::Solution, name: &str) -> V {
    let p = &(s.points.iter())
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no point {name}"))
        .1;
    [p[0], p[1]]
}

fn scalar(s: &gcs_compiler::solution::Solution, name: &str) -> f64 {
    (s.scalars.iter())
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no scalar {name}"))
        .1
}

/// How the touching point is tied to the line.
#[derive(Clone, Copy, Debug)]
enum Touch {
    /// `on(S.end, C)`: the segment's own end.
    End,
    /// A free point coincident with the segment's start, and on the circle.
    CoincidentStart,
    /// The same with the segment's end.
    CoincidentEnd,
    /// A free point on a fixed line (not a segment) by `on`, at a distance from a fixed
    /// point of it, and on the circle.
    OnLine,
}

#[test]
fn a_circle_tangent_to_a_line_at_a_point_of_it_has_its_centre_on_the_normal() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let touches = [
        Touch::End,
        Touch::CoincidentStart,
        Touch::CoincidentEnd,
        Touch::OnLine,
    ];
    for trial in 0..200 {
        let touch = touches[trial % touches.len()];
        // The centre's own line is met first or last.
        let centre_first = (trial / touches.len()).is_multiple_of(2);
        let a = rng.point(10.0);
        let len = rng.range(1.0, 10.0);
        let phi = rng.range(-std::f64::consts::PI, std::f64::consts::PI);
        let u = [phi.cos(), phi.sin()];
        let b = [a[0] + len * u[0], a[1] + len * u[1]];
        let t = match touch {
            Touch::End | Touch::CoincidentEnd => b,
            Touch::CoincidentStart => a,
            Touch::OnLine => {
                let along = rng.range(0.5, 1.5) * len;
                [a[0] + along * u[0], a[1] + along * u[1]]
            }
        };
        // The circle on either side, the centre along the left normal times the side.
        let side = if rng.next() < 0.5 { 1.0 } else { -1.0 };
        let radius = rng.range(0.5, 6.0);
        let n = [-u[1] * side, u[0] * side];
        let centre = [t[0] + radius * n[0], t[1] + radius * n[1]];
        // The fixed line the centre is on, at 25 to 155 degrees from the normal.
        let tilt = rng.range(25.0, 155.0).to_radians() * if rng.next() < 0.5 { 1.0 } else { -1.0 };
        let (c, s) = (tilt.cos(), tilt.sin());
        let m = [n[0] * c - n[1] * s, n[0] * s + n[1] * c];
        let m0 = [centre[0] - 3.0 * m[0], centre[1] - 3.0 * m[1]];
        let m1 = [centre[0] + 2.0 * m[0], centre[1] + 2.0 * m[1]];
        // The sketch: the circle and the point a little off.
        let jitter = 0.05 * radius;
        let sc = [
            centre[0] + rng.range(-jitter, jitter),
            centre[1] + rng.range(-jitter, jitter),
        ];
        let sr = radius * rng.range(0.9, 1.1);
        let sp = [
            t[0] + rng.range(-jitter, jitter),
            t[1] + rng.range(-jitter, jitter),
        ];
        let mut text = format!(
            "space 2d;\nfixed line M = ({}, {}) -> ({}, {});\n\
             circle C = center ({}, {}) radius {sr};\n",
            m0[0], m0[1], m1[0], m1[1], sc[0], sc[1]
        );
        let centre_on = if centre_first { "a" } else { "z" };
        text += &format!("{centre_on}: on(C.center, M);\n");
        match touch {
            Touch::OnLine => {
                text += &format!(
                    "fixed line S = ({}, {}) -> ({}, {});\npoint P = ({}, {});\n\
                     fixed point Q = ({}, {});\n\
                     p_on: on(P, S);\np_at: distance(P, Q) = {};\nt_on: on(P, C);\n",
                    a[0],
                    a[1],
                    b[0],
                    b[1],
                    sp[0],
                    sp[1],
                    a[0],
                    a[1],
                    ((t[0] - a[0]).powi(2) + (t[1] - a[1]).powi(2)).sqrt()
                );
            }
            _ => {
                text += &format!(
                    "fixed segment S = ({}, {}) -> ({}, {});\n",
                    a[0], a[1], b[0], b[1]
                );
                text += &match touch {
                    Touch::End => "t_on: on(S.end, C);\n".to_string(),
                    Touch::CoincidentStart | Touch::CoincidentEnd => {
                        let end = if matches!(touch, Touch::CoincidentStart) {
                            "start"
                        } else {
                            "end"
                        };
                        format!(
                            "point P = ({}, {});\nt_on: on(P, C);\nt_at: coincident(P, S.{end});\n",
                            sp[0], sp[1]
                        )
                    }
                    Touch::OnLine => unreachable!(),
                };
            }
        }
        text += "t_tangent: tangent(S, C);\n";
        let (_, model, diags) = gcs_lang::load("tangent.gcs", text.as_bytes());
        assert!(diags.iter().all(|d| !d.is_error()), "{diags:?}\n{text}");
        let model = model.expect("a model");
        let analysis = analyse(&model).expect("analysed");
        assert!(
            analysis.unsolved.is_empty(),
            "trial {trial} ({touch:?}): {:?}\n{text}",
            analysis.unsolved
        );
        let defaults: Vec<usize> = analysis.plan.branches.iter().map(|b| b.default).collect();
        let solved = solve(&model, &analysis, &[], &defaults)
            .unwrap_or_else(|e| panic!("trial {trial} ({touch:?}): {e}\n{text}"));
        let scale = 30.0;
        assert!(
            solved.max_residual <= 1e-9 * scale,
            "trial {trial} ({touch:?}): residual {:e}\n{text}",
            solved.max_residual
        );
        let got = point(&solved, "C.center");
        let off = ((got[0] - centre[0]).powi(2) + (got[1] - centre[1]).powi(2)).sqrt();
        let dr = (scalar(&solved, "C.radius") - radius).abs();
        assert!(
            off <= 1e-9 * scale && dr <= 1e-9 * scale,
            "trial {trial} ({touch:?}): centre {got:?} for {centre:?}, radius off by {dr:e}\n{text}"
        );
    }
}
