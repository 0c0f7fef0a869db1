/// Members of the generated model families (`gcs_bench::families`) at the sizes the
/// benchmarks and `gcs bench` use, by file stem under `families/`: each file is the generator's
/// output, kept in step by `compiler/bench/tests/family_files.rs`. `build.rs` compiles them into
/// solvers like the examples.
const EXAMPLES_FAMILIES: &[(&str, usize)] = &[
    ("fourbar_chain", 16),
    ("fourbar_chain", 128),
    ("sketch_profile", 16),
    ("truss", 16),
];
