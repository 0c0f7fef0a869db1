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

/// The cube's graph iterates on two defaults together (`C_angle`, `E_angle`) until two bars
/// close. Its diagonal bar goes from 6 to 7.8 and back in steps of 0.01, each solve from the
/// last answer's defaults: every step solves, every one of the thirteen bars keeps its length
/// (re-measured here), and no joint jumps; back at the start, the framework is where it began.
#[test]
fn the_cube_graph_follows_one_assembly_while_two_defaults_iterate_together() {
    use gcs_examples::cube_graph;
    let bars: [(&str, &str, f64); 12] = [
        ("A", "B", 4.000),
        ("A", "C", 3.536),
        ("A", "E", 3.606),
        ("B", "D", 4.031),
        ("B", "F", 3.536),
        ("C", "D", 4.031),
        ("C", "G", 3.048),
        ("D", "H", 3.202),
        ("E", "F", 4.528),
        ("E", "G", 4.230),
        ("F", "H", 4.528),
        ("G", "H", 4.571),
    ];
    let point = |s: &cube_graph::Solution, name: &str| {
        (s.points().into_iter())
            .find(|(n, _)| *n == name)
            .map(|(_, p)| p)
            .unwrap_or_else(|| panic!("no point {name}"))
    };
    let branches = cube_graph::Branches::default();
    let mut defaults = cube_graph::Defaults::default();
    let mut first: Option<cube_graph::Solution> = None;
    let mut last: Option<cube_graph::Solution> = None;
    let steps: Vec<i32> = (0..=180).chain((0..180).rev()).collect();
    for step in steps {
        let diagonal = 6.0 + f64::from(step) * 0.01;
        let params = cube_graph::Params { diagonal };
        let s = cube_graph::solve(&params, &branches, &defaults)
            .unwrap_or_else(|e| panic!("diagonal {diagonal}: {e}"));
        for (a, b, length) in bars.iter().copied().chain([("E", "H", diagonal)]) {
            let off = distance(point(&s, a), point(&s, b)) - length;
            assert!(
                off.abs() < 1e-12,
                "diagonal {diagonal}: {a}{b} off by {off:e}"
            );
        }
        if let Some(q) = &last {
            for (name, p) in s.points() {
                let moved = distance(p, point(q, name));
                assert!(moved < 0.2, "diagonal {diagonal}: {name} jumped {moved}");
            }
        }
        first.get_or_insert(s);
        last = Some(s);
        defaults = s.defaults();
    }
    let (first, last) = (first.expect("solved"), last.expect("solved"));
    for (name, p) in first.points() {
        assert!(
            distance(p, point(&last, name)) < 1e-9,
            "{name} did not come back"
        );
    }
}
