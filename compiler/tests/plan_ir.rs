//! The parts of the Plan IR the analysis does not emit yet, through every back end: a default
//! parameter that fixes a free motion, and an iterated region whose `Close` step measures the
//! constraint the default displaces. The plan is written by hand, as the defaults' analysis
//! will write it: `P` is at distance 5 from `A` (a circle, one DOF), its angle about `A` is a
//! default, and `distance(P, B) = 4` closes the region.
//!
//! `GCS_PLAN_IR_OUT=FILE` writes the generated module, to build it by hand (it builds under
//! `deny(warnings)` and solves with the closing angle as its default).

use gcs_compiler::plan::{
    BranchId, BranchVar, DefaultId, DefaultVar, Iteration, Meet, Op, Plan, PlanarOp, Reg, Step, Ty,
};
use gcs_lang::Model;
use gcs_runtime::error::ErrorKind;

const MODEL: &str = "space 2d;\n\
    fixed point A = (0, 0);\n\
    fixed point B = (7, 0);\n\
    point P = (3, 1);\n\
    reach: distance(A, P) = 5;\n\
    close: distance(P, B) = 4;\n";

fn model() -> Model {
    let (_, model, diags) = gcs_lang::load("ir.gcs", MODEL.as_bytes());
    model.unwrap_or_else(|| panic!("{diags:?}"))
}

/// The hand-written plan: `P` on the circle of radius 5 about `A`, where the ray at the
/// default angle crosses it, then the distance to `B` less 4 closes the region.
fn plan(model: &Model) -> Plan {
    let geom = |n: &str| model.geom_named(n).expect("geom");
    let constraint = |n: &str| {
        model
            .constraints
            .iter()
            .find(|(_, c)| c.name == n)
            .expect("constraint")
            .0
    };
    let (a, b, p) = (geom("A"), geom("B"), geom("P"));
    let (reach, close) = (constraint("reach"), constraint("close"));
    let five = model.constraints[reach].value.expect("a value");
    let four = model.constraints[close].value.expect("a value");
    let mut steps = Vec::new();
    let mut def = |op: Op, ty: Ty| {
        steps.push(Step {
            op,
            out: Some((Reg(steps.len() as u32), ty)),
            satisfies: vec![],
            works_for: None,
            explain: String::new(),
        });
    };
    def(Op::PointOf(a), Ty::Point); // r0
    def(Op::Expr(five), Ty::Scalar); // r1
    def(
        Op::Planar(PlanarOp::Circle {
            center: Reg(0),
            radius: Reg(1),
        }),
        Ty::Circle,
    ); // r2
    def(Op::Default(DefaultId(0)), Ty::Scalar); // r3
    def(Op::Planar(PlanarOp::Axis(1.0, 0.0)), Ty::Vector); // r4
    def(
        Op::Planar(PlanarOp::Rotated {
            dir: Reg(4),
            angle: Reg(3),
        }),
        Ty::Vector,
    ); // r5
    def(
        Op::Line {
            point: Reg(0),
            dir: Reg(5),
            offset: None,
        },
        Ty::Line,
    ); // r6
    def(Op::PointOf(p), Ty::Point); // r7
    def(
        Op::Intersect {
            meet: Meet::LineCircle,
            a: Reg(6),
            b: Reg(2),
            branch: BranchId(0),
            constraint: reach,
            near: Reg(7),
        },
        Ty::Point,
    ); // r8
    def(Op::PointOf(b), Ty::Point); // r9
    def(Op::Expr(four), Ty::Scalar); // r10
    steps.push(Step {
        op: Op::Translate {
            geoms: vec![p],
            from: Reg(7),
            to: Reg(8),
        },
        out: None,
        satisfies: vec![reach],
        works_for: None,
        explain: "Put P on the circle about A, at the default angle.".into(),
    });
    steps.push(Step {
        op: Op::PointOf(p),
        out: Some((Reg(11), Ty::Point)),
        satisfies: vec![],
        works_for: None,
        explain: String::new(),
    });
    steps.push(Step {
        op: Op::Planar(PlanarOp::RadiusFromPoint {
            at: Reg(9),
            b: Reg(10),
            plus: true,
            centre: Reg(11),
        }),
        out: Some((Reg(12), Ty::Scalar)),
        satisfies: vec![],
        works_for: None,
        explain: String::new(),
    });
    steps.push(Step {
        op: Op::Close {
            constraint: close,
            residual: Reg(12),
        },
        out: None,
        satisfies: vec![close],
        works_for: None,
        explain: "Close: P is 4 from B.".into(),
    });
    let mut plan = Plan::new(model.space);
    plan.regs = 13;
    plan.iterations.push(Iteration {
        defaults: vec![DefaultId(0)],
        start: 3,
        end: steps.len(),
        mode: None,
    });
    plan.steps = steps;
    plan.branches.push(BranchVar {
        name: "reach".into(),
        constraint: reach,
        count: 2,
        meanings: vec!["first along the ray".into(), "second".into()],
        default: 1,
        from_sketch: true,
        symmetric: false,
    });
    plan.defaults.push(DefaultVar {
        name: "p_angle".into(),
        meaning: "the angle of P about A".into(),
        sketch: 1f64.atan2(3.0),
        measure: None,
        geom: None,
        assembled: None,
    });
    plan
}

