//! `gcs check` end to end: the summary of every example, errors on stderr with a non-zero exit,
//! and a missing file.

mod support;

use expect_test::{expect, Expect};

/// Runs `gcs check` on a path (relative to the workspace root) and returns exit code, stdout
/// and stderr.
fn gcs_check(path: &str) -> (i32, String, String) {
    support::gcs(&["check", path])
}

fn check_example(name: &str, expected: Expect) {
    let (code, stdout, stderr) = gcs_check(&format!("examples/{name}.gcs"));
    assert_eq!(code, 0, "stderr: {stderr}");
    assert_eq!(stderr, "");
    expected.assert_eq(&stdout);
}

#[test]
fn fourbar() {
    check_example(
        "fourbar",
        expect![[r#"
            examples/fourbar.gcs: space 2d, 2 params, 6 geoms, 5 constraints

            geoms                    DOF  left
              A        fixed point     0     0
              D        fixed point     0     0
              X        fixed vector    0     0
              crank    body            3     0
              coupler  body            3     0
              rocker   body            3     0

            constraints                                                      removes
              coincident_crank_a_A          coincident(crank.a, A)                 2
              drive                         angle(X, crank.u) = theta              1
              coincident_crank_b_coupler_b  coincident(crank.b, coupler.b)         2
              elbow                         coincident(coupler.c, rocker.c)        2
              coincident_rocker_d_D         coincident(rocker.d, D)                2

            nominal DOF: 9 - 9 = 0
            analysis: well-constrained
              branch elbow: 2 roots, sketch takes 0: rocker.c to the left of the line from crank.b to D
        "#]],
    );
}

#[test]
fn brick() {
    check_example(
        "brick",
        expect![[r#"
            examples/brick.gcs: space 3d, 0 params, 4 geoms, 3 constraints

            geoms                 DOF  left
              g1     fixed point    0     0
              g2     fixed point    0     0
              g3     fixed point    0     0
              brick  body           6     0

            constraints                                         removes
              coincident_brick_b1_g1  coincident(brick.b1, g1)        3
              coincident_brick_b2_g2  coincident(brick.b2, g2)        3
              coincident_brick_b3_g3  coincident(brick.b3, g3)        3

            nominal DOF: 6 - 9 = -3
            analysis: well-constrained, with redundant constraints (3 redundant equations)
              implied in part: coincident_brick_b2_g2 (coincident(brick.b2, g2), line 12) is partly implied by coincident_brick_b1_g1 (with fixed g1 and fixed g2); that part is kept as a run-time check
              implied in part: coincident_brick_b3_g3 (coincident(brick.b3, g3), line 13) is partly implied by coincident_brick_b1_g1 and coincident_brick_b2_g2 (with fixed g1, fixed g2 and fixed g3); that part is kept as a run-time check
        "#]],
    );
}

#[test]
fn circle() {
    check_example(
        "circle",
        expect![[r#"
            examples/circle.gcs: space 2d, 0 params, 5 geoms, 5 constraints

            geoms                 DOF  left
              C     fixed circle    0     0
              L     fixed line      0     0
              P     fixed point     0     0
              Ls    segment         4     0
              G     circle          3     0

            constraints                                            removes
              length_Ls              length(Ls) = 3                      1
              coincident_Ls_start_P  coincident(Ls.start, P)             2
              meet                   coincident(Ls.end, G.center)        2
              tangent_L_G            tangent(L, G)                       1
              tangent_C_G            tangent(C, G)                       1

            nominal DOF: 7 - 7 = 0
            analysis: well-constrained
              branch meet: 4 roots, sketch takes 0: root 0 in increasing parameter along the parabola of centres of G
        "#]],
    );
}

#[test]
fn slider_crank() {
    check_example(
        "slider_crank",
        expect![[r#"
            examples/slider_crank.gcs: space 3d, 1 param, 4 geoms, 5 constraints

            geoms                 DOF  left
              ground  fixed body    0     0
              arm     body          6     0
              rod     body          6     0
              slider  body          6     0

            constraints                                                         removes
              revolute_arm_o_ground_o         revolute(arm.o, ground.o)               5
              offset_x_ground_o_arm_o         offset_x(ground.o, arm.o) = phi         3
              revolute_arm_tip_rod_a          revolute(arm.tip, rod.a)                5
              revolute_rod_b_slider_pin       revolute(rod.b, slider.pin)             5
              prismatic_slider_s_ground_rail  prismatic(slider.s, ground.rail)        5

            nominal DOF: 18 - 23 = -5
            analysis: well-constrained, with redundant constraints (5 redundant equations)
              implied in part: revolute_arm_o_ground_o (revolute(arm.o, ground.o), line 14) is partly implied by offset_x_ground_o_arm_o (with fixed ground); that part is kept as a run-time check
              implied in part: revolute_rod_b_slider_pin (revolute(rod.b, slider.pin), line 17) is partly implied by revolute_arm_o_ground_o, offset_x_ground_o_arm_o, revolute_arm_tip_rod_a and prismatic_slider_s_ground_rail (with fixed ground); that part is kept as a run-time check
              branch revolute_rod_b_slider_pin: 2 roots, sketch takes 1: the second crossing, along the line
        "#]],
    );
}

#[test]
fn points_planes() {
    check_example(
        "points_planes",
        expect![[r#"
            examples/points_planes.gcs: space 3d, 0 params, 6 geoms, 12 constraints

            geoms          DOF  left
              p1    point    3     0
              p2    point    3     0
              P3    plane    3     0
              P4    plane    3     0
              p5    point    3     0
              p6    point    3     0

            constraints                                       removes
              distance_p1_P3  distance(p1, P3) = 0                  1
              distance_p1_P4  distance(p1, P4) = -5                 1
              distance_p2_P4  distance(p2, P4) = -16/5              1
              distance_p2_P3  distance(p2, P3) = 4                  1
              distance_p1_p2  distance(p1, p2) = 5                  1
              distance_p1_p5  distance(p1, p5) = 2 * sqrt(3)        1
              distance_p5_P4  distance(p5, P4) = -11/5              1
              distance_p6_P4  distance(p6, P4) = -3/5               1
              distance_p2_p6  distance(p2, p6) = sqrt(19)           1
              distance_p5_P3  distance(p5, P3) = 2                  1
              distance_p6_P3  distance(p6, P3) = 1                  1
              distance_p5_p6  distance(p5, p6) = 3 * sqrt(2)        1

            nominal DOF: 18 - 12 = 6
            grounded: p1 (nothing is fixed: it is held at its sketch placement, and the rest is solved relative to it)
              and the direction from p1 to p2 is held as sketched (a point has no orientation of its own)
              and the plane through p1, p2 and p5 as sketched
            analysis: well-constrained up to its placement: 6 DOF held where the sketch has it (nothing is fixed)
              no closed form: iterates on P3_spin_angle until distance_p6_P4 closes
              branch distance_p1_p2: 2 roots, sketch takes 1: where the line from p1 through p2 as sketched leaves the sphere about p1 of radius 5, along the line (the other root is the same assembly turned as a whole)
              branch distance_p5_P3: 2 roots, sketch takes 1: the other crossing, second along that line (the other root is the same assembly turned as a whole)
              branch distance_p5_P4: 2 roots, sketch takes 1: turned clockwise from there
              branch distance_p6_P3: 2 roots, sketch takes 1: the other crossing, second along that line
        "#]],
    );
}

#[test]
fn redundant_constraints_name_what_implies_them() {
    let (code, stdout, stderr) = gcs_check("tests/models/redundant_checks.gcs");
    assert_eq!(code, 0, "stderr: {stderr}");
    assert_eq!(stderr, "");
    let redundant: Vec<&str> = (stdout.lines())
        .filter(|l| l.contains("redundant"))
        .collect();
    expect![[r#"
        tests/models/redundant_checks.gcs: space 2d, 9 params, 9 geoms, 17 constraints
        analysis: well-constrained, with redundant constraints (11 redundant equations)
          redundant: q_r (radius(R) = rr, line 45) is implied by fixed R; it is kept as a run-time check
          redundant: c_flat (horizontal(s), line 31) is implied by a_start, b_end and d_long (with fixed A and fixed B); it is kept as a run-time check
          redundant: f_up (vertical(u), line 34) is implied by a_start, b_end, d_long and e_up (with fixed A and fixed B); it is kept as a run-time check
          redundant: j_top (tangent(top, K), line 38) is implied by a_start, b_end, d_long, g_centre, h_p, i_p and k_radius (with fixed A, fixed B and fixed top); it is kept as a run-time check
          redundant: l_off (distance(P, R) = gap, line 40) is implied by a_start, b_end, d_long, h_p and i_p (with fixed A, fixed B and fixed R); it is kept as a run-time check
          redundant: m_r (tangent(R, K), line 41) is implied by a_start, b_end, d_long, g_centre, h_p, i_p and k_radius (with fixed A, fixed B and fixed R); it is kept as a run-time check
          redundant: n_ap (distance(P, A) = ap, line 42) is implied by a_start, b_end, d_long, h_p and i_p (with fixed A and fixed B); it is kept as a run-time check
          redundant: o_q (coincident(P, Q), line 43) is implied by a_start, b_end, d_long, h_p and i_p (with fixed A, fixed B and fixed Q); it is kept as a run-time check
          redundant: p_below (distance(P, top) = below, line 44) is implied by a_start, b_end, d_long, h_p and i_p (with fixed A, fixed B and fixed top); it is kept as a run-time check"#]]
    .assert_eq(&redundant.join("\n"));
}

#[test]
fn every_inconsistent_redundant_set_is_an_error_with_its_members() {
    // `a` conflicts with fixed A and B by 0.3; `d` asks C 2.25 from A where `b` put it 2 away.
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("tri.gcs");
    std::fs::write(
        &file,
        "space 2d;\nfixed point A = (0, 0);\nfixed point B = (3, 0);\npoint C = (1, 2);\n\
         a: distance(A, B) = 3.3;\nb: distance(A, C) = 2;\nc: distance(B, C) = 2.5;\n\
         d: distance(C, A) = 2.25;\n",
    )
    .expect("write");
    let (code, stdout, stderr) = gcs_check(file.to_str().expect("utf-8 path"));
    assert_eq!(code, 1);
    assert_eq!(stdout, "");
    let stderr = stderr.replace(file.to_str().expect("path"), "tri.gcs");
    expect![[r#"
        error: `a` conflicts with the constraints that imply it
          ┌─ tri.gcs:5:1
          │
        2 │ fixed point A = (0, 0);
          │             - fixed: part of what implies `a`
        3 │ fixed point B = (3, 0);
          │             - fixed: part of what implies `a`
        4 │ point C = (1, 2);
        5 │ a: distance(A, B) = 3.3;
          │ ^^^^^^^^^^^^^^^^^^^^^^^^ conflicting constraint: it is off by 0.3
          │
          = `a` is implied by fixed A and fixed B, and disagrees with them by 0.3: change or remove one of them
          = constraint `a` (distance(A, B) = 3.3) cannot be met: it is inconsistent with the constraints already met, by 0.2999999999999998

        error: `d` conflicts with the constraints that imply it
          ┌─ tri.gcs:8:1
          │
        2 │ fixed point A = (0, 0);
          │             - fixed: part of what implies `d`
        3 │ fixed point B = (3, 0);
          │             - fixed: part of what implies `d`
          ·
        6 │ b: distance(A, C) = 2;
          │ ---------------------- part of what implies `d`
        7 │ c: distance(B, C) = 2.5;
          │ ------------------------ part of what implies `d`
        8 │ d: distance(C, A) = 2.25;
          │ ^^^^^^^^^^^^^^^^^^^^^^^^^ conflicting constraint: it is off by 0.25
          │
          = `d` is implied by b and c (with fixed A and fixed B), and disagrees with them by 0.25: change or remove one of them
          = constraint `d` (distance(C, A) = 2.25) cannot be met: it is inconsistent with the constraints already met, by 0.25

        error: `tri.gcs` has 2 analysis errors
    "#]].assert_eq(&stderr);
}

#[test]
fn errors_go_to_stderr_with_exit_code_1() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("bad.gcs");
    std::fs::write(
        &file,
        "space 2d;\npoint P = (0, 0)\npoint Q = (1, 0);\ncoincident(P, R);\n",
    )
    .expect("write");
    let (code, stdout, stderr) = gcs_check(file.to_str().expect("utf-8 path"));
    assert_eq!(code, 1);
    assert_eq!(stdout, "");
    let stderr = stderr.replace(file.to_str().expect("path"), "bad.gcs");
    expect![[r#"
        error: expected `;`, found `point`
          ┌─ bad.gcs:2:17
          │
        2 │ point P = (0, 0)
          │                 ^ add `;` here
        3 │ point Q = (1, 0);
          │ ----- unexpected here

        error: could not load `bad.gcs` due to 1 previous error
    "#]]
    .assert_eq(&stderr);
}

#[test]
fn missing_file_is_a_clear_error() {
    let (code, stdout, stderr) = gcs_check("examples/no_such_model.gcs");
    assert_eq!(code, 2);
    assert_eq!(stdout, "");
    expect![[r#"
        error: cannot read `examples/no_such_model.gcs`: No such file or directory (os error 2)
    "#]]
    .assert_eq(&stderr);
}

/// Models with one token of 70,000 characters: a name, a label, a number literal (finite, and
/// one that overflows), in 2d (the analysis report) and in 3d (the nominal summary).
fn very_long_token_models() -> Vec<(&'static str, String)> {
    let name = format!("P{}", "x".repeat(70_000));
    let label = format!("L{}", "y".repeat(70_000));
    let one = format!("1.{}", "0".repeat(70_000));
    let huge = "9".repeat(70_000);
    vec![
        (
            "name",
            format!("space 2d;\nfixed point A = (0, 0);\npoint {name} = (1, 0);\ncoincident({name}, A);\n"),
        ),
        (
            "label",
            format!("space 2d;\nfixed point A = (0, 0);\npoint P = (1, 0);\n{label}: coincident(P, A);\n"),
        ),
        (
            "number",
            format!("space 2d;\nfixed point A = (0, 0);\npoint P = (1, 0);\nfixed vector X = (1, 0);\nsegment S = (0, 0) -> (1, 0);\ncoincident(S.start, A);\ncoincident(S.end, P);\nangle(X, S) = 0;\nlength(S) = {one};\n"),
        ),
        (
            "overflowing number",
            format!("space 2d;\nfixed point A = (0, 0);\npoint P = (1, 0);\ndistance(A, P) = {huge};\n"),
        ),
        (
            "name in 3d",
            format!("space 3d;\nfixed point A = (0, 0, 0);\npoint {name} = (1, 0, 0);\n{label}: coincident({name}, A);\n"),
        ),
        (
            "unknown names",
            format!("space 2d;\npoint {name} = (1, 0);\ncoincident({name}y, {name}z);\nparam {label} = {label}x;\n"),
        ),
    ]
}

#[test]
fn very_long_tokens_are_reported_never_a_panic() {
    let dir = tempfile::tempdir().expect("tempdir");
    for (what, text) in very_long_token_models() {
        let file = dir.path().join("long.gcs");
        std::fs::write(&file, &text).expect("write");
        let (code, stdout, stderr) = gcs_check(file.to_str().expect("utf-8 path"));
        assert!(
            code == 0 || code == 1,
            "{what}: exit {code}\nstderr: {}",
            &stderr[..stderr.len().min(2000)]
        );
        assert!(!stderr.contains("panicked"), "{what}");
        if code == 0 {
            // The table is there, and its other rows stay narrow.
            assert!(stdout.contains("nominal DOF"), "{what}");
            let short = stdout.lines().filter(|l| l.len() < 200).count();
            assert!(short >= 5, "{what}: {}", &stdout[..stdout.len().min(2000)]);
        }
    }
}

/// An under-constrained model checks with a warning and exit 0; `--deny under-constrained`
/// makes it an error (exit 1); a well-constrained one passes either way; an unknown warning
/// name is a usage error (exit 2).
#[test]
fn deny_under_constrained_makes_a_free_motion_an_error() {
    let run = |args: &[&str]| {
        let (code, _, stderr) = support::gcs(args);
        (code, stderr)
    };
    let (code, stderr) = run(&["check", "examples/fourbar_free.gcs"]);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains("warning: `crank` is under-constrained: default `crank_angle`"),
        "{stderr}"
    );
    let (code, stderr) = run(&[
        "check",
        "--deny",
        "under-constrained",
        "examples/fourbar_free.gcs",
    ]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("is under-constrained (mobility 1)"),
        "{stderr}"
    );
    let (code, stderr) = run(&[
        "check",
        "--deny",
        "under-constrained",
        "examples/fourbar.gcs",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let (code, stderr) = run(&["check", "--deny", "everything", "examples/fourbar.gcs"]);
    assert_eq!(code, 2, "{stderr}");
}
