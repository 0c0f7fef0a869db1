//! Degrees-of-freedom analysis of a `.gcs` [`gcs_lang::Model`] into a metaphorical assembly plan,
//! and the plan's consumers (interpreter, code generator, explainer). The analysis lands with
//! the DOF-analysis issue; for now the crate holds the nominal DOF count that `gcs check` prints.
