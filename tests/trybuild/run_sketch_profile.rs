// Runs the generated solver of `examples/sketch_profile.gcs` against the interpreter.
#![deny(warnings)]

mod solver {
    include!("generated/sketch_profile.rs");
}

const NAME: &str = "sketch_profile.gcs";
const MODEL: &str = include_str!("../../examples/sketch_profile.gcs");

include!("driver.rs");
