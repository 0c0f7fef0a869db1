//! Example `.gcs` models (in this folder) and, later, programs that embed their generated solvers.
