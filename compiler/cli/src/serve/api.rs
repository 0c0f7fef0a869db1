//! The page's JSON API as plain functions, text in and JSON out, so that it is tested without
//! a network: [`Api::answer`] takes a request's path and body and gives its status and JSON.
//!
//! Every request carries the model's text (the editor's, which may differ from the file), and
//! is answered with what the command line would print for it:
//!
//! - `/api/check` `{"text"}`: the diagnostics, located (line and column, as `gcs check` prints
//!   them) and rendered as `gcs check` renders them; `check`'s report and `explain`'s plan; and
//!   what the page makes controls of: the params with their sketch values, units and slider
//!   ranges, the branch variables with the meaning of each index, the defaults with their
//!   meanings and sketch values, and the points that can be traced.
//! - `/api/solve` `{"text", "set", "branch", "default", "sweep", "trace", "view"}`, the first
//!   four as `gcs draw`'s flags (`"set": ["theta=75deg"]`, `"sweep": "theta=0deg..360deg:60"`):
//!   the drawing (`gcs draw`'s SVG, its fit and view) and the solution (`gcs solve --json`'s
//!   object), with the traced points' curves over the sweep and its failed samples; or why
//!   not, in `gcs solve`'s words (the constraint, and by how much it is off).
//! - `/api/compile` `{"text"}`: the generated Rust module, as `gcs compile` writes it.
//!
//! A request that is not JSON, or lacks its text, is a 400; anything the model says (it does
//! not parse, it does not solve) is a 200 whose `ok` is false.

use crate::shared;
use codespan_reporting::files::Files as _;
use gcs_compiler::draw;
use gcs_compiler::pipeline::{AnalysisError, CompileError, Compiled};
use gcs_lang::expr::Dim;
use gcs_lang::{Diagnostic, SourceFile};
use serde_json::{json, Value};
use std::collections::BTreeSet;

/// The API of one served model: its name (the path as given, which diagnostics show) and the
/// last text that compiled, kept so that dragging a slider does not analyse the model again.
#[derive(Debug)]
pub struct Api {
    name: String,
    compiled: Option<(String, Compiled)>,
}

/// An answer: its HTTP status and JSON body.
#[derive(Debug, Clone, PartialEq)]
pub struct Answer {
    pub status: u16,
    pub body: Value,
}

impl Answer {
    fn ok(body: Value) -> Answer {
        Answer { status: 200, body }
    }

    fn bad(status: u16, why: impl Into<String>) -> Answer {
        Answer {
            status,
            body: json!({ "ok": false, "error": why.into() }),
        }
    }
}

impl Api {
    /// The API of the model called `name`.
    pub fn new(name: impl Into<String>) -> Api {
        Api {
            name: name.into(),
            compiled: None,
        }
    }

    /// The answer to a POST of `body` to `path`.
    pub fn answer(&mut self, path: &str, body: &[u8]) -> Answer {
        let request: Value = match serde_json::from_slice(body) {
            Ok(v) => v,
            Err(e) => return Answer::bad(400, format!("the request is not JSON: {e}")),
        };
        let Some(text) = request.get("text").and_then(Value::as_str) else {
            return Answer::bad(400, "the request has no \"text\" (the model's text)");
        };
        match path {
            "/api/check" => Answer::ok(self.check(text)),
            "/api/compile" => Answer::ok(self.compile(text)),
            "/api/solve" => match Request::read(&request) {
                Ok(r) => Answer::ok(self.solve(text, &r)),
                Err(why) => Answer::bad(400, why),
            },
            _ => Answer::bad(404, format!("no such API: {path}")),
        }
    }

    /// The model `text` through the pipeline, the last one that compiled kept.
    fn compiled(&mut self, text: &str) -> Result<&Compiled, CompileError> {
        let kept = self.compiled.take().filter(|(t, _)| t == text);
        let entry = match kept {
            Some(entry) => entry,
            None => (
                text.to_string(),
                gcs_compiler::compile(&self.name, text.as_bytes())?,
            ),
        };
        Ok(&self.compiled.insert(entry).1)
    }

