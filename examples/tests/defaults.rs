//! Under-constrained models through their generated solvers: a free motion is held by a
//! default at its sketch value (least motion), and a caller sets it through `Defaults`.

use gcs_examples::rectangle_free;

/// The rectangle missing its height keeps the sketch's (the right side's sketch length), is a
/// rectangle whatever the width, and takes the height a caller gives.
#[test]
fn the_rectangle_missing_its_height_keeps_the_sketch_height_until_given_one() {
    let sketch_height = (0.1f64 - 0.0).hypot(3.1 - 0.0);
    let corners = |s: &rectangle_free::Solution| {
        [
            s.bottom_start(),
            s.right_start(),
            s.top_start(),
            s.left_start(),
        ]
    };
    for (width, height) in [
        (4.0, None),
        (7.5, None),
        (4.0, Some(5.0)),
        (0.5, Some(0.25)),
    ] {
        let params = rectangle_free::Params { width };
        let mut defaults = rectangle_free::Defaults::default();
        if let Some(h) = height {
            defaults.left_length = h;
        }
        let s = rectangle_free::solve(&params, &rectangle_free::Branches::default(), &defaults)
            .unwrap_or_else(|e| panic!("width {width}: {e}"));
        let h = height.unwrap_or(sketch_height);
        let expected = [(0.0, 0.0), (width, 0.0), (width, h), (0.0, h)];
        for (p, (x, y)) in corners(&s).into_iter().zip(expected) {
            assert!(
                (p.x - x).abs() < 1e-12 && (p.y - y).abs() < 1e-12,
                "width {width}, height {h}: corner {p} instead of ({x}, {y})"
            );
        }
        // The segments meet end to end: the last corner closes on the first.
        assert!((s.left_end() - s.bottom_start()).norm() < 1e-12);
        assert!((s.right_end() - s.top_start()).norm() < 1e-12);
        assert!((s.top_end() - s.left_start()).norm() < 1e-12);
        assert!((s.defaults().left_length - h).abs() < 1e-12);
    }
}
