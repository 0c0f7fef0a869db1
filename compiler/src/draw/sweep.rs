//! A sweep of one param (`gcs draw --sweep N=FROM..TO[:STEPS]`): its samples, solved in order
//! as a caller following one assembly solves them, and the runs of samples that solved, which
//! a traced curve draws as separate polylines.

use crate::plan::Plan;
use crate::solution::Solution;
use gcs_lang::model::GeomId;
use gcs_lang::Model;
use gcs_runtime::error::SolveError;
use std::collections::BTreeSet;

/// A sweep of one param over evenly spaced values, both ends included.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// The param's index among the model's params.
    pub param: usize,
    /// The param's name.
    pub name: String,
    /// The param's value at each sample, in order.
    pub values: Vec<f64>,
}

impl Sweep {
    /// Steps of a sweep that does not say how many: 61 samples, six degrees apart over a turn.
    pub const STEPS: usize = 60;

    /// The sweep `text` says, `NAME=FROM..TO` or `NAME=FROM..TO:STEPS`: `STEPS` intervals
    /// (so `STEPS + 1` samples, at least one step), `FROM` and `TO` expressions of the language
    /// checked as `--set` checks a value (`theta=0deg..360deg`; a bare number for an angle is
    /// radians). The error says what is wrong, in words for the command line.
    pub fn parse(model: &Model, text: &str) -> Result<Sweep, String> {
        let Some((name, range)) = text.split_once('=') else {
            return Err("expected NAME=FROM..TO or NAME=FROM..TO:STEPS".to_string());
        };
        let name = name.trim();
        let Some(id) = model.param_named(name) else {
            let names: Vec<&str> = model.params.iter().map(|(_, p)| p.name.as_str()).collect();
            return Err(format!(
                "no param `{name}`; the params are: {}",
                if names.is_empty() {
                    "(none)".to_string()
                } else {
                    names.join(", ")
                }
            ));
        };
        let (range, steps) = match range.rsplit_once(':') {
            Some((range, steps)) => match steps.trim().parse::<usize>() {
                Ok(n) if n >= 1 => (range, n),
                _ => {
                    return Err(format!(
                        "`{}`: the steps are a whole number, 1 or more",
                        steps.trim()
                    ))
                }
            },
            None => (range, Sweep::STEPS),
        };
        let Some((from, to)) = range.split_once("..") else {
            return Err(format!("`{}`: expected a range FROM..TO", range.trim()));
        };
        let value = |t: &str| gcs_lang::parse::param_value(model, id, t);
        let (from, to) = (value(from)?, value(to)?);
        let values = (0..=steps)
            .map(|k| from + (to - from) * k as f64 / steps as f64)
            .collect();
        Ok(Sweep {
            param: id.into_raw().into_u32() as usize,
            name: name.to_string(),
            values,
        })
    }
}

/// Solves `plan` (over `scope`) at every sample of `sweep`, the other params at `params`, on
/// `branches` (indexed like the plan's) at every sample: a sweep never changes a branch, and a
/// sample with no real assembly on them is an error. The first sample starts from `defaults`,
/// as `gcs solve` does (given, when `given`; else the assembly that moves least from the
/// sketch); each later one from the defaults of the last sample that solved, so that a sweep
/// of an iterated or under-constrained model follows one assembly.
#[allow(clippy::too_many_arguments)]
pub fn solve(
    model: &Model,
    plan: &Plan,
    scope: &BTreeSet<GeomId>,
    params: &[f64],
    branches: &[usize],
    defaults: &[f64],
    given: bool,
    sweep: &Sweep,
) -> Vec<Result<Solution, SolveError>> {
    let mut warm: Option<Vec<f64>> = None;
    let mut out = Vec::with_capacity(sweep.values.len());
    for &v in &sweep.values {
        let mut p = params.to_vec();
        if let Some(slot) = p.get_mut(sweep.param) {
            *slot = v;
        }
        let solved = match &warm {
            Some(d) => crate::solve_plan_with(model, plan, scope, &p, branches, d),
            None if given => crate::solve_plan_with(model, plan, scope, &p, branches, defaults),
            None => crate::all::least_motion(model, plan, scope, &p, branches, defaults),
        };
        if let Ok(s) = &solved {
            warm = Some(s.defaults.iter().map(|(_, d)| *d).collect());
        }
        out.push(solved);
    }
    out
}

/// The runs of consecutive samples that have a value, in order: a curve through the samples is
/// one polyline a run, and never joins two samples across one without a value (a failed solve).
pub fn runs<T: Clone>(samples: &[Option<T>]) -> Vec<Vec<T>> {
    let mut out: Vec<Vec<T>> = Vec::new();
    let mut open = false;
    for s in samples {
        match s {
            Some(v) if open => {
                if let Some(last) = out.last_mut() {
                    last.push(v.clone());
                }
            }
            Some(v) => {
                out.push(vec![v.clone()]);
                open = true;
            }
            None => open = false,
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_sample_splits_the_curve() {
        let s = [Some(1), Some(2), None, Some(3), Some(4), Some(5)];
        assert_eq!(runs(&s), vec![vec![1, 2], vec![3, 4, 5]]);
        // Failures at the ends and in a row make no empty run; a lone sample is a run.
        let s = [None, Some(1), None, None, Some(2), Some(3), None];
        assert_eq!(runs(&s), vec![vec![1], vec![2, 3]]);
        assert_eq!(runs::<i32>(&[None, None]), Vec::<Vec<i32>>::new());
        assert_eq!(runs(&[Some(7)]), vec![vec![7]]);
        assert_eq!(runs::<i32>(&[]), Vec::<Vec<i32>>::new());
    }

    fn model(text: &str) -> Model {
        let (_, model, diags) = gcs_lang::load("sweep.gcs", text.as_bytes());
        model.unwrap_or_else(|| panic!("{diags:?}"))
    }

    #[test]
    fn a_sweep_is_parsed_with_units_and_steps() {
        let m = model("space 2d; param len = 2; param theta = 30 deg; fixed point A = (len, 0);");
        let s = Sweep::parse(&m, "theta=0deg..180deg:4").expect("parses");
        assert_eq!((s.param, s.name.as_str()), (1, "theta"));
        let want = [0.0, 45.0, 90.0, 135.0, 180.0].map(f64::to_radians);
        assert_eq!(s.values.len(), want.len());
        for (v, w) in s.values.iter().zip(want) {
            assert!((v - w).abs() < 1e-15);
        }
        let s = Sweep::parse(&m, " len = 1 .. 2*2 ").expect("parses");
        assert_eq!(s.values.len(), Sweep::STEPS + 1);
        assert_eq!((s.values[0], s.values[Sweep::STEPS]), (1.0, 4.0));
        for (text, why) in [
            ("theta", "expected NAME=FROM..TO"),
            ("phi=0..1", "no param `phi`; the params are: len, theta"),
            ("theta=0..1:0", "the steps are a whole number"),
            ("theta=0..1:x", "the steps are a whole number"),
            ("theta=0", "expected a range FROM..TO"),
            ("len=1deg..2", "give a length"),
            ("len=1..", ""),
        ] {
            let e = Sweep::parse(&m, text).expect_err(text);
            assert!(e.contains(why), "{text}: {e}");
        }
    }
}
