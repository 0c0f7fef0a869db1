//! Each arm written as a `.gcs` model, the way `examples/puma.gcs` writes an arm: a fixed
//! `ground` with the first joint's marker `base` and a `target` marker whose pose is nine
//! params, one body per link (`link_1` to `link_5`, then `tool`) with a marker at each of its
//! joints whose z axis is the joint's axis, `revolute` between consecutive links, and the
//! tool's `tcp` marker welded to the target. `cargo run --release --bin write_models` writes
//! `models/`; `tests/models.rs` checks that the files there are what this writes.
//!
//! The sketch is the arm at its `sketch` joint angles. A joint's marker sits where its axis
//! meets the next joint's axis (or else the one before), as a spherical wrist's three do, so
//! that the analysis sees that point known from the tool; otherwise at ik-geo's joint point.
//! Coordinates are written to the last bit (the shortest text that reads back as the same
//! number): a sketch rounded to 12 decimals is another arm, 1e-12 away, and gcs solves the
//! arm it is given.

use crate::arms::{square_to, Arm};
use ik_geo::nalgebra::{Matrix3, Vector3};
use std::fmt::Write as _;

/// Where the axes of joints `i` and `j` meet, in the zero configuration, if they do.
fn meeting(arm: &Arm, i: usize, j: usize) -> Option<Vector3<f64>> {
    let (a, u) = (arm.origin(i), arm.axis(i));
    let (b, w) = (arm.origin(j), arm.axis(j));
    let n = u.cross(&w);
    if n.norm() < 1e-9 {
        return None;
    }
    // The closest points a + s u and b + t w; the axes meet where they coincide.
    let d = b - a;
    let s = d.cross(&w).dot(&n) / n.norm_squared();
    let t = d.cross(&u).dot(&n) / n.norm_squared();
    let (p, q) = (a + s * u, b + t * w);
    ((p - q).norm() < 1e-12).then_some(round(p))
}

fn round(p: Vector3<f64>) -> Vector3<f64> {
    p.map(|x| (x * 1e12).round() / 1e12)
}

/// Joint `i`'s marker point in the zero configuration.
pub fn marker_point(arm: &Arm, i: usize) -> Vector3<f64> {
    (i < 5)
        .then(|| meeting(arm, i, i + 1))
        .flatten()
        .or_else(|| (i > 0).then(|| meeting(arm, i - 1, i)).flatten())
        .unwrap_or_else(|| round(arm.origin(i)))
}

/// A number as the model writes it: the shortest text that reads back as the same `f64`.
fn num(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    let s = format!("{x:?}");
    s.strip_suffix(".0").unwrap_or(&s).to_string()
}

fn triple(p: Vector3<f64>) -> String {
    format!("({}, {}, {})", num(p.x), num(p.y), num(p.z))
}

/// A marker's text: its point, z axis and x axis.
fn marker(name: &str, p: Vector3<f64>, z: Vector3<f64>, x: Vector3<f64>) -> String {
    format!(
        "    marker {name} = {} z {} x {};\n",
        triple(p),
        triple(z),
        triple(x)
    )
}

/// The model's file name: `ikgeo_<arm>.gcs`.
pub fn file_name(arm: &Arm) -> String {
    format!("ikgeo_{}.gcs", arm.name)
}

/// The body of link `k` (1 to 6): `link_k`, the last `tool`.
pub fn body(k: usize) -> String {
    if k == 6 {
        "tool".to_string()
    } else {
        format!("link_{k}")
    }
}

