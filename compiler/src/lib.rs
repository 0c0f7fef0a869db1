//! Degrees-of-freedom analysis of a `.gcs` [`gcs_lang::Model`] into a metaphorical assembly
//! plan, and the plan's consumers (interpreter, code generator, explainer).
//!
//! The analysis itself lands with the DOF-analysis issue; today the crate holds the nominal DOF
//! count that `gcs check` prints. Like every library crate here, it never prints or exits: it
//! returns values and text for the CLI to show.

pub mod nominal;