    /// `/api/check`: what `gcs check` and `gcs explain` print, and the controls.
    pub fn check(&mut self, text: &str) -> Value {
        let name = self.name.clone();
        match self.compiled(text) {
            Ok(c) if c.has_errors() => json!({
                "ok": false,
                "diagnostics": located(&c.source, &c.diagnostics),
                "rendered": rendered(&c.source, &c.diagnostics),
                "status": format!("error: {}", shared::analysis_errors(&name, &c.diagnostics)),
            }),
            Ok(c) => json!({
                "ok": true,
                "diagnostics": located(&c.source, &c.diagnostics),
                "rendered": rendered(&c.source, &c.diagnostics),
                "report": gcs_compiler::report::check_report(&c.model, &c.analysis),
                "explain": gcs_compiler::explain::explain(&c.model, &c.analysis.plan),
                "controls": controls(c),
            }),
            Err(CompileError::Load(r)) => json!({
                "ok": false,
                "diagnostics": located(&r.source, &r.diagnostics),
                "rendered": rendered(&r.source, &r.diagnostics),
                "status": format!("error: {}", shared::not_loaded(&name, &r.diagnostics)),
            }),
            Err(CompileError::Analysis(u)) => {
                // As `gcs check`: a model the analysis does not cover yet still gets its
                // nominal count.
                let report = match &u.error {
                    AnalysisError::Uncovered(_) => format!(
                        "{}analysis: not run: {}\n",
                        gcs_compiler::nominal::report(&u.model),
                        u.error
                    ),
                    AnalysisError::Malformed(_) => String::new(),
                };
                json!({
                    "ok": false,
                    "diagnostics": located(&u.source, &u.diagnostics),
                    "rendered": rendered(&u.source, &u.diagnostics),
                    "report": report,
                    "status": format!("error: {}", u.error),
                })
            }
        }
    }

    /// `/api/compile`: the generated module, as `gcs compile` writes it.
    pub fn compile(&mut self, text: &str) -> Value {
        let stem = file_stem(&self.name).to_string();
        match self.solvable(text) {
            Ok(c) => json!({
                "ok": true,
                "file": format!("{stem}.rs"),
                "code": gcs_compiler::codegen::format(&gcs_compiler::codegen::generate(
                    &c.model,
                    &c.analysis.plan,
                )),
            }),
            Err(errors) => errors,
        }
    }

    /// The model `text` if it can be solved; else the answer saying why not, in the command
    /// line's words.
    fn solvable(&mut self, text: &str) -> Result<&Compiled, Value> {
        let name = self.name.clone();
        let failed = |source: &SourceFile, diags: &[Diagnostic], status: String| {
            json!({
                "ok": false,
                "stage": "model",
                "errors": [status],
                "diagnostics": located(source, diags),
                "rendered": rendered(source, diags),
            })
        };
        match self.compiled(text) {
            Ok(c) if c.has_errors() => Err(failed(
                &c.source,
                &c.diagnostics,
                format!("could not solve `{name}`"),
            )),
            Ok(c) => Ok(c),
            Err(CompileError::Load(r)) => Err(failed(
                &r.source,
                &r.diagnostics,
                shared::not_loaded(&name, &r.diagnostics),
            )),
            Err(CompileError::Analysis(u)) => {
                Err(failed(&u.source, &u.diagnostics, u.error.to_string()))
            }
        }
    }