/// The model's text.
pub fn text(arm: &Arm, comment: &str) -> String {
    let links = arm.links(&arm.sketch);
    let rotation = |k: usize| -> Matrix3<f64> {
        // Link k's rotation (link 0 the ground).
        if k == 0 {
            Matrix3::identity()
        } else {
            links[k - 1].r
        }
    };
    // Joint i's marker (0-based joint, on links i and i + 1): its point, z and x at the
    // sketch. An axis parallel to the one before is taken from the link before that, so that
    // parallel axes are written with the same numbers.
    let joint = |i: usize| -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let h = arm.axis(i);
        let mut k = i;
        while k > 0 && arm.axis(k - 1).cross(&h).norm() < 1e-12 {
            k -= 1;
        }
        let r = rotation(k);
        // A point shared with the joints before (where their axes meet) is placed by the link
        // before the first of them, so that it is written with the same numbers.
        let m = marker_point(arm, i);
        let mut first = i;
        while first > 0 && marker_point(arm, first - 1) == m {
            first -= 1;
        }
        let p = if first == 0 {
            m
        } else {
            links[first - 1].point(m)
        };
        (p, r * h, r * square_to(h))
    };
    let tcp = links[5].point(arm.tool());
    let (tz, tx) = (
        links[5].r.column(2).into_owned(),
        links[5].r.column(0).into_owned(),
    );
    let mut s = String::new();
    for line in comment.lines() {
        let _ = writeln!(s, "// {line}");
    }
    s.push_str("space 3d;\n");
    let names = ["px", "py", "pz", "zx", "zy", "zz", "xx", "xy", "xz"];
    let values = [tcp.x, tcp.y, tcp.z, tz.x, tz.y, tz.z, tx.x, tx.y, tx.z];
    for (n, x) in names.iter().zip(values) {
        let _ = writeln!(s, "param {n} = {};", num(x));
    }
    s.push_str("fixed body ground {\n");
    let (p, z, x) = joint(0);
    s.push_str(&marker("base", p, z, x));
    s.push_str("    marker target = (px, py, pz) z (zx, zy, zz) x (xx, xy, xz);\n}\n");
    for k in 1..=6 {
        let _ = writeln!(s, "body {} {{", body(k));
        let (p, z, x) = joint(k - 1);
        s.push_str(&marker(&format!("j{k}"), p, z, x));
        if k < 6 {
            let (p, z, x) = joint(k);
            s.push_str(&marker(&format!("j{}", k + 1), p, z, x));
        } else {
            s.push_str(&marker("tcp", tcp, tz, tx));
        }
        s.push_str("}\n");
    }
    s.push_str("revolute(link_1.j1, ground.base);\n");
    for k in 2..=6 {
        let _ = writeln!(s, "revolute({}.j{k}, {}.j{k});", body(k), body(k - 1));
    }
    s.push_str("weld(tool.tcp, ground.target);\n");
    s
}

/// The leading comment of an arm's model: what the arm is, and where the file comes from.
pub fn comment(arm: &Arm) -> String {
    let what = match arm.name {
        "ur5" => {
            "ik-geo's `ur5()` (UR5 dimensions): a base that yaws, three parallel axes (shoulder,\n\
             elbow, first wrist joint), then two wrist joints, each axis meeting the one before.\n\
             ik-geo solves it by `three_parallel_two_intersecting`."
        }
        "irb6640" => {
            "ik-geo's `irb6640()` (ABB IRB 6640 dimensions): a base that yaws, a shoulder off its\n\
             axis, a shoulder and an elbow about parallel axes, and a spherical wrist. ik-geo\n\
             solves it by `spherical_two_parallel`."
        }
        "spherical_bot" => {
            "ik-geo's `spherical_bot()`: three joints in general position (no two axes parallel\n\
             or meeting), then a spherical wrist. ik-geo solves it by `spherical` (its\n\
             subproblem 5, a quartic)."
        }
        "three_parallel_bot" => {
            "ik-geo's `three_parallel_bot()`: a base that yaws, three parallel axes, then two\n\
             joints; no two axes meet. ik-geo solves it by `three_parallel` (its subproblem 6,\n\
             a quartic)."
        }
        "two_parallel_bot" => {
            "ik-geo's `two_parallel_bot()`: two parallel axes, the others in general position: no\n\
             closed form. ik-geo solves it by `two_parallel`, a search over the base's angle\n\
             with its subproblem 6 inside."
        }
        _ => "An arm of ik-geo.",
    };
    let q: Vec<String> = arm.sketch.iter().map(|x| x.to_string()).collect();
    format!(
        "{what}\n\
         The tool's pose (its point, its z and x axes) comes from params; the tool's frame is\n\
         the base's at zero joint angles, as in ik-geo. Sketched at joint angles\n\
         ({}), the params' defaults the tool's pose there.\n\
         Written by `cargo run --release --bin write_models` in ikgeo/ (src/model.rs) from\n\
         ik-geo 0.1.2's h and p: edit that, not this file.",
        q.join(", ")
    )
}
