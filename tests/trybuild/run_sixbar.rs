// Runs the generated solver of `examples/sixbar.gcs` against the interpreter.
#![deny(warnings)]

mod solver {
    include!("generated/sixbar.rs");
}

const NAME: &str = "sixbar.gcs";
const MODEL: &str = include_str!("../../examples/sixbar.gcs");

include!("driver.rs");
