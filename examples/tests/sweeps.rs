//! Sweeps through generated solvers that iterate: each solve starts from the last answer's
//! defaults (`Solution::defaults`), so the sweep follows one assembly. The triad six-bar's
//! crank turns a whole turn in 1-degree steps: every step solves, no joint drifts (each
//! closure re-measured here by plain arithmetic), and the platform never jumps.

use gcs_examples::triad_sixbar;

fn distance(a: gcs_runtime::nalgebra::Point2<f64>, b: gcs_runtime::nalgebra::Point2<f64>) -> f64 {
    (a - b).norm()
}

#[test]
fn the_triad_six_bar_follows_one_assembly_through_a_whole_turn() {
    let mut defaults = triad_sixbar::Defaults::default();
    let branches = triad_sixbar::Branches::default();
    let mut last: Option<gcs_runtime::nalgebra::Point2<f64>> = None;
    for step in 0..=360 {
        let params = triad_sixbar::Params {
            theta: (step as f64).to_radians(),
        };
        let s = triad_sixbar::solve(&params, &branches, &defaults)
            .unwrap_or_else(|e| panic!("{step} deg: {e}"));
        // The three joints the iteration and the construction close.
        for (a, b, what) in [
            (s.link1_p(), s.platform_p1(), "j1"),
            (s.link2_p(), s.platform_p2(), "j2"),
            (s.link3_p(), s.platform_p3(), "j3"),
        ] {
            assert!(
                distance(a, b) < 1e-12,
                "{step} deg: {what} off by {}",
                distance(a, b)
            );
        }
        // The links keep their lengths (from the model: 3, 3.5 and 3).
        let lengths = [
            distance(s.link1_o(), s.link1_p()) - 3.0,
            distance(s.link2_o(), s.link2_p()) - 3.5,
            distance(s.link3_o(), s.link3_p()) - 3.0,
        ];
        assert!(
            lengths.iter().all(|l| l.abs() < 1e-12),
            "{step} deg: {lengths:?}"
        );
        // One degree of crank moves the platform a little, never to another assembly.
        let p = s.platform_p1();
        if let Some(q) = last {
            assert!(
                distance(p, q) < 0.2,
                "{step} deg: the platform jumped {}",
                distance(p, q)
            );
        }
        last = Some(p);
        defaults = s.defaults();
    }
}
