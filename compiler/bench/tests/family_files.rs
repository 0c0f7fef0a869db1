//! The family models kept under `examples/families/` (`<family>_<n>.gcs`) are exactly what
//! the generators write at those sizes. Rewrite them with
//! `GCS_WRITE_FAMILIES=1 cargo test -p gcs-bench --test family_files`; add one with
//! `cargo run -p gcs-bench --example family -- NAME N > examples/families/NAME_N.gcs`.

use gcs_bench::families::Family;

mod discover {
    include!("../../../examples/discover.rs");
}

#[test]
fn family_files_match_their_generators() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let members: Vec<_> = discover::models(&root)
        .into_iter()
        .filter(|m| m.folder == discover::Folder::Families)
        .collect();
    assert!(
        !members.is_empty(),
        "no family models under examples/families"
    );
    for m in members {
        let (name, n) = m
            .stem
            .rsplit_once('_')
            .and_then(|(name, n)| Some((name, n.parse::<usize>().ok()?)))
            .unwrap_or_else(|| panic!("{}: not named `<family>_<n>.gcs`", m.relative()));
        let family =
            Family::named(name).unwrap_or_else(|| panic!("{}: no family `{name}`", m.relative()));
        let want = family.model(n);
        if std::env::var_os("GCS_WRITE_FAMILIES").is_some() {
            std::fs::write(&m.path, &want).unwrap_or_else(|e| panic!("{}: {e}", m.path.display()));
        } else {
            assert!(
                m.text == want,
                "{} differs from its generator: rewrite it with GCS_WRITE_FAMILIES=1",
                m.relative()
            );
        }
    }
}
