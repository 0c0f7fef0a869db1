//! The view transform of a drawing, in two steps: [`View`] projects the model's space onto the
//! picture's plane (orthographic: the identity for a planar model, one of four views of a
//! spatial one), and [`Fit`] maps the projected plane to the SVG's pixels, fitted to what is
//! drawn with a margin, its y axis turned down as SVG's is.

/// An orthographic view of space: the picture's right and up directions, as unit vectors of the
/// model's frame, orthogonal to each other. The viewer looks along `up × right`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum View {
    /// From above (+z toward the viewer): x to the right, y up. A planar model's only view.
    Xy,
    /// From the front (−y toward the viewer): x to the right, z up.
    Xz,
    /// From the side (+x toward the viewer): y to the right, z up.
    Yz,
    /// Isometric, from (1, 1, 1) toward the origin: z up, x down to the left, y down to the
    /// right, each axis foreshortened alike (by √(2/3)).
    #[default]
    Iso,
}

impl View {
    /// The view named on the command line: `xy`, `xz`, `yz` or `iso`.
    pub fn named(name: &str) -> Option<View> {
        match name {
            "xy" => Some(View::Xy),
            "xz" => Some(View::Xz),
            "yz" => Some(View::Yz),
            "iso" => Some(View::Iso),
            _ => None,
        }
    }

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            View::Xy => "xy",
            View::Xz => "xz",
            View::Yz => "yz",
            View::Iso => "iso",
        }
    }

    /// The picture's right and up directions in the model's frame.
    pub fn axes(self) -> ([f64; 3], [f64; 3]) {
        const R2: f64 = std::f64::consts::FRAC_1_SQRT_2;
        // 1/√6 and 2/√6: z projected on the plane normal to (1, 1, 1), normalised.
        let r6 = 1.0 / 6f64.sqrt();
        match self {
            View::Xy => ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]),
            View::Xz => ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            View::Yz => ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            View::Iso => ([-R2, R2, 0.0], [-r6, -r6, 2.0 * r6]),
        }
    }

    /// A position or direction of the model (two or three coordinates; a planar one has z = 0)
    /// on the picture's plane.
    pub fn project(self, p: &[f64]) -> [f64; 2] {
        let (r, u) = self.axes();
        let z = p.get(2).copied().unwrap_or(0.0);
        let q = [
            p.first().copied().unwrap_or(0.0),
            p.get(1).copied().unwrap_or(0.0),
            z,
        ];
        let dot = |a: [f64; 3]| a[0] * q[0] + a[1] * q[1] + a[2] * q[2];
        [dot(r), dot(u)]
    }
}

/// The picture's size and margin: the larger side of the fitted drawing is [`Fit::SIZE`]
/// pixels, the geometry [`Fit::MARGIN`] pixels inside it (room for labels and arrows).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// Pixels per unit of the model.
    pub scale: f64,
    /// The model's projected (x, y) that lands at the pixel (0, 0).
    pub corner: [f64; 2],
    /// The picture's width and height in pixels.
    pub size: [f64; 2],
    /// The middle of the fitted box (projected, model units): labels right of it end at
    /// their point, so that they stay inside.
    pub mid: [f64; 2],
}

impl Fit {
    /// The larger side of the picture, in pixels.
    pub const SIZE: f64 = 800.0;
    /// The empty band around the geometry, in pixels.
    pub const MARGIN: f64 = 48.0;