    /// `/api/solve`: the model solved and drawn at the request's inputs, as `gcs draw` draws
    /// it, with the solution as `gcs solve --json` prints it; or why it does not solve.
    pub fn solve(&mut self, text: &str, r: &Request) -> Value {
        let c = match self.solvable(text) {
            Ok(c) => c,
            Err(errors) => return errors,
        };
        let (model, analysis) = (&c.model, &c.analysis);
        let refused = |why: String| json!({ "ok": false, "stage": "inputs", "errors": [why] });
        let inputs = match shared::inputs(model, analysis, &r.set, &r.branch, &r.default) {
            Ok(i) => i,
            Err(why) => return refused(why),
        };
        let view = match r.view.as_deref() {
            None => draw::View::default(),
            Some(v) => match draw::View::named(v) {
                Some(view) => view,
                None => return refused(format!("no view `{v}`: xy, xz, yz or iso")),
            },
        };
        let sweep = match r.sweep.as_deref() {
            None if r.trace.is_empty() => None,
            None => return refused("a trace needs a sweep of a param".to_string()),
            Some(s) => match draw::Sweep::parse(model, s) {
                Ok(sweep) => Some(sweep),
                Err(e) => return refused(format!("`--sweep {s}`: {e}")),
            },
        };
        // Everything is drawn, whatever the `output` statements say, as `gcs draw` does.
        let plan = &analysis.plan;
        let scope: BTreeSet<_> = model.top_level().map(|(id, _)| id).collect();
        let given = !r.default.is_empty();
        let (params, branches, defaults) = (&inputs.params, &inputs.branches, &inputs.defaults);
        // The page gives every branch; a branch it does not is the sketch's, or changed (and
        // then in the solution's `branches_changed`).
        let held = shared::held(plan, &r.branch);
        let solved = shared::solve(
            model,
            plan,
            &scope,
            (params, branches, defaults),
            given,
            &held,
        );
        let shown = match solved {
            Ok(kept) => kept.solution,
            Err(e) => {
                let errors = shared::failure(model, plan, params, defaults, branches.clone(), &e);
                return json!({ "ok": false, "stage": "solve", "errors": errors });
            }
        };
        let (samples, swept) = match &sweep {
            None => (Vec::new(), Value::Null),
            Some(sweep) => {
                let solved = draw::sweep::solve(
                    model, plan, &scope, params, branches, defaults, given, sweep,
                );
                let failed: Vec<Value> = (sweep.values.iter().zip(&solved))
                    .filter_map(|(v, s)| {
                        let e = s.as_ref().err()?;
                        Some(json!({ "value": v, "error": e.to_string() }))
                    })
                    .collect();
                let swept = json!({
                    "param": sweep.name,
                    "samples": sweep.values.len(),
                    "failed": failed,
                });
                (solved.into_iter().map(Result::ok).collect(), swept)
            }
        };
        let options = draw::Options {
            view,
            traces: r.trace.clone(),
            animate: false,
        };
        let drawing = match draw::draw(model, &shown, &samples, &options) {
            Ok(d) => d,
            Err(why) => return refused(format!("`--trace`: {why}")),
        };
        let solution: Value =
            serde_json::from_str(&shown.to_json()).unwrap_or(Value::String(shown.to_json()));
        json!({
            "ok": true,
            "svg": drawing.svg,
            "view": drawing.view.name(),
            "fit": {
                "scale": drawing.fit.scale,
                "corner": drawing.fit.corner,
                "size": drawing.fit.size,
            },
            "solution": solution,
            "sweep": swept,
        })
    }
}

/// What `/api/solve` is asked, beside the text: `gcs draw`'s flags.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Request {
    pub set: Vec<String>,
    pub branch: Vec<String>,
    pub default: Vec<String>,
    pub sweep: Option<String>,
    pub trace: Vec<String>,
    pub view: Option<String>,
}

impl Request {
    /// Reads the request's fields; each is optional, a list of strings or a string.
    pub fn read(v: &Value) -> Result<Request, String> {
        let list = |key: &str| -> Result<Vec<String>, String> {
            match v.get(key) {
                None | Some(Value::Null) => Ok(Vec::new()),
                Some(Value::Array(items)) => (items.iter())
                    .map(|i| {
                        i.as_str()
                            .map(str::to_string)
                            .ok_or_else(|| format!("\"{key}\" is a list of strings"))
                    })
                    .collect(),
                Some(_) => Err(format!("\"{key}\" is a list of strings")),
            }
        };
        let one = |key: &str| -> Result<Option<String>, String> {
            match v.get(key) {
                None | Some(Value::Null) => Ok(None),
                Some(Value::String(s)) => Ok(Some(s.clone())),
                Some(_) => Err(format!("\"{key}\" is a string")),
            }
        };
        Ok(Request {
            set: list("set")?,
            branch: list("branch")?,
            default: list("default")?,
            sweep: one("sweep")?,
            trace: list("trace")?,
            view: one("view")?,
        })
    }
}

/// The file's name without its folders and extension, for the generated module's file.
fn file_stem(name: &str) -> &str {
    let base = name.rsplit(['/', '\\']).next().unwrap_or(name);
    base.strip_suffix(".gcs").unwrap_or(base)
}

/// The diagnostics as `gcs check` renders them on its standard error (without colour).
fn rendered(source: &SourceFile, diags: &[Diagnostic]) -> String {
    gcs_lang::diagnostic::render_plain(source, diags)
}

/// The diagnostics `gcs check` shows, each with the line and column (1-based, in characters,
/// as the rendering says them) of its primary span's start and end.
fn located(source: &SourceFile, diags: &[Diagnostic]) -> Vec<Value> {
    let file = gcs_lang::diagnostic::codespan_file(source);
    let at = |offset: usize| match file.location((), offset) {
        Ok(l) => json!([l.line_number, l.column_number]),
        Err(_) => Value::Null,
    };
    (gcs_lang::diagnostic::shown(diags).diagnostics.iter())
        .map(|d| {
            let span = d.primary.span.range();
            json!({
                "severity": if d.is_error() { "error" } else { "warning" },
                "message": d.message,
                "start": at(span.start),
                "end": at(span.end),
                "label": d.primary.message,
                "notes": d.notes,
            })
        })
        .collect()
}

