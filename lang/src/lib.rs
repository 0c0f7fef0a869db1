//! The `.gcs` language.
