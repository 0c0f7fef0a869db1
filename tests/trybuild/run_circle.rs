// Runs the generated solver of `examples/circle.gcs` against the interpreter.
#![deny(warnings)]

mod solver {
    include!("generated/circle.rs");
}

const NAME: &str = "circle.gcs";
const MODEL: &str = include_str!("../../examples/circle.gcs");

include!("driver.rs");