/// What the page makes controls of: each param with its sketch value and a slider's range
/// (in degrees for an angle), each branch variable with the meaning of each index and its
/// default (`from_sketch` when the sketch reaches it), each default with its meaning and
/// sketch value, the points that can be traced, the views.
fn controls(c: &Compiled) -> Value {
    let (model, plan) = (&c.model, &c.analysis.plan);
    let params: Vec<Value> = (model.params.iter())
        .map(|(_, p)| {
            let (value, min, max, step, unit) = slider(p.dim, p.default);
            json!({
                "name": p.name,
                "dim": match p.dim {
                    Dim::Angle => "angle",
                    Dim::Length => "length",
                    Dim::Number => "number",
                },
                "unit": unit,
                "value": value,
                "min": min,
                "max": max,
                "step": step,
            })
        })
        .collect();
    let branches: Vec<Value> = (plan.branches.iter())
        .map(|b| {
            json!({
                "name": b.name,
                "count": b.count,
                "default": b.default,
                "from_sketch": b.from_sketch,
                "meanings": b.meanings,
            })
        })
        .collect();
    let defaults: Vec<Value> = (plan.defaults.iter())
        .map(|d| {
            let angle = d.is_angle();
            json!({
                "name": d.name,
                "meaning": d.meaning,
                "unit": if angle { "deg" } else { "" },
                "value": if angle { degrees(d.sketch) } else { d.sketch },
            })
        })
        .collect();
    json!({
        "space": model.space.to_string(),
        "params": params,
        "branches": branches,
        "defaults": defaults,
        "points": draw::traceable(model),
    })
}

/// An angle in degrees, rounded to nine decimals: `30 deg` is shown as 30, not as the
/// 29.999999999999996 its radians make.
fn degrees(radians: f64) -> f64 {
    (radians.to_degrees() * 1e9).round() / 1e9
}

/// A param's slider, from its sketch value: `(value, min, max, step, unit)`, an angle in
/// degrees over a turn about its sketch value, a length or number from zero to twice it (or
/// about zero when it is zero), in a thousand steps.
fn slider(dim: Dim, sketch: f64) -> (f64, f64, f64, f64, &'static str) {
    if dim == Dim::Angle {
        let v = degrees(sketch);
        return (v, v - 180.0, v + 180.0, 0.1, "deg");
    }
    let (min, max) = if sketch > 0.0 {
        (0.0, 2.0 * sketch)
    } else if sketch < 0.0 {
        (2.0 * sketch, 0.0)
    } else {
        (-1.0, 1.0)
    };
    (sketch, min, max, (max - min) / 1000.0, "")
}

#[cfg(test)]
mod tests {
    use super::*;

    const FOURBAR: &str = include_str!("../../../../examples/fourbar.gcs");

    fn api() -> Api {
        Api::new("examples/fourbar.gcs")
    }

    fn solve(api: &mut Api, text: &str, fields: Value) -> Value {
        let mut body = fields;
        body["text"] = Value::String(text.to_string());
        let a = api.answer("/api/solve", body.to_string().as_bytes());
        assert_eq!(a.status, 200, "{}", a.body);
        a.body
    }

    fn point(v: &Value, name: &str) -> [f64; 2] {
        let p = &v["solution"]["points"][name];
        [p[0].as_f64().expect("x"), p[1].as_f64().expect("y")]
    }

