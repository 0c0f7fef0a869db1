// Runs the generated solver of `examples/crank_rocker.gcs` against the interpreter.
#![deny(warnings)]

mod solver {
    include!("generated/crank_rocker.rs");
}

const NAME: &str = "crank_rocker.gcs";
const MODEL: &str = include_str!("../../examples/crank_rocker.gcs");

include!("driver.rs");
