// Runs the generated solver of `examples/slider_crank_2d.gcs` against the interpreter.
#![deny(warnings)]

mod solver {
    include!("generated/slider_crank_2d.rs");
}

const NAME: &str = "slider_crank_2d.gcs";
const MODEL: &str = include_str!("../../examples/slider_crank_2d.gcs");

include!("driver.rs");
