// Runs the generated solver of `examples/tenbar.gcs` against the interpreter.
#![deny(warnings)]

mod solver {
    include!("generated/tenbar.rs");
}

const NAME: &str = "tenbar.gcs";
const MODEL: &str = include_str!("../../examples/tenbar.gcs");

include!("driver.rs");
