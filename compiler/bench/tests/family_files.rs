//! The family models kept under `examples/families/` are exactly what the generators write.
//! Rewrite them with `GCS_WRITE_FAMILIES=1 cargo test -p gcs-bench --test family_files`.

use gcs_bench::families::Family;
use std::path::PathBuf;

include!("../../../examples/examples_families.rs");

#[test]
fn family_files_match_their_generators() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/families");
    for &(name, n) in EXAMPLES_FAMILIES {
        let family = Family::named(name).unwrap_or_else(|| panic!("no family {name}"));
        let path = dir.join(format!("{name}_{n}.gcs"));
        let want = family.model(n);
        if std::env::var_os("GCS_WRITE_FAMILIES").is_some() {
            std::fs::write(&path, &want).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
        let have =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert!(
            have == want,
            "{} differs from its generator: rewrite it with GCS_WRITE_FAMILIES=1",
            path.display()
        );
    }
}
