//! Names of the model that would become one identifier of a generated solver's public API are
//! an error naming both: a param `k` and a param `K`, two constraints whose names differ in
//! case (their branch variables), a geom and a member whose dotted name snake-cases the same
//! (their accessors), and a geom named like `Solution::points`. Without it the second took a
//! `_2` suffix, and `Branches { on_p_a_b_line: 1, .. }` set the other constraint's branch.

use expect_test::{expect, Expect};

fn check(text: &str, expected: Expect) {
    let c = gcs_compiler::compile("names.gcs", text.as_bytes()).expect("compiles");
    let errors: Vec<_> = c.diagnostics.into_iter().filter(|d| d.is_error()).collect();
    expected.assert_eq(&gcs_lang::diagnostic::render_plain(&c.source, &errors));
}

#[test]
fn params_that_differ_in_case() {
    check(
        "space 2d;\nparam k = 1;\nparam K = 2;\nfixed point A = (0, 0);\npoint P = (1, 0);\n\
         fixed line L = (0, 0) -> (1, 0);\ndistance(A, P) = k + K;\non(P, L);\n",
        expect![[r#"
            error: the params `k` and `K` both become `k`, a field of `Params`, in the generated solver
              ┌─ names.gcs:3:7
              │
            2 │ param k = 1;
              │       - `k` becomes `k` too
            3 │ param K = 2;
              │       ^ `K` becomes `k`
              │
              = a name becomes its snake case in generated code (lower case, `_` for anything else): rename one so that each is its own identifier

        "#]],
    );
}

#[test]
fn branch_variables_of_constraints_that_differ_in_case() {
    check(
        "space 2d;\nfixed point A = (0, 0);\nfixed point B = (4, 0);\npoint P = (2, 1);\n\
         point Q = (2, -1);\nfixed line L = (0, 1) -> (1, 1);\n\
         A1: distance(A, P) = 3;\nPq: distance(B, P) = 3;\n\
         a1: distance(A, Q) = 3;\npq: distance(B, Q) = 3;\n",
        expect![[r#"
            error: the branch variables `Pq` and `pq` both become `pq`, a field of `Branches`, in the generated solver
               ┌─ names.gcs:10:1
               │
             8 │ Pq: distance(B, P) = 3;
               │ ----------------------- `Pq` becomes `pq` too
             9 │ a1: distance(A, Q) = 3;
            10 │ pq: distance(B, Q) = 3;
               │ ^^^^^^^^^^^^^^^^^^^^^^^ `pq` becomes `pq`
               │
               = a name becomes its snake case in generated code (lower case, `_` for anything else): rename one so that each is its own identifier

        "#]],
    );
}

#[test]
fn an_accessor_of_a_member_and_one_of_a_geom() {
    check(
        "space 2d;\nfixed point A = (0, 0);\nfixed point crank_b = (1, 0);\n\
         body crank { point a = (0, 0); point b = (1, 0); }\n\
         coincident(crank.a, A);\ncoincident(crank.b, crank_b);\n",
        expect![[r#"
            error: the values `crank_b` and `crank.b` both become `crank_b`, an accessor of `Solution`, in the generated solver
              ┌─ names.gcs:4:38
              │
            3 │ fixed point crank_b = (1, 0);
              │             ------- `crank_b` becomes `crank_b` too
            4 │ body crank { point a = (0, 0); point b = (1, 0); }
              │                                      ^ `crank.b` becomes `crank_b`
              │
              = a name becomes its snake case in generated code (lower case, `_` for anything else): rename one so that each is its own identifier

        "#]],
    );
}

#[test]
fn a_point_named_like_the_api() {
    check(
        "space 2d;\nfixed point points = (0, 0);\npoint P = (1, 1);\ncoincident(P, points);\n",
        expect![[r#"
            error: the value `points` becomes `points`, which the generated solver's API already has
              ┌─ names.gcs:2:13
              │
            2 │ fixed point points = (0, 0);
              │             ^^^^^^ `points` becomes `points`
              │
              = a name becomes its snake case in generated code (lower case, `_` for anything else): rename one so that each is its own identifier

        "#]],
    );
}

#[test]
fn keywords_and_repeats_are_no_clash() {
    check(
        "space 2d;\nparam Self = 1;\nparam type = 2;\nfixed point A = (0, 0);\npoint P = (1, 1);\n\
         fixed line L = (0, 0) -> (1, 0);\nmatch: distance(A, P) = Self + type;\non(P, L);\n",
        expect![[r#""#]],
    );
}
