// Runs the generated solver of `examples/jansen_leg.gcs` against the interpreter.
#![deny(warnings)]

mod solver {
    include!("generated/jansen_leg.rs");
}

const NAME: &str = "jansen_leg.gcs";
const MODEL: &str = include_str!("../../examples/jansen_leg.gcs");

include!("driver.rs");