#[test]
fn a_default_and_an_iterated_region_are_valid_and_read_by_every_back_end() {
    let model = model();
    let plan = plan(&model);
    assert_eq!(plan.validate(&model), Ok(()));
    assert_eq!(plan.varied(&plan.iterations[0]), ["p_angle"]);
    assert_eq!(plan.closes(&plan.iterations[0]).len(), 1);

    // |P - B| = 4 with |P| = 5 and B = (7, 0): P = (29/7, sqrt(384)/7), at this angle.
    let closing = 384f64.sqrt().atan2(29.0);
    let choice = gcs_compiler::interp::Choice::Given(vec![1]);
    let params = model.default_params();
    let run =
        |angle: f64| gcs_compiler::interp::run_with(&model, &plan, &params, &[angle], &choice);
    let solved = run(closing).expect("the closing angle closes the region");
    let p = solved
        .config
        .point(&model, model.geom_named("P").expect("P"));
    assert!((p - nalgebra::Point2::new(29.0 / 7.0, 384f64.sqrt() / 7.0)).norm() < 1e-14);
    // The sketch's angle does not close it: the outer iteration varies it until it does.
    assert!((plan.sketch_defaults()[0] - closing).abs() > 0.1);
    // A scan of the turn finds the closing angle and its mirror image in A B, and only them.
    let scan = gcs_compiler::interp::scan(&model, &plan, &params, &plan.sketch_defaults(), &choice);
    assert!(scan.scanned());
    assert_eq!(scan.roots().len(), 2, "{:?}", scan.roots());
    assert!(
        (scan.roots()[0] + closing).abs() < 1e-12,
        "{:?}",
        scan.roots()
    );
    assert!(
        (scan.roots()[1] - closing).abs() < 1e-12,
        "{:?}",
        scan.roots()
    );
    let iterated = gcs_compiler::interp::run(&model, &plan, &params, &choice).expect("closes");
    assert!(
        (iterated.defaults[0] - closing).abs() < 1e-12,
        "{iterated:?}"
    );
    assert!(iterated.iterations > 0);
    let e = run(f64::NAN).expect_err("a NaN default");
    assert_eq!(
        (e.label.as_ref(), e.kind),
        ("p_angle", ErrorKind::InvalidInput)
    );

    let code = gcs_compiler::codegen::generate(&model, &plan);
    if let Ok(path) = std::env::var("GCS_PLAN_IR_OUT") {
        std::fs::write(path, gcs_compiler::codegen::format(&code)).expect("write");
    }
    for part in [
        "pub p_angle: f64,",
        "/// `p_angle`: the angle of P about A; the sketch's value is",
        "(\"p_angle\", defaults.p_angle)",
        // An angle's iteration that fails searches the whole turn for a root.
        ".spanning(gcs_runtime::iterate::Span::Turn)",
        ".map_err(|failure| failure.into_error(\"close\",",
    ] {
        assert!(code.contains(part), "no `{part}` in:\n{code}");
    }
    let explained = gcs_compiler::explain::explain(&model, &plan);
    assert!(
        explained.contains("- p_angle (the sketch's "),
        "{explained}"
    );
    assert!(
        explained.contains("Vary p_angle until close closes."),
        "{explained}"
    );
    let dump = plan.dump(&model);
    assert!(dump.contains("iterate steps 3..15 over p_angle"), "{dump}");
    assert!(dump.contains("r3 : Scalar = default p_angle"), "{dump}");
    assert!(dump.contains("close close by r12"), "{dump}");
}