    #[test]
    fn check_gives_the_report_the_plan_and_the_controls() {
        let v = api().check(FOURBAR);
        assert_eq!(v["ok"], true, "{v}");
        let report = v["report"].as_str().expect("report");
        assert!(
            report.starts_with("examples/fourbar.gcs: space 2d, 2 params"),
            "{report}"
        );
        assert!(report.contains("analysis: well-constrained"), "{report}");
        let explain = v["explain"].as_str().expect("explain");
        assert!(explain.starts_with("Assembly plan for examples/fourbar.gcs"));
        let controls = &v["controls"];
        assert_eq!(
            controls["params"][0],
            json!({"name": "theta", "dim": "angle", "unit": "deg", "value": 30.0,
                   "min": -150.0, "max": 210.0, "step": 0.1})
        );
        assert_eq!(controls["params"][1]["dim"], "length");
        assert_eq!(
            (
                controls["params"][1]["min"].as_f64(),
                controls["params"][1]["max"].as_f64()
            ),
            (Some(0.0), Some(3.0))
        );
        let elbow = &controls["branches"][0];
        assert_eq!(
            (elbow["name"].as_str(), elbow["count"].as_u64()),
            (Some("elbow"), Some(2))
        );
        assert_eq!(
            elbow["meanings"][1],
            "rocker.c to the right of the line from crank.b to D"
        );
        assert_eq!(
            (elbow["default"].as_u64(), elbow["from_sketch"].as_bool()),
            (Some(0), Some(true))
        );
        assert_eq!(controls["defaults"], json!([]));
        let points: Vec<&str> = (controls["points"].as_array().expect("points").iter())
            .filter_map(Value::as_str)
            .collect();
        assert!(
            points.contains(&"coupler.c") && points.contains(&"A"),
            "{points:?}"
        );
    }

    #[test]
    fn a_syntax_error_is_located_as_gcs_check_says_it() {
        let text = FOURBAR.replace("coincident(rocker.d, D);", "coincident(rocker.d, D;");
        let v = api().check(&text);
        assert_eq!(v["ok"], false);
        let line = 1 + text[..text.find("coincident(rocker.d, D;").expect("there")]
            .matches('\n')
            .count();
        let d = &v["diagnostics"][0];
        assert_eq!(d["severity"], "error");
        assert_eq!(d["start"][0].as_u64(), Some(line as u64), "{d}");
        let rendered = v["rendered"].as_str().expect("rendered");
        let col = d["start"][1].as_u64().expect("column");
        assert!(
            rendered.contains(&format!("examples/fourbar.gcs:{line}:{col}")),
            "{rendered}"
        );
        assert!(rendered.contains(d["message"].as_str().expect("message")));
        assert!(v["status"]
            .as_str()
            .expect("status")
            .starts_with("error: could not load `examples/fourbar.gcs` due to"));
    }

    #[test]
    fn solve_draws_the_model_at_the_given_inputs_and_on_the_other_branch() {
        let mut api = api();
        let at = solve(&mut api, FOURBAR, json!({"set": ["theta=75deg"]}));
        assert_eq!(at["ok"], true, "{at}");
        assert!(at["svg"].as_str().expect("svg").starts_with("<svg"));
        // The drawn point is where the solution has it, through the fit.
        let fit = &at["fit"];
        let (scale, cx, cy) = (
            fit["scale"].as_f64().expect("scale"),
            fit["corner"][0].as_f64().expect("x"),
            fit["corner"][1].as_f64().expect("y"),
        );
        let c = point(&at, "coupler.c");
        let px = format!("cx=\"{}\"", draw::svg::num((c[0] - cx) * scale));
        let py = format!("cy=\"{}\"", draw::svg::num((cy - c[1]) * scale));
        let svg = at["svg"].as_str().expect("svg");
        let dot = &svg[svg.find("data-name=\"coupler.c\" cx").expect("the dot")..];
        assert!(
            dot.contains(&px) && dot.contains(&py),
            "{px} {py} {}",
            &dot[..80]
        );
        let other = solve(
            &mut api,
            FOURBAR,
            json!({"set": ["theta=75deg"], "branch": ["elbow=1"]}),
        );
        assert_eq!(other["solution"]["branches"]["elbow"], 1);
        let d = point(&other, "coupler.c");
        assert!((c[0] - d[0]).hypot(c[1] - d[1]) > 0.5, "{c:?} {d:?}");
    }

    #[test]
    fn a_failed_solve_names_the_constraint_and_the_gap() {
        let v = solve(&mut api(), FOURBAR, json!({"set": ["crank_len=20"]}));
        assert_eq!(
            (v["ok"].as_bool(), v["stage"].as_str()),
            (Some(false), Some("solve"))
        );
        let e = v["errors"][0].as_str().expect("error");
        assert_eq!(
            e,
            "constraint `elbow` (coincident(coupler.c, rocker.c)) cannot be met: no \
             intersection, the loci miss by 9.656408238107332"
        );
        assert!(v.get("svg").is_none());
    }