    /// The fit of the projected points `points` (those that are finite): their bounding box
    /// scaled alike in x and y so that its larger side spans `SIZE − 2 MARGIN` pixels, centred
    /// in a picture of whole pixels. A box that is flat in one direction gets a picture as high
    /// (or wide) as its margins; one that is a single point (or empty) is drawn at one pixel
    /// per unit about it (about the origin when empty).
    pub fn around(points: impl IntoIterator<Item = [f64; 2]>) -> Fit {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in points {
            if p[0].is_finite() && p[1].is_finite() {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        if lo[0] > hi[0] {
            (lo, hi) = ([0.0; 2], [0.0; 2]);
        }
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        let inner = Fit::SIZE - 2.0 * Fit::MARGIN;
        let scale = if extent > 0.0 { inner / extent } else { 1.0 };
        let size = [
            ((hi[0] - lo[0]) * scale + 2.0 * Fit::MARGIN).ceil(),
            ((hi[1] - lo[1]) * scale + 2.0 * Fit::MARGIN).ceil(),
        ];
        let mid = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
        Fit {
            scale,
            corner: [
                mid[0] - size[0] / 2.0 / scale,
                mid[1] + size[1] / 2.0 / scale,
            ],
            size,
            mid,
        }
    }

    /// The same fit in a picture grown by whole pixels on each side, `[left, top, right,
    /// bottom]` (each rounded up; a negative one is none): what was drawn moves right by
    /// `left` and down by `top`.
    pub fn grow(&self, by: [f64; 4]) -> Fit {
        let by = by.map(|b| if b > 0.0 { b.ceil() } else { 0.0 });
        Fit {
            scale: self.scale,
            corner: [
                self.corner[0] - by[0] / self.scale,
                self.corner[1] + by[1] / self.scale,
            ],
            size: [self.size[0] + by[0] + by[2], self.size[1] + by[1] + by[3]],
            mid: self.mid,
        }
    }

    /// The pixel of a projected position.
    pub fn pixel(&self, p: [f64; 2]) -> [f64; 2] {
        [
            (p[0] - self.corner[0]) * self.scale,
            (self.corner[1] - p[1]) * self.scale,
        ]
    }

    /// A projected direction in pixels per unit: y turned down.
    pub fn turn(&self, d: [f64; 2]) -> [f64; 2] {
        [d[0], -d[1]]
    }
}

/// The part of the line through `p` along `d` (both in pixels) inside the rectangle from the
/// origin to `size`, as its two ends in the order of `d`; `None` when the line misses it or `d`
/// is zero (Liang–Barsky clipping).
pub fn clip_line(p: [f64; 2], d: [f64; 2], size: [f64; 2]) -> Option<([f64; 2], [f64; 2])> {
    if !(d[0].is_finite() && d[1].is_finite()) || (d[0] == 0.0 && d[1] == 0.0) {
        return None;
    }
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..2 {
        if d[k] == 0.0 {
            if p[k] < 0.0 || p[k] > size[k] {
                return None;
            }
        } else {
            let (a, b) = ((0.0 - p[k]) / d[k], (size[k] - p[k]) / d[k]);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
    }
    (t0 < t1).then(|| {
        let at = |t: f64| [p[0] + t * d[0], p[1] + t * d[1]];
        (at(t0), at(t1))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12
    }

    #[test]
    fn the_axis_views_drop_one_coordinate() {
        let p = [1.0, 2.0, 3.0];
        assert_eq!(View::Xy.project(&p), [1.0, 2.0]);
        assert_eq!(View::Xz.project(&p), [1.0, 3.0]);
        assert_eq!(View::Yz.project(&p), [2.0, 3.0]);
        // A planar position is at z = 0.
        assert_eq!(View::Xz.project(&[1.0, 2.0]), [1.0, 0.0]);
    }

    #[test]
    fn every_view_is_orthonormal_and_looks_along_up_cross_right() {
        for view in [View::Xy, View::Xz, View::Yz, View::Iso] {
            let (r, u) = view.axes();
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            assert!((dot(r, r) - 1.0).abs() < 1e-15, "{view:?}");
            assert!((dot(u, u) - 1.0).abs() < 1e-15, "{view:?}");
            assert!(dot(r, u).abs() < 1e-15, "{view:?}");
            // The projection along the viewing direction is a point.
            let toward = [
                r[1] * u[2] - r[2] * u[1],
                r[2] * u[0] - r[0] * u[2],
                r[0] * u[1] - r[1] * u[0],
            ];
            assert!(close(view.project(&toward), [0.0, 0.0]), "{view:?}");
            assert_eq!(View::named(view.name()), Some(view));
        }
        assert_eq!(View::named("top"), None);
    }

    #[test]
    fn the_isometric_view_shows_the_three_axes_alike_with_z_up() {
        let v = View::Iso;
        let (x, y, z) = (
            v.project(&[1.0, 0.0, 0.0]),
            v.project(&[0.0, 1.0, 0.0]),
            v.project(&[0.0, 0.0, 1.0]),
        );
        let len = |p: [f64; 2]| p[0].hypot(p[1]);
        for a in [x, y, z] {
            assert!((len(a) - (2.0f64 / 3.0).sqrt()).abs() < 1e-15);
        }
        // z straight up, x down to the left, y down to the right, 120 degrees apart.
        assert!(z[0].abs() < 1e-15 && z[1] > 0.0);
        assert!(x[0] < 0.0 && x[1] < 0.0 && y[0] > 0.0 && y[1] < 0.0);
        let cos = (x[0] * y[0] + x[1] * y[1]) / (len(x) * len(y));
        assert!((cos + 0.5).abs() < 1e-15);
        // (1, 1, 1) is the viewing direction: the origin's pixel.
        assert!(close(v.project(&[1.0, 1.0, 1.0]), [0.0, 0.0]));
    }

    #[test]
    fn a_fit_keeps_the_aspect_and_puts_the_box_inside_its_margins() {
        let fit = Fit::around([[-1.0, 0.0], [3.0, 2.0], [0.0, 1.0]]);
        // The wider side spans the picture less its margins.
        assert_eq!(fit.size, [800.0, 448.0]);
        assert_eq!(fit.scale, (800.0 - 96.0) / 4.0);
        assert!(close(fit.pixel([-1.0, 2.0]), [48.0, 48.0]));
        assert!(close(fit.pixel([3.0, 0.0]), [752.0, 400.0]));
        // y turned down: higher in the model is a smaller pixel row.
        assert!(fit.pixel([0.0, 2.0])[1] < fit.pixel([0.0, 0.0])[1]);
        assert_eq!(fit.turn([1.0, 1.0]), [1.0, -1.0]);
        // A tall box: its height is the larger side.
        let tall = Fit::around([[0.0, 0.0], [1.0, 10.0]]);
        assert_eq!(tall.size, [167.0, 800.0]);
        let mid = tall.pixel([0.5, 5.0]);
        assert!(close(mid, [83.5, 400.0]));
    }

    #[test]
    fn a_degenerate_box_still_fits() {
        // Flat: the picture is as high as its margins.
        let flat = Fit::around([[0.0, 1.0], [2.0, 1.0]]);
        assert_eq!(flat.size, [800.0, 96.0]);
        assert!(close(flat.pixel([1.0, 1.0]), [400.0, 48.0]));
        // One point: one pixel a unit, the point in the middle.
        let one = Fit::around([[5.0, -3.0]]);
        assert_eq!((one.scale, one.size), (1.0, [96.0, 96.0]));
        assert!(close(one.pixel([5.0, -3.0]), [48.0, 48.0]));
        // Nothing finite: about the origin.
        let none = Fit::around([[f64::NAN, 0.0]]);
        assert!(close(none.pixel([0.0, 0.0]), [48.0, 48.0]));
    }

    #[test]
    fn a_grown_fit_moves_the_drawing_by_whole_pixels() {
        let fit = Fit::around([[-1.0, 0.0], [3.0, 2.0]]);
        let grown = fit.grow([10.2, 0.0, -3.0, 5.0]);
        assert_eq!(grown.size, [fit.size[0] + 11.0, fit.size[1] + 5.0]);
        for p in [[-1.0, 0.0], [3.0, 2.0], [0.5, 0.5]] {
            let (a, b) = (fit.pixel(p), grown.pixel(p));
            assert!(close([a[0] + 11.0, a[1]], b), "{a:?} {b:?}");
        }
        assert_eq!((grown.scale, grown.mid), (fit.scale, fit.mid));
        assert_eq!(fit.grow([0.0; 4]), fit);
    }

    #[test]
    fn a_line_is_clipped_to_the_picture() {
        let size = [100.0, 50.0];
        let (a, b) = clip_line([10.0, 10.0], [1.0, 0.0], size).expect("crosses");
        assert!(close(a, [0.0, 10.0]) && close(b, [100.0, 10.0]));
        let (a, b) = clip_line([50.0, 25.0], [-1.0, -1.0], size).expect("crosses");
        assert!(close(a, [75.0, 50.0]) && close(b, [25.0, 0.0]));
        assert_eq!(clip_line([10.0, 60.0], [1.0, 0.0], size), None);
        assert_eq!(clip_line([200.0, 10.0], [1.0, 1.0], size), None);
        assert_eq!(clip_line([10.0, 10.0], [0.0, 0.0], size), None);
    }
}
