//! The values of joints named in `output` (`J.angle`, `J.travel`): which forms the resolver
//! accepts and what it records in the `Model`. The refused forms are golden diagnostics in
//! `diagnostics.rs`.

use gcs_lang::constraints::JointValue;
use gcs_lang::model::OutputOf;
use gcs_lang::Model;

/// Loads a model that must check clean.
fn load(src: &str) -> Model {
    let (source, model, diags) = gcs_lang::load("model.gcs", src.as_bytes());
    assert!(
        diags.is_empty(),
        "{}",
        gcs_lang::diagnostic::render_plain(&source, &diags)
    );
    model.expect("a model")
}

/// Each output as (path, what it names in words): `geom NAME` or `NAME's angle|travel`.
fn outputs(m: &Model) -> Vec<(String, String)> {
    (m.outputs.iter())
        .map(|o| {
            let what = match o.of {
                OutputOf::Geom(g) => format!("geom {}", m.geoms[g].name),
                OutputOf::Joint(c, v) => format!("{}'s {}", m.constraints[c].name, v.name()),
            };
            (o.path.clone(), what)
        })
        .collect()
}

fn pairs(items: &[(&str, &str)]) -> Vec<(String, String)> {
    (items.iter())
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

const SPACE: &str = "space 3d;
fixed body ground { marker m = (0, 0, 0) z (0, 0, 1) x (1, 0, 0);
                    marker rail = (0, 0, 0) z (1, 0, 0) x (0, 1, 0); }
body a { marker m = (0, 0, 0) z (0, 0, 1) x (1, 0, 0); marker tip = (2, 0, 0) z (0, 0, 1) x (1, 0, 0); }
body b { marker m = (2, 0, 0) z (0, 0, 1) x (1, 0, 0); }
body c { marker s = (2, 0, 0) z (1, 0, 0) x (0, 1, 0); }
point P = (3, 0, 0);
";

#[test]
fn every_joint_value_by_label_and_by_derived_name_in_3d() {
    let m = load(&format!(
        "{SPACE}q1: revolute(a.m, ground.m);
offset_x(ground.m, a.m) = 0.3;
cyl: cylindrical(b.m, a.tip);
prismatic(c.s, ground.rail);
in_line(P, ground.rail);
output q1.angle, offset_x_ground_m_a_m.angle;
output cyl.angle, cyl.travel, prismatic_c_s_ground_rail.travel;
output in_line_P_ground_rail.travel, a.tip;
"
    ));
    assert_eq!(
        outputs(&m),
        pairs(&[
            ("q1.angle", "q1's angle"),
            (
                "offset_x_ground_m_a_m.angle",
                "offset_x_ground_m_a_m's angle"
            ),
            ("cyl.angle", "cyl's angle"),
            ("cyl.travel", "cyl's travel"),
            (
                "prismatic_c_s_ground_rail.travel",
                "prismatic_c_s_ground_rail's travel"
            ),
            (
                "in_line_P_ground_rail.travel",
                "in_line_P_ground_rail's travel"
            ),
            ("a.tip", "geom a.tip"),
        ])
    );
    // A joint's value needs both its arguments solved: the markers (or the point of `in_line`).
    let needs = |path: &str| -> Vec<String> {
        let o = m
            .outputs
            .iter()
            .find(|o| o.path == path)
            .expect("an output");
        (m.output_geoms(o).iter())
            .map(|&g| m.geoms[g].name.clone())
            .collect()
    };
    assert_eq!(needs("cyl.travel"), ["b.m", "a.tip"]);
    assert_eq!(needs("in_line_P_ground_rail.travel"), ["P", "ground.rail"]);
    assert_eq!(needs("a.tip"), ["a.tip"]);
}

#[test]
fn every_joint_value_in_2d() {
    let m = load(
        "space 2d;
fixed body ground { marker m = (0, 0) x (1, 0); marker rail = (0, -1) x (1, 0); }
body a { marker m = (0, 0) x (1, 0); }
body s at (2, -1) { marker m = (0, 0) x (1, 0); }
point P = (1, -1);
q1: revolute(a.m, ground.m);
drive: offset_x(ground.m, a.m) = 0.5;
slide: prismatic(s.m, ground.rail);
in_line(P, ground.rail);
output q1.angle, drive.angle, slide.travel, in_line_P_ground_rail.travel;
",
    );
    assert_eq!(
        outputs(&m),
        pairs(&[
            ("q1.angle", "q1's angle"),
            ("drive.angle", "drive's angle"),
            ("slide.travel", "slide's travel"),
            (
                "in_line_P_ground_rail.travel",
                "in_line_P_ground_rail's travel"
            ),
        ])
    );
}

/// A name may be a geom's and a label's at once (they have namespaces of their own): a path
/// that names a geom's member is that member; one that does not, with a joint value's word, is
/// the joint's value.
#[test]
fn a_geom_member_wins_over_a_joint_value_of_the_same_name() {
    let m = load(
        "space 2d;
fixed body ground { marker m = (0, 0) x (1, 0); }
body arm { marker m = (0, 0) x (1, 0); marker angle = (1, 0) x (1, 0); }
body q1 { marker m = (1, 0) x (1, 0); }
arm: revolute(arm.m, ground.m);
q1: revolute(q1.m, arm.angle);
output arm.angle, q1.angle;
",
    );
    assert_eq!(
        outputs(&m),
        pairs(&[("arm.angle", "geom arm.angle"), ("q1.angle", "q1's angle")])
    );
}

/// Constraints may come after the outputs that name them, as every name may; a value named
/// twice is one value.
#[test]
fn a_joint_value_may_be_named_before_its_constraint_and_twice() {
    let m = load(
        "space 2d;
output q1.angle;
fixed body ground { marker m = (0, 0) x (1, 0); }
body a { marker m = (0, 0) x (1, 0); }
q1: revolute(a.m, ground.m);
output q1.angle, a;
",
    );
    assert_eq!(m.outputs.len(), 3);
    let joints = m.joint_outputs();
    assert_eq!(joints.len(), 1);
    let (path, c, value) = joints[0];
    assert_eq!(
        (path, m.constraints[c].name.as_str(), value),
        ("q1.angle", "q1", JointValue::Angle)
    );
}