    #[test]
    fn wrong_inputs_are_refused_in_the_command_lines_words() {
        let mut api = api();
        for (fields, why) in [
            (json!({"set": ["phi=1"]}), "`--set phi=1`: no param `phi`"),
            (json!({"branch": ["elbow=2"]}), "`elbow` has indices 0 to 1"),
            (json!({"trace": ["coupler.c"]}), "a trace needs a sweep"),
            (
                json!({"sweep": "theta=0..1", "trace": ["crank"]}),
                "`crank` is a body",
            ),
            (json!({"view": "top"}), "no view `top`"),
        ] {
            let v = solve(&mut api, FOURBAR, fields);
            assert_eq!(v["stage"], "inputs", "{v}");
            let e = v["errors"][0].as_str().expect("error");
            assert!(e.contains(why), "{e}");
        }
    }

    #[test]
    fn a_sweep_traces_points_and_counts_its_gaps() {
        let v = solve(
            &mut api(),
            FOURBAR,
            json!({"sweep": "theta=0deg..360deg:36", "trace": ["coupler.c"]}),
        );
        assert_eq!(v["ok"], true, "{v}");
        assert_eq!(v["sweep"]["samples"], 37);
        let svg = v["svg"].as_str().expect("svg");
        assert!(svg.contains("<g class=\"trace t0\" data-name=\"coupler.c\">"));
        // With a long crank the four-bar does not close near theta = 0 nor near a half turn:
        // gaps, said.
        let v = solve(
            &mut api(),
            FOURBAR,
            json!({"set": ["crank_len=4.5", "theta=90deg"],
                   "sweep": "theta=0deg..360deg:36", "trace": ["coupler.c"]}),
        );
        assert_eq!(v["ok"], true, "{v}");
        let failed = v["sweep"]["failed"].as_array().expect("failed");
        assert_eq!(failed.len(), 17, "{failed:?}");
        assert_eq!(failed[0]["value"], 0.0);
        assert!(failed[0]["error"]
            .as_str()
            .expect("error")
            .contains("elbow"));
    }

    #[test]
    fn compile_gives_the_module_gcs_compile_writes() {
        let v = api().compile(FOURBAR);
        assert_eq!(
            (v["ok"].as_bool(), v["file"].as_str()),
            (Some(true), Some("fourbar.rs"))
        );
        let c = gcs_compiler::compile("examples/fourbar.gcs", FOURBAR.as_bytes()).expect("ok");
        let code = gcs_compiler::codegen::format(&gcs_compiler::codegen::generate(
            &c.model,
            &c.analysis.plan,
        ));
        assert_eq!(v["code"].as_str(), Some(code.as_str()));
        let v = api().compile("space 2d; coincident(A, B);");
        assert_eq!(v["ok"], false);
        assert!(v["errors"][0]
            .as_str()
            .expect("why")
            .starts_with("could not load"));
    }

    #[test]
    fn every_cut_of_a_model_is_answered() {
        // Every prefix of the four-bar (cut at every third character), and each with a line
        // dropped: checked, solved and compiled, each an answer and none a panic.
        let mut api = api();
        let lines: Vec<&str> = FOURBAR.lines().collect();
        let cuts = (FOURBAR.char_indices().step_by(3)).map(|(i, _)| FOURBAR[..i].to_string());
        let dropped = (0..lines.len()).map(|k| {
            let mut l = lines.clone();
            l.remove(k);
            l.join("\n")
        });
        for text in cuts.chain(dropped) {
            let body = json!({ "text": text, "set": ["theta=200deg"], "branch": ["elbow=1"] });
            for path in ["/api/check", "/api/solve", "/api/compile"] {
                let a = api.answer(path, body.to_string().as_bytes());
                assert_eq!(a.status, 200, "{path} {text:?}: {}", a.body);
                assert!(a.body["ok"].is_boolean(), "{path} {text:?}: {}", a.body);
            }
        }
    }

    #[test]
    fn malformed_requests_are_400_and_unknown_apis_404() {
        let mut api = api();
        assert_eq!(api.answer("/api/check", b"{not json").status, 400);
        assert_eq!(api.answer("/api/check", b"{\"txt\": 1}").status, 400);
        assert_eq!(
            api.answer("/api/solve", b"{\"text\": \"\", \"set\": 3}")
                .status,
            400
        );
        assert_eq!(api.answer("/api/nothing", b"{\"text\": \"\"}").status, 404);
        // A model that does not parse is an answer, not a failure of the request.
        let a = api.answer("/api/solve", b"{\"text\": \"space 2d; (((\"}");
        assert_eq!((a.status, a.body["stage"].as_str()), (200, Some("model")));
        assert!(!a.body["diagnostics"].as_array().expect("list").is_empty());
    }
}
