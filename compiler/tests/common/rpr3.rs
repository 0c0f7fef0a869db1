//! The 3-RPR of `examples/rpr3.gcs`, recomputed in closed form from the example's numbers (the
//! circle of `platform.p1`, the circle-circle intersection that places `platform.p2` on branch
//! `l2`, the platform's rigid triangle), never from the plan or the runtime: what the tests of
//! its outer iteration measure gcs against.

use gcs_lang::Model;

/// The example's numbers, which the closed form reads (checked against its text).
pub const LEG1: f64 = 14.98;
pub const LEG2: f64 = 15.38;
pub const B2: [f64; 2] = [15.91, 0.0];
pub const B3: [f64; 2] = [0.0, 10.0];
/// `platform.p2` and `platform.p3` in the platform's frame, where `platform.p1` is the origin.
pub const P2_X: f64 = 17.04;
pub const P3: [f64; 2] = [15.940021741400596, 13.425362538233478];

/// The example, loaded, after checking that it still has the numbers above.
pub fn model() -> Model {
    let path = format!("{}/../examples/rpr3.gcs", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("read {path}: {e}"));
    for part in [
        "param leg1 = 14.98;",
        "param leg2 = 15.38;",
        "fixed point B1 = (0, 0);",
        "fixed point B2 = (15.91, 0);",
        "fixed point B3 = (0, 10);",
        "point p1 = (0, 0);",
        "point p2 = (17.04, 0);",
        "point p3 = (15.940021741400596, 13.425362538233478);",
    ] {
        assert!(
            text.contains(part),
            "the example changed: update this test ({part})"
        );
    }
    let (_, model, diags) = gcs_lang::load(&path, text.as_bytes());
    model.unwrap_or_else(|| panic!("{diags:?}"))
}

/// The distance from `B3` to `platform.p3` with `platform.p1` at angle `t` on its circle about
/// `B1`, and `platform.p2` on the circle about `B2` on branch `l2` (0: to the left of the line
/// from `platform.p1` to `B2`, 1: to its right); `None` where the circles miss.
pub fn reach(t: f64, l2: usize) -> Option<f64> {
    let p1 = [LEG1 * t.cos(), LEG1 * t.sin()];
    let (dx, dy) = (B2[0] - p1[0], B2[1] - p1[1]);
    let d = dx.hypot(dy);
    let along = (P2_X * P2_X - LEG2 * LEG2 + d * d) / (2.0 * d);
    let across = (P2_X * P2_X - along * along).sqrt();
    if across.is_nan() {
        return None;
    }
    let (ux, uy) = (dx / d, dy / d);
    let side = if l2 == 0 { 1.0 } else { -1.0 };
    let p2 = [
        p1[0] + along * ux - side * across * uy,
        p1[1] + along * uy + side * across * ux,
    ];
    // The platform's x axis along p1 -> p2, its y axis a quarter turn on.
    let (vx, vy) = ((p2[0] - p1[0]) / P2_X, (p2[1] - p1[1]) / P2_X);
    let p3 = [
        p1[0] + P3[0] * vx - P3[1] * vy,
        p1[1] + P3[0] * vy + P3[1] * vx,
    ];
    Some((p3[0] - B3[0]).hypot(p3[1] - B3[1]))
}
