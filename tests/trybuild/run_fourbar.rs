// Runs the generated solver of `examples/fourbar.gcs` against the interpreter.
#![deny(warnings)]

mod solver {
    include!("generated/fourbar.rs");
}

const NAME: &str = "fourbar.gcs";
const MODEL: &str = include_str!("../../examples/fourbar.gcs");

include!("driver.rs");
