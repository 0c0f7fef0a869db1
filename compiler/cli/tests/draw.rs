//! `gcs draw`: golden SVGs of four examples (`tests/goldens/draw/`; regenerate them with
//! `UPDATE_EXPECT=1 cargo test -p gcs-cli --test draw`), every example drawn as an SVG a
//! renderer reads, renders of the four-bar checked at the pixels where its solved points
//! project, a traced curve's gap where a sweep's sample fails, and the errors.

use expect_test::expect_file;
use gcs_compiler::draw;
use resvg::tiny_skia;
use std::path::Path;

use support::{gcs, root};

mod support;

mod discover {
    include!("../../../examples/discover.rs");
}

/// `gcs draw ARGS` succeeds without errors, and its SVG matches `goldens/draw/NAME.svg`.
fn golden(name: &str, args: &[&str]) {
    assert!(GOLDENS.contains(&name), "{name} is listed in GOLDENS");
    let mut all = vec!["draw"];
    all.extend(args);
    let (code, svg, stderr) = gcs(&all);
    assert_eq!(code, 0, "{name}: {stderr}");
    assert!(!stderr.contains("error"), "{name}: {stderr}");
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/goldens/draw/{name}.svg"));
    expect_file![path].assert_eq(&svg);
    // Valid: a renderer reads it.
    resvg::usvg::Tree::from_data(svg.as_bytes(), &resvg::usvg::Options::default())
        .unwrap_or_else(|e| panic!("{name}: not an SVG a renderer reads: {e}"));
}

/// The goldens of this file's tests, each once: no other file is in `goldens/draw/`.
const GOLDENS: [&str; 5] = [
    "fourbar",
    "fourbar_animated",
    "jansen_leg_foot",
    "rssr_iso",
    "sketch_profile",
];

