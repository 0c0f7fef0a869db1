//! Golden tests of diagnostics: one per kind of mistake a user makes, rendered as the CLI
//! renders them (without colour). Regenerate with `UPDATE_EXPECT=1 cargo test -p gcs-lang`.

use expect_test::{expect, Expect};

/// Loads `src` and renders every diagnostic.
fn check(src: &str, expected: Expect) {
    let (source, model, diags) = gcs_lang::load("model.gcs", src.as_bytes());
    assert_eq!(
        model.is_none(),
        gcs_lang::diagnostic::has_errors(&diags),
        "a model is returned exactly when there is no error"
    );
    expected.assert_eq(&gcs_lang::diagnostic::render_plain(&source, &diags));
}

#[test]
fn missing_semicolon() {
    check(
        "space 2d;\nparam a = 1\nparam b = 2;\npoint P = (a, b);\n",
        expect![[r#"
            error: expected `;`, found `param`
              ┌─ model.gcs:2:12
              │
            2 │ param a = 1
              │            ^ add `;` here
            3 │ param b = 2;
              │ ----- unexpected here

        "#]],
    );
}

#[test]
fn missing_semicolon_at_end_of_file() {
    check(
        "space 2d;\npoint P = (0, 0)",
        expect![[r#"
            error: expected `;`, found end of file
              ┌─ model.gcs:2:17
              │
            2 │ point P = (0, 0)
              │                 ^ add `;` here

        "#]],
    );
}

#[test]
fn unclosed_brace() {
    check(
        "space 2d;\nbody B at (0, 0) {\n    point a = (0, 0);\n",
        expect![[r#"
            error: unclosed brace `{`
              ┌─ model.gcs:2:18
              │
            2 │ body B at (0, 0) {
              │                  ^ this `{` is never closed
              │
              = the file ends before the matching `}`

        "#]],
    );
}

#[test]
fn unexpected_closing_brace() {
    check(
        "space 2d;\npoint P = (0, 0);\n}\npoint Q = (1, 0);\n",
        expect![[r#"
            error: unexpected closing brace `}`
              ┌─ model.gcs:3:1
              │
            3 │ }
              │ ^ no `{` is open here

        "#]],
    );
}

#[test]
fn unbalanced_parenthesis() {
    check(
        "space 2d;\npoint P = (0, 0);\npoint Q = (1, 0);\ndistance(P, Q = 2;\n",
        expect![[r#"
            error: expected `,` or `)`, found `=`
              ┌─ model.gcs:4:15
              │
            4 │ distance(P, Q = 2;
              │               ^

        "#]],
    );
}

#[test]
fn malformed_number() {
    check(
        "space 2d;\npoint P = (1.2.3, 0);\n",
        expect![[r#"
            error: malformed number `1.2.3`
              ┌─ model.gcs:2:12
              │
            2 │ point P = (1.2.3, 0);
              │            ^^^^^ not a number
              │
              = numbers are written `12`, `1.5`, `1e-3` or `.5`

        "#]],
    );
}

#[test]
fn malformed_exponent() {
    check(
        "space 2d;\nparam r = 1e;\n",
        expect![[r#"
            error: unknown unit `e`
              ┌─ model.gcs:2:12
              │
            2 │ param r = 1e;
              │            ^ not a unit of the language
              │
              = the units are `deg` and `rad`, on angles; a length is a plain number, in the model's own unit

        "#]],
    );
}

#[test]
fn unterminated_comment() {
    check(
        "space 2d;\npoint P = (0, 0);\n/* the rest is\n   never closed\npoint Q = (1, 1);\n",
        expect![[r#"
            error: unterminated block comment
              ┌─ model.gcs:3:1
              │
            3 │ /* the rest is
              │ ^^ this comment is never closed
              │
              = close it with `*/`; block comments do not nest

        "#]],
    );
}

#[test]
fn unknown_name_with_suggestion() {
    check(
        "space 2d;\nfixed point Anchor = (0, 0);\npoint P = (1, 0);\ncoincident(P, Anchr);\n",
        expect![[r#"
            error: unknown name `Anchr`
              ┌─ model.gcs:4:15
              │
            4 │ coincident(P, Anchr);
              │               ^^^^^ no geom has this name
              │
              = did you mean `Anchor`?

        "#]],
    );
}

#[test]
fn unknown_member_with_suggestion() {
    check(
        "space 2d;\nfixed point A = (0, 0);\nbody crank { point tip = (1, 0); }\ncoincident(crank.tpi, A);\n",
        expect![[r#"
            error: `crank` has no member `tpi`
              ┌─ model.gcs:4:12
              │
            4 │ coincident(crank.tpi, A);
              │            ^^^^^^^^^ unknown member of a body
              │
              = did you mean `crank.tip`?

        "#]],
    );
}

#[test]
fn unknown_param_in_expression() {
    check(
        "space 2d;\nparam length = 2;\nsegment S = (0, 0) -> (lenght, 0);\n",
        expect![[r#"
            error: unknown name `lenght`
              ┌─ model.gcs:3:24
              │
            3 │ segment S = (0, 0) -> (lenght, 0);
              │                        ^^^^^^ no param has this name
              │
              = did you mean `length`?

        "#]],
    );
}

#[test]
fn unknown_constraint() {
    check(
        "space 2d;\npoint P = (0, 0);\npoint Q = (1, 0);\ncoincidnet(P, Q);\n",
        expect![[r#"
            error: unknown constraint `coincidnet`
              ┌─ model.gcs:4:1
              │
            4 │ coincidnet(P, Q);
              │ ^^^^^^^^^^ not a constraint of the language
              │
              = did you mean `coincident`?

        "#]],
    );
}

#[test]
fn unknown_function() {
    check(
        "space 2d;\nparam r = sqr(2);\ncircle C = center (0, 0) radius r;\n",
        expect![[r#"
            error: unknown function `sqr`
              ┌─ model.gcs:2:11
              │
            2 │ param r = sqr(2);
              │           ^^^ not a function of the language
              │
              = did you mean `sqrt`?

        "#]],
    );
}

#[test]
fn function_arity() {
    check(
        "space 2d;\nparam a = atan2(1);\nvector v = (cos(a), sin(a));\n",
        expect![[r#"
            error: `atan2` takes 2 arguments, found 1
              ┌─ model.gcs:2:11
              │
            2 │ param a = atan2(1);
              │           ^^^^^^^^ wrong number of arguments

        "#]],
    );
}

#[test]
fn duplicate_name() {
    check(
        "space 2d;\npoint P = (0, 0);\nline P = (0, 0) -> (1, 0);\n",
        expect![[r#"
            error: `P` is declared twice
              ┌─ model.gcs:3:6
              │
            2 │ point P = (0, 0);
              │       - first declared here
            3 │ line P = (0, 0) -> (1, 0);
              │      ^ second declaration
              │
              = params, geoms and bodies share one namespace

        "#]],
    );
}

#[test]
fn duplicate_name_param_and_geom() {
    check(
        "space 2d;\nparam r = 1;\ncircle r = center (0, 0) radius 1;\n",
        expect![[r#"
            error: `r` is declared twice
              ┌─ model.gcs:3:8
              │
            2 │ param r = 1;
              │       - first declared here
            3 │ circle r = center (0, 0) radius 1;
              │        ^ second declaration
              │
              = params, geoms and bodies share one namespace

        "#]],
    );
}

#[test]
fn duplicate_member() {
    check(
        "space 2d;\nbody B { point a = (0, 0); point a = (1, 0); }\n",
        expect![[r#"
            error: `B.a` is declared twice
              ┌─ model.gcs:2:34
              │
            2 │ body B { point a = (0, 0); point a = (1, 0); }
              │                -                 ^ second declaration
              │                │                  
              │                first declared here

        "#]],
    );
}

#[test]
fn duplicate_label() {
    check(
        "space 2d;\nfixed point A = (0, 0);\npoint P = (1, 0);\npoint Q = (2, 0);\nk: coincident(P, A);\nk: distance(Q, A) = 2;\n",
        expect![[r#"
            error: label `k` is used twice
              ┌─ model.gcs:6:1
              │
            5 │ k: coincident(P, A);
              │ - first used here
            6 │ k: distance(Q, A) = 2;
              │ ^ second use
              │
              = labels name branch variables and errors, so each must be unique

        "#]],
    );
}

#[test]
fn keyword_as_name() {
    check(
        "space 2d;\npoint param = (0, 0);\n",
        expect![[r#"
            error: `param` is a reserved word and cannot name a geom
              ┌─ model.gcs:2:7
              │
            2 │ point param = (0, 0);
              │       ^^^^^ reserved word
              │
              = reserved words: space param fixed point vector line segment circle plane body marker output deg rad pi

        "#]],
    );
}

#[test]
fn keyword_as_label() {
    check(
        "space 2d;\nfixed point A = (0, 0);\npoint P = (1, 0);\nfixed: coincident(P, A);\n",
        expect![[r#"
            error: `fixed` is a reserved word and cannot be a label
              ┌─ model.gcs:4:1
              │
            4 │ fixed: coincident(P, A);
              │ ^^^^^ reserved word
              │
              = choose another label

        "#]],
    );
}

#[test]
fn wrong_argument_kind() {
    check(
        "space 2d;\nfixed point A = (0, 0);\ncircle C = center (1, 0) radius 1;\ncoincident(A, C);\n",
        expect![[r#"
            error: expected a point, found a circle
              ┌─ model.gcs:4:15
              │
            4 │ coincident(A, C);
              │               ^ `C` is a circle
              │
              = `coincident` accepts a point and a point

        "#]],
    );
}

#[test]
fn body_where_a_point_is_expected() {
    check(
        "space 2d;\nfixed point A = (0, 0);\nbody crank { point a = (0, 0); }\ncoincident(crank, A);\n",
        expect![[r#"
            error: expected a point, found a body
              ┌─ model.gcs:4:12
              │
            4 │ coincident(crank, A);
              │            ^^^^^ `crank` is a body
              │
              = `coincident` accepts a point and a point
              = a body is not itself a point or a line: name one of its members, such as `crank.…`

        "#]],
    );
}

#[test]
fn no_form_fits_both_arguments() {
    check(
        "space 2d;\nline L = (0, 0) -> (1, 0);\nline M = (0, 1) -> (1, 1);\ndistance(L, M) = 1;\n",
        expect![[r#"
            error: `distance` does not relate a line `L` and a line `M`
              ┌─ model.gcs:4:10
              │
            4 │ distance(L, M) = 1;
              │          ^^^^
              │
              = `distance` accepts a point and a point; a point and a line; a point and a plane; a point and a circle; a line and a circle; a circle and a circle

        "#]],
    );
}

#[test]
fn wrong_arity() {
    check(
        "space 2d;\npoint P = (0, 0);\npoint Q = (1, 0);\npoint R = (2, 0);\ncoincident(P, Q, R);\n",
        expect![[r#"
            error: `coincident` takes 2 arguments, found 3
              ┌─ model.gcs:5:11
              │
            5 │ coincident(P, Q, R);
              │           ^^^^^^^^^ wrong number of arguments

        "#]],
    );
}

#[test]
fn expression_as_argument() {
    check(
        "space 2d;\npoint P = (0, 0);\ndistance(P, 3) = 1;\n",
        expect![[r#"
            error: expected the name of a geom, found an expression
              ┌─ model.gcs:3:13
              │
            3 │ distance(P, 3) = 1;
              │             ^ constraint arguments are geoms, members or sub-geoms

        "#]],
    );
}

#[test]
fn param_as_argument() {
    check(
        "space 2d;\nparam d = 1;\npoint P = (0, 0);\ndistance(P, d) = 1;\n",
        expect![[r#"
            error: `d` is a param, not a geom
              ┌─ model.gcs:4:13
              │
            4 │ distance(P, d) = 1;
              │             ^ params are numbers

        "#]],
    );
}

#[test]
fn missing_value() {
    check(
        "space 2d;\npoint P = (0, 0);\npoint Q = (1, 0);\ndistance(P, Q);\n",
        expect![[r#"
            error: `distance` needs a value
              ┌─ model.gcs:4:1
              │
            4 │ distance(P, Q);
              │ ^^^^^^^^^^^^^^^ missing `= a length`
              │
              = write `distance(a, b) = ...;`

        "#]],
    );
}

#[test]
fn unexpected_value() {
    check(
        "space 2d;\npoint P = (0, 0);\npoint Q = (1, 0);\ncoincident(P, Q) = 0;\n",
        expect![[r#"
            error: `coincident` takes no value
              ┌─ model.gcs:4:20
              │
            4 │ coincident(P, Q) = 0;
              │                    ^ remove `= ...`

        "#]],
    );
}

#[test]
fn constrained_to_itself() {
    check(
        "space 2d;\npoint P = (0, 0);\ncoincident(P, P);\n",
        expect![[r#"
            error: `P` is constrained to itself
              ┌─ model.gcs:3:11
              │
            3 │ coincident(P, P);
              │           ^^^^^^ both arguments name the same geom

        "#]],
    );
}

#[test]
fn equal_segment_and_circle() {
    check(
        "space 2d;\nsegment S = (0, 0) -> (1, 0);\ncircle C = center (3, 0) radius 1;\nequal(S, C);\n",
        expect![[r#"
            error: expected a segment, found a circle
              ┌─ model.gcs:4:10
              │
            4 │ equal(S, C);
              │          ^ `C` is a circle
              │
              = `equal` accepts a segment and a segment; a circle and a circle

        "#]],
    );
}

#[test]
fn equal_of_points() {
    check(
        "space 2d;\npoint P = (0, 0);\npoint Q = (1, 0);\nequal(P, Q);\n",
        expect![[r#"
            error: expected a segment or a circle, found a point
              ┌─ model.gcs:4:7
              │
            4 │ equal(P, Q);
              │       ^ `P` is a point
              │
              = `equal` accepts a segment and a segment; a circle and a circle

        "#]],
    );
}

#[test]
fn weld_of_points() {
    check(
        "space 3d;\npoint P = (0, 0, 0);\npoint Q = (1, 0, 0);\nweld(P, Q);\n",
        expect![[r#"
            error: expected a marker, found a point
              ┌─ model.gcs:4:6
              │
            4 │ weld(P, Q);
              │      ^ `P` is a point
              │
              = `weld` accepts a marker and a marker

        "#]],
    );
}

#[test]
fn weld_of_a_marker_and_a_point() {
    check(
        "space 2d;\nbody B { marker m = (0, 0) x (1, 0); }\npoint Q = (1, 0);\nweld(B.m, Q);\n",
        expect![[r#"
            error: expected a marker, found a point
              ┌─ model.gcs:4:11
              │
            4 │ weld(B.m, Q);
              │           ^ `Q` is a point
              │
              = `weld` accepts a marker and a marker

        "#]],
    );
}

#[test]
fn equal_with_a_value() {
    check(
        "space 2d;\nsegment S = (0, 0) -> (1, 0);\nsegment T = (0, 1) -> (1, 1);\nequal(S, T) = 2;\n",
        expect![[r#"
            error: `equal` takes no value
              ┌─ model.gcs:4:15
              │
            4 │ equal(S, T) = 2;
              │               ^ remove `= ...`

        "#]],
    );
}

#[test]
fn equal_to_itself() {
    check(
        "space 2d;\ncircle C = center (0, 0) radius 1;\nequal(C, C);\n",
        expect![[r#"
            error: `C` is constrained to itself
              ┌─ model.gcs:3:6
              │
            3 │ equal(C, C);
              │      ^^^^^^ both arguments name the same geom

        "#]],
    );
}

#[test]
fn midpoint_of_a_line() {
    check(
        "space 2d;\npoint M = (0, 0);\nline L = (0, 0) -> (1, 0);\nmidpoint(M, L);\n",
        expect![[r#"
            error: expected a segment, found a line
              ┌─ model.gcs:4:13
              │
            4 │ midpoint(M, L);
              │             ^ `L` is a line
              │
              = `midpoint` accepts a point and a segment

        "#]],
    );
}

#[test]
fn midpoint_arguments_swapped() {
    check(
        "space 2d;\npoint M = (0, 0);\nsegment S = (-1, 0) -> (1, 0);\nmidpoint(S, M);\n",
        expect![[r#"
            error: expected a point, found a segment
              ┌─ model.gcs:4:10
              │
            4 │ midpoint(S, M);
              │          ^ `S` is a segment
              │
              = `midpoint` accepts a point and a segment

        "#]],
    );
}

#[test]
fn midpoint_arity() {
    check(
        "space 2d;\npoint M = (0, 0);\nmidpoint(M);\n",
        expect![[r#"
            error: `midpoint` takes 2 arguments, found 1
              ┌─ model.gcs:3:9
              │
            3 │ midpoint(M);
              │         ^^^ wrong number of arguments

        "#]],
    );
}

#[test]
fn midpoint_at_an_end() {
    check(
        "space 2d;\nsegment S = (-1, 0) -> (1, 0);\nmidpoint(S.end, S);\n",
        expect![[r#"
            error: `S.end` is an end of `S`, not its midpoint
              ┌─ model.gcs:3:10
              │
            3 │ midpoint(S.end, S);
              │          ^^^^^ an end of `S`
              │
              = a segment's end is its midpoint only when its length is zero

        "#]],
    );
}

#[test]
fn symmetric_arity() {
    check(
        "space 2d;\npoint P = (0, 1);\npoint Q = (0, -1);\nsymmetric(P, Q);\n",
        expect![[r#"
            error: `symmetric` takes 3 arguments, found 2
              ┌─ model.gcs:4:10
              │
            4 │ symmetric(P, Q);
              │          ^^^^^^ wrong number of arguments

        "#]],
    );
}

#[test]
fn symmetric_across_a_circle() {
    check(
        "space 2d;\npoint P = (0, 1);\npoint Q = (0, -1);\ncircle C = center (0, 0) radius 1;\nsymmetric(P, Q, C);\n",
        expect![[r#"
            error: expected a line, found a circle
              ┌─ model.gcs:5:17
              │
            5 │ symmetric(P, Q, C);
              │                 ^ `C` is a circle
              │
              = in 2d, `symmetric` accepts a point, a point and a line

        "#]],
    );
}

#[test]
fn symmetric_with_a_value() {
    check(
        "space 2d;\npoint P = (0, 1);\npoint Q = (0, -1);\nline L = (-1, 0) -> (1, 0);\nsymmetric(P, Q, L) = 0;\n",
        expect![[r#"
            error: `symmetric` takes no value
              ┌─ model.gcs:5:22
              │
            5 │ symmetric(P, Q, L) = 0;
              │                      ^ remove `= ...`

        "#]],
    );
}

#[test]
fn symmetric_onto_itself() {
    check(
        "space 2d;\npoint P = (0, 1);\nline L = (-1, 0) -> (1, 0);\nsymmetric(P, P, L);\n",
        expect![[r#"
            error: `symmetric` mirrors `P` onto itself
              ┌─ model.gcs:4:10
              │
            4 │ symmetric(P, P, L);
              │          ^^^^^^^^^ the two points are the same geom
              │
              = a point is its own mirror image only on the mirror: to put it there, write `on(P, L);`

        "#]],
    );
}

#[test]
fn symmetric_across_a_line_in_3d() {
    check(
        "space 3d;\npoint P = (0, 1, 0);\npoint Q = (0, -1, 0);\nline L = (-1, 0, 0) -> (1, 0, 0);\nsymmetric(P, Q, L);\n",
        expect![[r#"
            error: expected a plane, found a line
              ┌─ model.gcs:5:17
              │
            5 │ symmetric(P, Q, L);
              │                 ^ `L` is a line
              │
              = in 3d, `symmetric` accepts a point, a point and a plane

        "#]],
    );
}

#[test]
fn symmetric_across_a_plane_in_2d() {
    check(
        "space 2d;\npoint P = (0, 1);\npoint Q = (0, -1);\nplane M = normal (0, 1, 0) offset 0;\nsymmetric(P, Q, M);\n",
        expect![[r#"
            error: a plane is not valid in 2d
              ┌─ model.gcs:4:1
              │
            4 │ plane M = normal (0, 1, 0) offset 0;
              │ ^^^^^ planes exist only in 3d
              │
              = in 2d every geom lies in the XY plane; use a line

        "#]],
    );
}

#[test]
fn horizontal_in_3d() {
    check(
        "space 3d;\nline L = (0, 0, 0) -> (1, 0, 0);\nhorizontal(L);\n",
        expect![[r#"
            error: `horizontal` is not valid in 3d
              ┌─ model.gcs:3:1
              │
            3 │ horizontal(L);
              │ ^^^^^^^^^^ only valid in 2d
              │
              = in 3d, constrain the direction with `angle` or `parallel` against a fixed vector

        "#]],
    );
}

#[test]
fn plane_in_2d() {
    check(
        "space 2d;\nplane Q = normal (0, 0, 1) offset 0;\n",
        expect![[r#"
            error: a plane is not valid in 2d
              ┌─ model.gcs:2:1
              │
            2 │ plane Q = normal (0, 0, 1) offset 0;
              │ ^^^^^ planes exist only in 3d
              │
              = in 2d every geom lies in the XY plane; use a line

        "#]],
    );
}

#[test]
fn parallel_z_in_2d() {
    check(
        "space 2d;\nbody A { marker m = (0, 0) x (1, 0); }\nbody B { marker m = (1, 0) x (1, 0); }\nparallel_z(A.m, B.m);\n",
        expect![[r#"
            error: `parallel_z` is not valid in 2d
              ┌─ model.gcs:4:1
              │
            4 │ parallel_z(A.m, B.m);
              │ ^^^^^^^^^^ only valid in 3d
              │
              = in 2d every marker's z axis is out of the plane, so this says nothing

        "#]],
    );
}

#[test]
fn missing_space_header() {
    check(
        "point P = (0, 0);\npoint Q = (1, 0);\n",
        expect![[r#"
            error: missing `space` header
              ┌─ model.gcs:1:1
              │
            1 │ point P = (0, 0);
              │ ^ expected `space 2d;` or `space 3d;` here
              │
              = every model says first which space it lives in

        "#]],
    );
}

#[test]
fn repeated_space_header() {
    check(
        "space 2d;\npoint P = (0, 0);\nspace 3d;\n",
        expect![[r#"
            error: repeated `space` header
              ┌─ model.gcs:3:1
              │
            1 │ space 2d;
              │ --------- the space is already set here
            2 │ point P = (0, 0);
            3 │ space 3d;
              │ ^^^^^^^^^ a second header
              │
              = a model has exactly one `space` header, first

        "#]],
    );
}

#[test]
fn header_not_first() {
    check(
        "point P = (0, 0);\nspace 2d;\n",
        expect![[r#"
            error: the `space` header must come first
              ┌─ model.gcs:2:1
              │
            1 │ point P = (0, 0);
              │ ----------------- this statement comes before it
            2 │ space 2d;
              │ ^^^^^^^^^

        "#]],
    );
}

#[test]
fn unknown_space() {
    check(
        "space 4d;\n",
        expect![[r#"
            error: unknown space `4d`
              ┌─ model.gcs:1:7
              │
            1 │ space 4d;
              │       ^^ expected `2d` or `3d`

        "#]],
    );
}

#[test]
fn wrong_coordinate_count_2d() {
    check(
        "space 2d;\npoint P = (0, 0, 0);\n",
        expect![[r#"
            error: expected 2 coordinates in 2d, found 3
              ┌─ model.gcs:2:11
              │
            2 │ point P = (0, 0, 0);
              │           ^^^^^^^^^ `P` needs 2 coordinates

        "#]],
    );
}

#[test]
fn wrong_coordinate_count_3d() {
    check(
        "space 3d;\nsegment S = (0, 0) -> (1, 0, 0);\n",
        expect![[r#"
            error: expected 3 coordinates in 3d, found 2
              ┌─ model.gcs:2:13
              │
            2 │ segment S = (0, 0) -> (1, 0, 0);
              │             ^^^^^^ the first point needs 3 coordinates

        "#]],
    );
}

#[test]
fn single_value_for_coordinates() {
    check(
        "space 2d;\npoint P = 3;\n",
        expect![[r#"
            error: expected coordinates (x, y), found a single value
              ┌─ model.gcs:2:11
              │
            2 │ point P = 3;
              │           ^ `P` needs 2 coordinates

        "#]],
    );
}

#[test]
fn malformed_circle() {
    check(
        "space 2d;\ncircle C = (0, 0) radius 1;\n",
        expect![[r#"
            error: malformed circle declaration
              ┌─ model.gcs:2:12
              │
            2 │ circle C = (0, 0) radius 1;
              │            ^^^^^^^^^^^^^^^ not the form of a circle
              │
              = write `circle C = center (x, y) radius r;`

        "#]],
    );
}

#[test]
fn circle_normal_in_2d() {
    check(
        "space 2d;\ncircle C = center (0, 0) radius 1 normal (0, 0, 1);\n",
        expect![[r#"
            error: `normal` is not part of circle declaration
              ┌─ model.gcs:2:35
              │
            2 │ circle C = center (0, 0) radius 1 normal (0, 0, 1);
              │                                   ^^^^^^ a 2d circle lies in the XY plane and takes no normal
              │
              = write `circle C = center (x, y) radius r;`

        "#]],
    );
}

#[test]
fn circle_without_normal_in_3d() {
    check(
        "space 3d;\ncircle C = center (0, 0, 0) radius 1;\n",
        expect![[r#"
            error: a 3d circle needs a normal
              ┌─ model.gcs:2:12
              │
            2 │ circle C = center (0, 0, 0) radius 1;
              │            ^^^^^^^^^^^^^^^^^^^^^^^^^ add `normal (a, b, c)`
              │
              = write `circle C = center (x, y, z) radius r normal (a, b, c);`

        "#]],
    );
}

#[test]
fn zero_length_vector() {
    check(
        "space 2d;\nfixed vector X = (0, 0);\n",
        expect![[r#"
            error: zero-length vector
              ┌─ model.gcs:2:18
              │
            2 │ fixed vector X = (0, 0);
              │                  ^^^^^^ all components are zero
              │
              = a direction needs a non-zero vector; it is normalised to unit length

        "#]],
    );
}

#[test]
fn zero_length_line() {
    check(
        "space 2d;\nline L = (1, 1) -> (1, 1);\n",
        expect![[r#"
            error: zero-length line: its two points coincide
              ┌─ model.gcs:2:10
              │
            2 │ line L = (1, 1) -> (1, 1);
              │          ^^^^^^^^^^^^^^^^ the direction is undefined
              │
              = sketch the line with two distinct points

        "#]],
    );
}

#[test]
fn negative_radius() {
    check(
        "space 2d;\ncircle C = center (0, 0) radius -2;\n",
        expect![[r#"
            error: negative radius
              ┌─ model.gcs:2:33
              │
            2 │ circle C = center (0, 0) radius -2;
              │                                 ^^ this is -2
              │
              = a radius is a length, zero or more

        "#]],
    );
}

#[test]
fn zero_normal() {
    check(
        "space 3d;\nplane Q = normal (0, 0, 0) offset 1;\n",
        expect![[r#"
            error: zero-length normal
              ┌─ model.gcs:2:18
              │
            2 │ plane Q = normal (0, 0, 0) offset 1;
              │                  ^^^^^^^^^ all components are zero
              │
              = a direction needs a non-zero vector; it is normalised to unit length

        "#]],
    );
}

#[test]
fn zero_vector_from_params() {
    check(
        "space 2d;\nparam a = 0;\nvector v = (a, a * 2);\n",
        expect![[r#"
            error: zero-length vector
              ┌─ model.gcs:3:12
              │
            3 │ vector v = (a, a * 2);
              │            ^^^^^^^^^^ all components are zero
              │
              = a direction needs a non-zero vector; it is normalised to unit length

        "#]],
    );
}

#[test]
fn non_orthogonal_marker_axes() {
    check(
        "space 3d;\nbody B { marker k = (0, 0, 0) z (0, 0, 1) x (1, 0, 1); }\n",
        expect![[r#"
            error: marker axes are not orthogonal
              ┌─ model.gcs:2:21
              │
            2 │ body B { marker k = (0, 0, 0) z (0, 0, 1) x (1, 0, 1); }
              │                     ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^ the z and x axes are 45 degrees apart
              │
              = a marker's z and x axes must be at right angles

        "#]],
    );
}

#[test]
fn angle_unit_on_a_length() {
    check(
        "space 2d;\npoint P = (0, 0);\npoint Q = (1, 0);\ndistance(P, Q) = 3 deg;\n",
        expect![[r#"
            error: expected a length, found an angle
              ┌─ model.gcs:4:18
              │
            4 │ distance(P, Q) = 3 deg;
              │                  ^^^^^
              │                    │
              │                    an angle unit on a length
              │
              = angle units (`deg`, `rad`) go only on angles

        "#]],
    );
}

#[test]
fn angle_unit_on_a_coordinate() {
    check(
        "space 2d;\npoint P = (0, 90 deg);\n",
        expect![[r#"
            error: expected a length, found an angle
              ┌─ model.gcs:2:15
              │
            2 │ point P = (0, 90 deg);
              │               ^^^^^^
              │                  │
              │                  an angle unit on a length
              │
              = angle units (`deg`, `rad`) go only on angles

        "#]],
    );
}

#[test]
fn angle_param_as_a_length() {
    check(
        "space 2d;\nparam theta = 30 deg;\npoint P = (0, 0);\npoint Q = (1, 0);\ndistance(P, Q) = 2 * theta;\n",
        expect![[r#"
            error: expected a length, found an angle
              ┌─ model.gcs:5:18
              │
            2 │ param theta = 30 deg;
              │       ----- `theta` holds an angle
              ·
            5 │ distance(P, Q) = 2 * theta;
              │                  ^^^^^^^^^ this is an angle
              │
              = a length cannot be computed from an angle param; declare a separate param

        "#]],
    );
}

#[test]
fn length_where_angle_required() {
    check(
        "space 2d;\nparam crank_len = 1.5;\nfixed vector X = (1, 0);\nbody crank { point b = (crank_len, 0); vector u = (1, 0); }\nangle(X, crank.u) = crank_len;\n",
        expect![[r#"
            error: expected an angle, found a length
              ┌─ model.gcs:5:21
              │
            4 │ body crank { point b = (crank_len, 0); vector u = (1, 0); }
              │                         --------- `crank_len` is used as a length here
            5 │ angle(X, crank.u) = crank_len;
              │                     ^^^^^^^^^ an angle is required here
              │
              = a param holds either lengths or angles; declare another param for the angle

        "#]],
    );
}

#[test]
fn unit_on_an_angle() {
    check(
        "space 2d;\nparam theta = 30 deg;\nbody B rotated (theta) deg { point a = (0, 0); }\n",
        expect![[r#"
            error: a unit on something that is already an angle
              ┌─ model.gcs:3:16
              │
            3 │ body B rotated (theta) deg { point a = (0, 0); }
              │                ^^^^^^^^^^^ this is already in radians
              │
              = `deg` and `rad` apply to plain numbers

        "#]],
    );
}

#[test]
fn division_by_zero() {
    check(
        "space 2d;\nparam d = 1 / 0;\npoint P = (d, 0);\n",
        expect![[r#"
            error: division by zero
              ┌─ model.gcs:2:15
              │
            2 │ param d = 1 / 0;
              │               ^ this is zero

        "#]],
    );
}

#[test]
fn division_by_zero_through_a_param() {
    check(
        "space 2d;\nparam n = 0;\npoint P = (1 / n, 0);\n",
        expect![[r#"
            error: division by zero
              ┌─ model.gcs:3:16
              │
            3 │ point P = (1 / n, 0);
              │                ^ this is zero
              │
              = with the params at their defaults

        "#]],
    );
}

#[test]
fn nan_from_sqrt() {
    check(
        "space 2d;\npoint P = (sqrt(-4), 0);\n",
        expect![[r#"
            error: square root of a negative number (-4)
              ┌─ model.gcs:2:12
              │
            2 │ point P = (sqrt(-4), 0);
              │            ^^^^^^^^

        "#]],
    );
}

#[test]
fn nan_from_acos() {
    check(
        "space 2d;\nparam a = acos(2);\nfixed vector X = (1, 0);\nvector v = (0, 1);\nangle(X, v) = a;\n",
        expect![[r#"
            error: `acos` of 2, outside [-1, 1]
              ┌─ model.gcs:2:11
              │
            2 │ param a = acos(2);
              │           ^^^^^^^

        "#]],
    );
}

#[test]
fn infinity_from_overflow() {
    check(
        "space 2d;\npoint P = (10 ^ 400, 0);\n",
        expect![[r#"
            error: this expression overflows to infinity
              ┌─ model.gcs:2:12
              │
            2 │ point P = (10 ^ 400, 0);
              │            ^^^^^^^^

        "#]],
    );
}

#[test]
fn recursive_param() {
    check(
        "space 2d;\nparam a = a + 1;\npoint P = (a, 0);\n",
        expect![[r#"
            error: param `a` is defined in terms of itself
              ┌─ model.gcs:2:7
              │
            2 │ param a = a + 1;
              │       ^ recursive definition
              │
              = a param's default may use other params, but not itself

        "#]],
    );
}

#[test]
fn mutually_recursive_params() {
    check(
        "space 2d;\nparam a = b + 1;\nparam b = 2 * a;\npoint P = (a, b);\n",
        expect![[r#"
            error: params `a`, `b` are defined in terms of each other
              ┌─ model.gcs:2:7
              │
            2 │ param a = b + 1;
              │       ^ recursive definition
            3 │ param b = 2 * a;
              │       - `b` depends on it
              │
              = a param's default may use other params, but not itself

        "#]],
    );
}

#[test]
fn undefined_param() {
    check(
        "space 2d;\nparam a = b + 1;\npoint P = (a, 0);\n",
        expect![[r#"
            error: unknown name `b`
              ┌─ model.gcs:2:11
              │
            2 │ param a = b + 1;
              │           ^ no param has this name

        "#]],
    );
}

#[test]
fn output_of_unknown_geom() {
    check(
        "space 2d;\npoint P = (0, 0);\noutput Q;\n",
        expect![[r#"
            error: unknown name `Q`
              ┌─ model.gcs:3:8
              │
            3 │ output Q;
              │        ^ no geom or member has this name

        "#]],
    );
}

#[test]
fn output_of_unknown_member() {
    check(
        "space 2d;\nbody crank { point a = (0, 0); }\noutput crank.b;\n",
        expect![[r#"
            error: `crank` has no member `b`
              ┌─ model.gcs:3:8
              │
            3 │ output crank.b;
              │        ^^^^^^^ unknown member of a body
              │
              = `crank` has `crank.a`

        "#]],
    );
}

#[test]
fn fixed_on_a_param() {
    check(
        "space 2d;\nfixed param a = 1;\npoint P = (a, 0);\n",
        expect![[r#"
            error: `fixed` means nothing here
              ┌─ model.gcs:2:1
              │
            2 │ fixed param a = 1;
              │ ^^^^^
              │
              = a param is a run-time input; it cannot be fixed

        "#]],
    );
}

#[test]
fn fixed_on_a_member() {
    check(
        "space 2d;\nbody B { fixed point a = (0, 0); }\n",
        expect![[r#"
            error: `fixed` means nothing here
              ┌─ model.gcs:2:10
              │
            2 │ body B { fixed point a = (0, 0); }
              │          ^^^^^
              │
              = members move with their body; write `fixed` before `body` to ground the body

        "#]],
    );
}

#[test]
fn fixed_on_a_constraint() {
    check(
        "space 2d;\nfixed point A = (0, 0);\npoint P = (1, 0);\nfixed coincident(P, A);\n",
        expect![[r#"
            error: `fixed` means nothing here
              ┌─ model.gcs:4:1
              │
            4 │ fixed coincident(P, A);
              │ ^^^^^
              │
              = constraints are not grounded; `fixed` goes before a geom or body declaration

        "#]],
    );
}

#[test]
fn marker_outside_a_body() {
    check(
        "space 2d;\nmarker k = (0, 0) x (1, 0);\n",
        expect![[r#"
            error: a marker belongs to a body
              ┌─ model.gcs:2:1
              │
            2 │ marker k = (0, 0) x (1, 0);
              │ ^^^^^^ marker outside a body
              │
              = declare it inside a body: `body B { marker k = (0, 0) x (1, 0); }`

        "#]],
    );
}

#[test]
fn line_inside_a_body() {
    check(
        "space 2d;\nbody B { line L = (0, 0) -> (1, 0); }\n",
        expect![[r#"
            error: a body cannot hold a line
              ┌─ model.gcs:2:10
              │
            2 │ body B { line L = (0, 0) -> (1, 0); }
              │          ^^^^ not a body member
              │
              = body members are points, vectors and markers; declare other geoms at top level and constrain them to the body

        "#]],
    );
}

#[test]
fn marker_z_in_2d() {
    check(
        "space 2d;\nbody B { marker k = (0, 0) z (0, 0) x (1, 0); }\n",
        expect![[r#"
            error: `z` is not part of marker declaration
              ┌─ model.gcs:2:28
              │
            2 │ body B { marker k = (0, 0) z (0, 0) x (1, 0); }
              │                            ^ in 2d a marker has only its x axis; its z axis is out of the plane
              │
              = write `marker k = (x, y) x (a, b);`

        "#]],
    );
}

#[test]
fn about_in_2d() {
    check(
        "space 2d;\nbody B rotated 10 deg about (0, 0, 1) { point a = (0, 0); }\n",
        expect![[r#"
            error: `about` is not valid in 2d
              ┌─ model.gcs:2:29
              │
            2 │ body B rotated 10 deg about (0, 0, 1) { point a = (0, 0); }
              │                             ^^^^^^^^^ a 2d body rotates about the z axis
              │
              = drop `about (...)`

        "#]],
    );
}

#[test]
fn dimension_as_argument() {
    check(
        "space 2d;\ncircle G = center (0, 0) radius 1;\npoint P = (0, 0);\ndistance(P, G.radius) = 1;\n",
        expect![[r#"
            error: `G.radius` is a dimension, not a geom
              ┌─ model.gcs:4:13
              │
            4 │ distance(P, G.radius) = 1;
              │             ^^^^^^^^ dimensions are not geoms
              │
              = constrain it with `radius(G) = ...`

        "#]],
    );
}

#[test]
fn line_point_is_output_only() {
    check(
        "space 2d;\nfixed point A = (0, 0);\nline L = (0, 1) -> (1, 1);\ncoincident(L.point, A);\n",
        expect![[r#"
            error: `L.point` is an output, not a constraint argument
              ┌─ model.gcs:4:12
              │
            4 │ coincident(L.point, A);
              │            ^^^^^^^ the foot of the perpendicular from the line's first sketch point
              │
              = to put a point on the line, write `on(P, L);`

        "#]],
    );
}

#[test]
fn geom_in_expression() {
    check(
        "space 2d;\npoint P = (0, 0);\npoint Q = (P, 0);\n",
        expect![[r#"
            error: `P` is a point, not a number
              ┌─ model.gcs:3:12
              │
            3 │ point Q = (P, 0);
              │            ^ expressions may use params, numbers and `pi`
              │
              = constrain geoms with constraints, such as `distance(a, b) = d;`

        "#]],
    );
}

#[test]
fn offset_z_of_zero() {
    check(
        "space 3d;\nbody A { marker m = (0, 0, 0) z (0, 0, 1) x (1, 0, 0); }\nbody B { marker m = (1, 0, 0) z (0, 0, 1) x (1, 0, 0); }\noffset_z(A.m, B.m) = 0;\n",
        expect![[r#"
            error: `offset_z` needs a non-zero angle
              ┌─ model.gcs:4:22
              │
            4 │ offset_z(A.m, B.m) = 0;
              │                      ^
              │
              = for parallel z axes, use `parallel_z(m1, m2);`

        "#]],
    );
}

#[test]
fn empty_file() {
    check(
        "",
        expect![[r#"
            error: empty model
              ┌─ model.gcs:1:1
              │
            1 │ 
              │ ^
              │
              = a model starts with `space 2d;` or `space 3d;`, then declares geoms and constraints

        "#]],
    );
}

#[test]
fn only_comments() {
    check(
        "// nothing here\n/* at all */\n",
        expect![[r#"
            error: empty model
              ┌─ model.gcs:3:1
              │
            3 │ 
              │ ^
              │
              = a model starts with `space 2d;` or `space 3d;`, then declares geoms and constraints

        "#]],
    );
}

#[test]
fn several_errors_at_once() {
    check(
        "space 2d;\npoint P = (0, 0, 0);\npoint P = (1, 1);\ncoincident(P, Q);\nangle(P, P) = 1;\n",
        expect![[r#"
            error: expected 2 coordinates in 2d, found 3
              ┌─ model.gcs:2:11
              │
            2 │ point P = (0, 0, 0);
              │           ^^^^^^^^^ `P` needs 2 coordinates

            error: `P` is declared twice
              ┌─ model.gcs:3:7
              │
            2 │ point P = (0, 0, 0);
              │       - first declared here
            3 │ point P = (1, 1);
              │       ^ second declaration
              │
              = params, geoms and bodies share one namespace

            error: unknown name `Q`
              ┌─ model.gcs:4:15
              │
            4 │ coincident(P, Q);
              │               ^ no geom has this name

            error: expected a vector, line, segment or plane, found a point
              ┌─ model.gcs:5:7
              │
            5 │ angle(P, P) = 1;
              │       ^ `P` is a point
              │
              = `angle` accepts a vector, line, segment or plane and a vector, line, segment or plane

        "#]],
    );
}

#[test]
fn unused_param_is_a_warning() {
    check(
        "space 2d;\nparam unused = 3;\npoint P = (0, 0);\n",
        expect![[r#"
            warning: param `unused` is never used
              ┌─ model.gcs:2:7
              │
            2 │ param unused = 3;
              │       ^^^^^^ unused
              │
              = it still becomes a field of the solver's params

        "#]],
    );
}

#[test]
fn not_utf8() {
    let (source, model, diags) = gcs_lang::load("model.gcs", b"space 2d;\npoint P = (0, \xff);\n");
    assert!(model.is_none());
    expect![[r#"
        error: file is not valid UTF-8
          ┌─ model.gcs:2:15
          │
        2 │ point P = (0, �);
          │               ^ invalid byte at offset 24
          │
          = gcs reads models as UTF-8 text

    "#]]
    .assert_eq(&gcs_lang::diagnostic::render_plain(&source, &diags));
}

/// Loads bytes (not text) and renders every diagnostic.
fn check_bytes(src: &[u8], expected: Expect) {
    let (source, model, diags) = gcs_lang::load("model.gcs", src);
    assert_eq!(model.is_none(), gcs_lang::diagnostic::has_errors(&diags));
    expected.assert_eq(&gcs_lang::diagnostic::render_plain(&source, &diags));
}

#[test]
fn misspelt_keyword_gets_a_suggestion() {
    check(
        "space 2d;\npointt B = (0, 0);\nfixedd point C = (1, 0);\n",
        expect![[r#"
            error: unknown keyword `pointt`
              ┌─ model.gcs:2:1
              │
            2 │ pointt B = (0, 0);
              │ ^^^^^^ did you mean `point`?
              │
              = a statement starts with `space`, `param`, a geom kind (`point`, `vector`, `line`, `segment`, `circle`, `plane`, `marker`), `body`, `fixed`, `output`, a label, or a constraint

            error: unknown keyword `fixedd`
              ┌─ model.gcs:3:1
              │
            3 │ fixedd point C = (1, 0);
              │ ^^^^^^ did you mean `fixed`?
              │
              = a statement starts with `space`, `param`, a geom kind (`point`, `vector`, `line`, `segment`, `circle`, `plane`, `marker`), `body`, `fixed`, `output`, a label, or a constraint

        "#]],
    );
}

#[test]
fn non_ascii_name_points_at_the_character() {
    check(
        "space 2d;\npoint Bé = (0, 0);\nparam w = 2; // café is fine in a comment\npoint C = (w, 0) ; /* ß */\n",
        expect![[r#"
            error: `é` cannot be part of a name: names are ASCII
              ┌─ model.gcs:2:8
              │
            2 │ point Bé = (0, 0);
              │        ^ U+00E9
              │
              = names are ASCII letters, digits and `_`, starting with a letter or `_`

        "#]],
    );
    check(
        "space 2d;\npoint B = (0, 0) ± 1;\n",
        expect![[r#"
        error: unexpected character `±`: gcs models are ASCII outside comments
          ┌─ model.gcs:2:18
          │
        2 │ point B = (0, 0) ± 1;
          │                  ^ U+00B1
          │
          = other characters may stand only in comments

    "#]],
    );
}

#[test]
fn unknown_unit_lists_the_units() {
    check(
        "space 2d;\nparam w = 25 mm;\nparam t = 1.5in;\npoint B = (w, t);\n",
        expect![[r#"
            error: unknown unit `mm`
              ┌─ model.gcs:2:14
              │
            2 │ param w = 25 mm;
              │              ^^ not a unit of the language
              │
              = the units are `deg` and `rad`, on angles; a length is a plain number, in the model's own unit

            error: unknown unit `in`
              ┌─ model.gcs:3:14
              │
            3 │ param t = 1.5in;
              │              ^^ not a unit of the language
              │
              = the units are `deg` and `rad`, on angles; a length is a plain number, in the model's own unit

        "#]],
    );
}

#[test]
fn a_byte_order_mark_is_skipped() {
    check_bytes(
        b"\xef\xbb\xbfspace 2d;\nfixed point B = (0, 0);\n",
        expect![[r#""#]],
    );
    // Only at the start: elsewhere it is a character like any other.
    check_bytes(
        b"space 2d;\n\xef\xbb\xbffixed point B = (0, 0);\n",
        expect![[r#"
            error: unexpected character `﻿`: gcs models are ASCII outside comments
              ┌─ model.gcs:2:1
              │
            2 │ ﻿fixed point B = (0, 0);
              │  U+FEFF
              │
              = other characters may stand only in comments

        "#]],
    );
}

#[test]
fn a_binary_file_is_not_echoed() {
    let mut bytes = b"\x7fELF\x02\x01\x01\x00\x00\x00".to_vec();
    bytes.extend((0..4000u32).map(|i| (i * 7919 % 251) as u8));
    check_bytes(
        &bytes,
        expect![[r#"
        error: this is a binary file, not a gcs model
          ┌─ model.gcs:1:1
          │
        1 │ 
          │ ^ a NUL byte at offset 7
          │
          = gcs reads models as UTF-8 text

    "#]],
    );
    // A long line with a stray byte, no NUL: not shown either.
    let mut long = b"space 2d; // ".to_vec();
    long.extend(std::iter::repeat_n(b'x', 1000));
    long.push(0xff);
    check_bytes(
        &long,
        expect![[r#"
        error: this is a binary file, not a gcs model
          ┌─ model.gcs:1:1
          │
        1 │ 
          │ ^ an invalid UTF-8 byte at offset 1013, on a line of 1014 bytes
          │
          = gcs reads models as UTF-8 text

    "#]],
    );
    // A short line with a stray byte (Latin-1 in a comment) is shown.
    check_bytes(
        b"space 2d;\n// caf\xe9\n",
        expect![[r#"
        error: file is not valid UTF-8
          ┌─ model.gcs:2:7
          │
        2 │ // caf�
          │       ^ invalid byte at offset 16
          │
          = gcs reads models as UTF-8 text

    "#]],
    );
}

/// A 3d model for the joint-value tests: `q1` a revolute, `prismatic_b_m_ground_rail` an
/// unlabelled prismatic, `fix` a coincidence.
const JOINTS: &str = "space 3d;
fixed body ground { marker m = (0, 0, 0) z (0, 0, 1) x (1, 0, 0); marker rail = (0, 0, 0) z (1, 0, 0) x (0, 1, 0); }
body a { marker m = (0, 0, 0) z (0, 0, 1) x (1, 0, 0); marker s = (0, 0, 0) z (1, 0, 0) x (0, 1, 0); }
body b { marker m = (1, 0, 0) z (0, 0, 1) x (1, 0, 0); }
q1: revolute(a.m, ground.m);
prismatic(b.m, ground.rail);
fix: coincident(b.m, a.s);
";

#[test]
fn joint_value_of_a_constraint_that_is_not_that_joint() {
    check(
        &format!("{JOINTS}output prismatic_b_m_ground_rail.angle;\n"),
        expect![[r#"
            error: `prismatic_b_m_ground_rail` is a `prismatic` constraint, which has no angle
              ┌─ model.gcs:8:8
              │
            6 │ prismatic(b.m, ground.rail);
              │ ---------------------------- `prismatic_b_m_ground_rail` is this `prismatic` constraint
            7 │ fix: coincident(b.m, a.s);
            8 │ output prismatic_b_m_ground_rail.angle;
              │        ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^ `.angle` is the value of a `revolute`, `cylindrical` or `offset_x` joint
              │
              = its joint has `prismatic_b_m_ground_rail.travel`

        "#]],
    );
    check(
        &format!("{JOINTS}output fix.travel;\n"),
        expect![[r#"
        error: `fix` is a `coincident` constraint, which has no travel
          ┌─ model.gcs:8:8
          │
        7 │ fix: coincident(b.m, a.s);
          │ -------------------------- `fix` is this `coincident` constraint
        8 │ output fix.travel;
          │        ^^^^^^^^^^ `.travel` is the value of a `prismatic`, `cylindrical` or `in_line` joint

    "#]],
    );
}

#[test]
fn joint_value_of_an_unknown_constraint() {
    check(
        &format!("{JOINTS}output q2.angle;\n"),
        expect![[r#"
        error: unknown constraint `q2`
          ┌─ model.gcs:8:8
          │
        8 │ output q2.angle;
          │        ^^ no constraint or geom has this name
          │
          = `.angle` names the value of a joint by its constraint's name: its label, or the name `gcs check` prints

    "#]],
    );
    check(
        &format!("{JOINTS}output prismatic_b_m_ground.travel;\n"),
        expect![[r#"
            error: unknown constraint `prismatic_b_m_ground`
              ┌─ model.gcs:8:8
              │
            8 │ output prismatic_b_m_ground.travel;
              │        ^^^^^^^^^^^^^^^^^^^^ no constraint or geom has this name
              │
              = `.travel` names the value of a joint by its constraint's name: its label, or the name `gcs check` prints
              = did you mean `prismatic_b_m_ground_rail.travel`?

        "#]],
    );
}

#[test]
fn unknown_joint_value() {
    check(
        &format!("{JOINTS}output q1.angel;\n"),
        expect![[r#"
        error: unknown joint value `angel`
          ┌─ model.gcs:8:11
          │
        5 │ q1: revolute(a.m, ground.m);
          │ ---------------------------- `q1` is this `revolute` constraint
          ·
        8 │ output q1.angel;
          │           ^^^^^ a joint's value is `.angle` or `.travel`
          │
          = did you mean `q1.angle`?

    "#]],
    );
    check(
        &format!("{JOINTS}output q1.turn;\n"),
        expect![[r#"
        error: unknown joint value `turn`
          ┌─ model.gcs:8:11
          │
        5 │ q1: revolute(a.m, ground.m);
          │ ---------------------------- `q1` is this `revolute` constraint
          ·
        8 │ output q1.turn;
          │           ^^^^ a joint's value is `.angle` or `.travel`
          │
          = its joint has `q1.angle`

    "#]],
    );
    check(
        &format!("{JOINTS}output fix.x;\n"),
        expect![[r#"
        error: unknown joint value `x`
          ┌─ model.gcs:8:12
          │
        7 │ fix: coincident(b.m, a.s);
          │ -------------------------- `fix` is this `coincident` constraint
        8 │ output fix.x;
          │            ^ a joint's value is `.angle` or `.travel`
          │
          = a `coincident` constraint is not a joint with a value to output

    "#]],
    );
}

#[test]
fn joint_value_is_output_only() {
    check(
        &format!("{JOINTS}coincident(q1.angle, ground.m);\n"),
        expect![[r#"
            error: `q1.angle` is the angle of joint `q1`: an output, not a constraint argument
              ┌─ model.gcs:8:12
              │
            8 │ coincident(q1.angle, ground.m);
              │            ^^^^^^^^ constraint arguments are geoms, members or sub-geoms
              │
              = a joint's value is measured on the solved model: name it in `output q1.angle;`

        "#]],
    );
    check(
        &format!(
            "{JOINTS}param p = prismatic_b_m_ground_rail.travel;\noffset_x(a.m, ground.m) = p;\n"
        ),
        expect![[r#"
            error: `prismatic_b_m_ground_rail.travel` is the travel of joint `prismatic_b_m_ground_rail`: an output, not a number
              ┌─ model.gcs:8:11
              │
            8 │ param p = prismatic_b_m_ground_rail.travel;
              │           ^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^^ expressions may use params, numbers and `pi`
              │
              = a joint's value is measured on the solved model: name it in `output prismatic_b_m_ground_rail.travel;`

        "#]],
    );
    // A name that is no constraint is reported as before.
    check(
        &format!("{JOINTS}coincident(q9.angle, ground.m);\n"),
        expect![[r#"
            error: unknown name `q9.angle`
              ┌─ model.gcs:8:12
              │
            8 │ coincident(q9.angle, ground.m);
              │            ^^^^^^^^ no geom has this name

        "#]],
    );
}
