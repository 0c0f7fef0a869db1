//! `gcs solve --least-motion global`: the free motions chosen together. A four-bar with no
//! drive, its coupler drawn too long: the crank's free angle taken together with the rest
//! moves the points less, in total, than the angle that moves nothing at its own step; a
//! default given with `--default` is kept; anything but `step` or `global` is refused.

mod support;

const MODEL: &str = "space 2d;
fixed point A = (0, 0);
fixed point D = (4, 0);
point B = (0.3, 1.4);
point C = (4.6, 2.6);
distance(A, B) = 1.5;
distance(B, C) = 4;
distance(C, D) = 2.5;
";

fn gcs(args: &[&str]) -> (i32, String, String) {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("free.gcs"), MODEL).expect("write model");
    let mut all = vec!["solve", "free.gcs", "--json"];
    all.extend(args);
    support::gcs_in(dir.path(), &all)
}

/// The sum of squared displacements of B and C from their sketch, read from the JSON.
fn motion(json: &str) -> f64 {
    let sketch = [("B", [0.3, 1.4]), ("C", [4.6, 2.6])];
    sketch
        .iter()
        .map(|(name, at)| {
            let key = format!("\"{name}\": [");
            let from = json.find(&key).expect("the point") + key.len();
            let xy: Vec<f64> = json[from..json[from..].find(']').expect("]") + from]
                .split(',')
                .map(|v| v.trim().parse().expect("a number"))
                .collect();
            (xy[0] - at[0]).powi(2) + (xy[1] - at[1]).powi(2)
        })
        .sum()
}

#[test]
fn the_global_choice_moves_the_points_less_in_total() {
    let (code, step, err) = gcs(&[]);
    assert_eq!(code, 0, "{err}");
    let (code, global, err) = gcs(&["--least-motion", "global"]);
    assert_eq!(code, 0, "{err}");
    let (ms, mg) = (motion(&step), motion(&global));
    assert!(mg < 0.7 * ms, "together {mg}, step by step {ms}");
    assert!(global.contains("\"max_residual\": "), "{global}");
}

#[test]
fn a_given_default_is_kept() {
    let (_, step, _) = gcs(&["--default", "B_angle=1"]);
    let (code, global, err) = gcs(&["--default", "B_angle=1", "--least-motion", "global"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(step, global);
}

#[test]
fn another_choice_is_refused() {
    let (code, out, err) = gcs(&["--least-motion", "nearest"]);
    assert_eq!(code, 2, "{out}");
    assert!(err.contains("step") && err.contains("global"), "{err}");
}