#[test]
fn every_draw_golden_belongs_to_a_test() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/goldens/draw");
    let mut found: Vec<String> = std::fs::read_dir(folder)
        .expect("the goldens' folder")
        .map(|e| {
            e.expect("a golden")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    found.sort();
    assert_eq!(found, GOLDENS.map(|g| format!("{g}.svg")));
}

#[test]
fn the_fourbar_matches_its_golden() {
    golden("fourbar", &["examples/fourbar.gcs"]);
}

#[test]
fn the_jansen_leg_with_its_foot_over_a_turn_of_the_crank_matches_its_golden() {
    golden(
        "jansen_leg_foot",
        &[
            "examples/jansen_leg.gcs",
            "--sweep",
            "theta=0deg..360deg:60",
            "--trace",
            "foot",
        ],
    );
}

#[test]
fn the_sketch_profile_matches_its_golden() {
    golden("sketch_profile", &["examples/sketch_profile.gcs"]);
}

#[test]
fn the_rssr_in_isometric_view_matches_its_golden() {
    golden("rssr_iso", &["examples/rssr.gcs", "--view", "iso"]);
    // Iso is the default view of a 3d model.
    let (_, iso, _) = gcs(&["draw", "examples/rssr.gcs", "--view", "iso"]);
    let (_, default, _) = gcs(&["draw", "examples/rssr.gcs"]);
    assert_eq!(iso, default);
}

#[test]
fn an_animated_fourbar_matches_its_golden() {
    golden(
        "fourbar_animated",
        &[
            "examples/fourbar.gcs",
            "--sweep",
            "theta=0deg..360deg:8",
            "--trace",
            "coupler.c",
            "--animate",
        ],
    );
}

/// Every example the analysis covers draws (each 3d one in its four views) as an SVG a
/// renderer reads, with a dot for each of its points.
#[test]
fn every_example_draws_as_a_valid_svg() {
    let examples = discover::analysed(&root(), discover::Folder::Examples);
    assert!(examples.len() > 20, "{} examples", examples.len());
    let failures: Vec<String> = std::thread::scope(|s| {
        let runs: Vec<_> = (examples.iter())
            .map(|m| {
                s.spawn(move || {
                    let file = m.relative();
                    let views: &[&str] = if m.space == gcs_lang::model::Space::D3 {
                        &["xy", "xz", "yz", "iso"]
                    } else {
                        &["xy"]
                    };
                    let mut failed = Vec::new();
                    for view in views {
                        let (code, svg, stderr) = gcs(&["draw", &file, "--view", view]);
                        if code != 0 {
                            failed.push(format!("{file} --view {view}: exit {code}: {stderr}"));
                            continue;
                        }
                        let opts = resvg::usvg::Options::default();
                        if let Err(e) = resvg::usvg::Tree::from_data(svg.as_bytes(), &opts) {
                            failed.push(format!("{file} --view {view}: {e}"));
                        }
                        if !svg.contains("<circle class=\"point\"")
                            && !svg.contains("<circle class=\"end\"")
                        {
                            failed.push(format!("{file} --view {view}: no point drawn"));
                        }
                    }
                    failed
                })
            })
            .collect();
        runs.into_iter()
            .flat_map(|r| r.join().expect("no panic"))
            .collect()
    });
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The four-bar of examples/fourbar.gcs, compiled, with its whole plan and the sketch's
/// branches.
fn fourbar() -> gcs_compiler::pipeline::Compiled {
    let path = root().join("examples/fourbar.gcs");
    let bytes = std::fs::read(&path).expect("read the four-bar");
    gcs_compiler::compile("examples/fourbar.gcs", &bytes).expect("compiles")
}

/// Renders an SVG at `scale` times its size.
fn render(svg: &str, scale: f32) -> tiny_skia::Pixmap {
    let tree = resvg::usvg::Tree::from_data(svg.as_bytes(), &resvg::usvg::Options::default())
        .expect("an SVG");
    let size = tree.size().to_int_size().scale_by(scale).expect("a size");
    let mut pixmap = tiny_skia::Pixmap::new(size.width(), size.height()).expect("a pixmap");
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    pixmap
}

/// The colour at pixel `p` of the drawing (in its own pixels) of a render at `scale`.
fn colour_at(pixmap: &tiny_skia::Pixmap, p: [f64; 2], scale: f32) -> [u8; 3] {
    let (x, y) = (
        (p[0] * scale as f64).floor() as u32,
        (p[1] * scale as f64).floor() as u32,
    );
    let c = pixmap.pixel(x, y).expect("inside the picture").demultiply();
    [c.red(), c.green(), c.blue()]
}

fn hex(colour: &str) -> [u8; 3] {
    let v = u32::from_str_radix(colour.trim_start_matches('#'), 16).expect("a colour");
    [(v >> 16) as u8, (v >> 8) as u8, v as u8]
}

fn near(a: [u8; 3], b: [u8; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| x.abs_diff(y) <= 3)
}

#[test]
fn a_render_of_the_fourbar_shows_a_point_dot_at_each_solved_point() {
    let c = fourbar();
    let (model, plan) = (&c.model, &c.analysis.plan);
    let scope = model.top_level().map(|(id, _)| id).collect();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let solution =
        gcs_compiler::solve_plan(model, plan, &scope, &model.default_params(), &branches)
            .expect("solves");
    let drawing = draw::draw(model, &solution, &[], &draw::Options::default()).expect("draws");
    // The command line draws the same picture.
    let (code, svg, stderr) = gcs(&["draw", "examples/fourbar.gcs"]);
    assert_eq!(code, 0, "{stderr}");
    assert_eq!(svg, drawing.svg);
    for scale in [1.0, 2.0] {
        let pixmap = render(&drawing.svg, scale);
        assert_eq!(
            [pixmap.width(), pixmap.height()],
            drawing.fit.size.map(|s| (s * scale as f64) as u32)
        );
        let dot = hex(draw::svg::POINT_COLOUR);
        assert_eq!(solution.points.len(), 8, "{:?}", solution.points);
        for (name, p) in &solution.points {
            let at = drawing.pixel(p);
            assert!(
                near(colour_at(&pixmap, at, scale), dot),
                "{name} at {at:?} (scale {scale}): {:?}",
                colour_at(&pixmap, at, scale)
            );
            // Beside the dot, one radius and a half off, it is not the dot's colour.
            let beside = [at[0], at[1] - 1.5 * draw::svg::POINT_RADIUS];
            assert!(
                !near(colour_at(&pixmap, beside, scale), dot),
                "{name}: the dot is larger than drawn"
            );
        }
        // The background is white, and where no geom is.
        assert_eq!(colour_at(&pixmap, [2.0, 2.0], scale), [255, 255, 255]);
    }
}

/// The pixels of the polylines of the `traces` group of an SVG, one list a polyline.
fn polylines(svg: &str) -> Vec<Vec<[f64; 2]>> {
    let start = svg.find("<g id=\"traces\">").expect("a traces group");
    let group = &svg[start..];
    let group = &group[..group.find("\n</g>").expect("closed")];
    (group.split("<polyline points=\"").skip(1))
        .map(|l| {
            l[..l.find('"').expect("closed")]
                .split(' ')
                .map(|p| {
                    let (x, y) = p.split_once(',').expect("x,y");
                    [x.parse().expect("x"), y.parse().expect("y")]
                })
                .collect()
        })
        .collect()
}

#[test]
fn a_sample_that_does_not_solve_leaves_a_gap_in_the_traced_curve() {
    // A crank of 6 closes the loop near theta = 0 and never near pi: 37 samples, a run of
    // failures in the middle.
    let args = [
        "draw",
        "examples/fourbar.gcs",
        "--set",
        "crank_len=6",
        "--sweep",
        "theta=0deg..360deg:36",
        "--trace",
        "coupler.c",
    ];
    let (code, svg, stderr) = gcs(&args);
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains("samples did not solve, and leave gaps; the first, at theta = ")
            && stderr.contains("constraint `elbow`"),
        "{stderr}"
    );
    let lines = polylines(&svg);
    assert_eq!(lines.len(), 2, "{svg}");
    // The samples that solved, by the library: the polylines are their two runs, in order.
    let c = fourbar();
    let (model, plan) = (&c.model, &c.analysis.plan);
    let scope = model.top_level().map(|(id, _)| id).collect();
    let branches: Vec<usize> = plan.branches.iter().map(|b| b.default).collect();
    let sweep = draw::Sweep::parse(model, "theta=0deg..360deg:36").expect("a sweep");
    let mut params = model.default_params();
    params[1] = 6.0;
    let samples: Vec<_> = draw::sweep::solve(
        model,
        plan,
        &scope,
        &params,
        &branches,
        &plan.sketch_defaults(),
        false,
        &sweep,
    )
    .into_iter()
    .map(Result::ok)
    .collect();
    let failed = samples.iter().filter(|s| s.is_none()).count();
    assert!(failed > 0 && stderr.contains(&format!("{failed} of 37 samples")));
    let runs = draw::runs(&samples);
    assert_eq!(
        lines.iter().map(Vec::len).collect::<Vec<_>>(),
        runs.iter().map(Vec::len).collect::<Vec<_>>()
    );
    // Rendered: the trace's colour halfway along a chord of a run, and not across the gap.
    let pixmap = render(&svg, 1.0);
    let red = hex(draw::svg::TRACE_COLOURS[0]);
    let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    let (first, second) = (&lines[0], &lines[1]);
    let along = mid(first[first.len() - 2], first[first.len() - 1]);
    assert!(near(colour_at(&pixmap, along, 1.0), red), "{along:?}");
    let across = mid(first[first.len() - 1], second[0]);
    assert_eq!(
        colour_at(&pixmap, across, 1.0),
        [255, 255, 255],
        "{across:?}"
    );
}

#[test]
fn a_model_with_a_syntax_error_gets_its_located_diagnostic_and_no_svg() {
    let dir = tempfile::tempdir().expect("tempdir");
    let model = dir.path().join("broken.gcs");
    std::fs::write(&model, "space 2d;\nfixed point A = (0, 0;\n").expect("write");
    let out = dir.path().join("broken.svg");
    let (m, o) = (model.to_string_lossy(), out.to_string_lossy());
    let (code, stdout, stderr) = gcs(&["draw", &m, "-o", &o]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stdout.is_empty());
    assert!(!out.exists(), "no SVG is written");
    assert!(stderr.contains("broken.gcs:2:22"), "{stderr}");
    assert!(stderr.contains("could not load"), "{stderr}");
    let (code, stdout, _) = gcs(&["draw", &m]);
    assert_eq!((code, stdout.as_str()), (1, ""));
}

#[test]
fn a_solve_that_fails_names_the_constraint_and_the_gap() {
    let (code, stdout, stderr) = gcs(&["draw", "examples/fourbar.gcs", "--set", "crank_len=20"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stdout.is_empty());
    assert!(
        stderr.contains("constraint `elbow`") && stderr.contains("miss by"),
        "{stderr}"
    );
    // A sweep none of whose samples solves is an error too.
    let (code, stdout, stderr) = gcs(&[
        "draw",
        "examples/fourbar.gcs",
        "--set",
        "crank_len=20",
        "--sweep",
        "theta=0..1:4",
    ]);
    assert_eq!(code, 1, "{stderr}");
    assert!(stdout.is_empty());
    assert!(
        stderr.contains(
            "no sample of `--sweep theta=0..1:4` solves; at theta = 0: constraint `elbow`"
        ),
        "{stderr}"
    );
}

#[test]
fn bad_arguments_are_refused_with_exit_code_2() {
    for (args, message) in [
        (
            vec!["--sweep", "theta=0..1", "--trace", "coupler.z"],
            "error: `--trace coupler.z`: no point `coupler.z`; the points are: A, D, crank.a, \
             crank.b, coupler.b, coupler.c, rocker.d, rocker.c",
        ),
        (
            vec!["--sweep", "theta=0..1", "--trace", "X"],
            "error: `--trace X`: `X` is a vector, not a point",
        ),
        (
            vec!["--trace", "coupler.c"],
            "error: `--trace` plays a sweep: give one with `--sweep NAME=FROM..TO[:STEPS]`",
        ),
        (
            vec!["--animate"],
            "error: `--animate` plays a sweep: give one with `--sweep NAME=FROM..TO[:STEPS]`",
        ),
        (
            vec!["--sweep", "phi=0..1"],
            "error: `--sweep phi=0..1`: no param `phi`; the params are: theta, crank_len",
        ),
        (
            vec!["--sweep", "theta=0..1:none"],
            "error: `--sweep theta=0..1:none`: `none`: the steps are a whole number, 1 or more",
        ),
        (
            vec!["--sweep", "crank_len=1deg..2"],
            "error: `--sweep crank_len=1deg..2`: ",
        ),
        (
            vec!["--view", "xz"],
            "error: `--view xz`: `examples/fourbar.gcs` is a 2d model, drawn in its plane (xy)",
        ),
        (
            vec!["--view", "top"],
            "invalid value 'top' for '--view <VIEW>'",
        ),
        (
            vec!["--set", "nothing=1"],
            "error: `--set nothing=1`: no param `nothing`",
        ),
        (
            vec!["--branch", "elbow=2"],
            "error: `--branch elbow=2`: `elbow` has indices 0 to 1",
        ),
    ] {
        let mut all = vec!["draw", "examples/fourbar.gcs"];
        all.extend(&args);
        let (code, stdout, stderr) = gcs(&all);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stdout.is_empty(), "{args:?}");
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
}

#[test]
fn the_svg_goes_to_the_file_given() {
    let dir = tempfile::tempdir().expect("tempdir");
    let out = dir.path().join("fourbar.svg");
    let o = out.to_string_lossy();
    let (code, stdout, stderr) = gcs(&["draw", "examples/fourbar.gcs", "-o", &o]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.is_empty());
    let (_, to_stdout, _) = gcs(&["draw", "examples/fourbar.gcs"]);
    assert_eq!(std::fs::read_to_string(&out).expect("written"), to_stdout);
}
