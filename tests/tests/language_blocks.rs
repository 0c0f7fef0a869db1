//! Every ```gcs block of the language contract (`../shared/LANGUAGE.md`) and of the project's
//! reference (`docs/LANGUAGE.md`) checks clean, and every shared example lives in `examples/`.

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The ```gcs blocks of a Markdown file, with the line each starts on.
fn gcs_blocks(markdown: &str) -> Vec<(usize, String)> {
    let mut blocks = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for (i, line) in markdown.lines().enumerate() {
        match &mut current {
            None if line.trim_start() == "```gcs" => current = Some((i + 2, String::new())),
            Some(_) if line.trim_start() == "```" => blocks.extend(current.take()),
            Some((_, text)) => {
                text.push_str(line);
                text.push('\n');
            }
            None => {}
        }
    }
    blocks
}

/// Loads a model and fails with its rendered diagnostics unless it has no error and no warning.
fn assert_clean(name: &str, text: &str) {
    let (source, model, diags) = gcs_lang::load(name, text.as_bytes());
    assert!(
        model.is_some() && diags.is_empty(),
        "{name} does not check clean:\n{}",
        gcs_lang::diagnostic::render_plain(&source, &diags)
    );
}

#[test]
fn project_reference_blocks_check_clean() {
    let text = std::fs::read_to_string(root().join("docs/LANGUAGE.md")).expect("docs/LANGUAGE.md");
    let blocks = gcs_blocks(&text);
    assert!(
        blocks.len() >= 10,
        "docs/LANGUAGE.md has only {} gcs blocks",
        blocks.len()
    );
    for (line, block) in blocks {
        assert_clean(&format!("docs/LANGUAGE.md:{line}"), &block);
    }
}

#[test]
fn shared_contract_blocks_check_clean_and_live_in_examples() {
    let shared = root().join("../shared/LANGUAGE.md");
    let Ok(text) = std::fs::read_to_string(&shared) else {
        // The contract sits beside the repository in CI; a bare clone has only the copy in
        // docs/LANGUAGE.md, which the test above covers.
        eprintln!(
            "note: {} not found; checked docs/LANGUAGE.md only",
            shared.display()
        );
        return;
    };
    let reference =
        std::fs::read_to_string(root().join("docs/LANGUAGE.md")).expect("docs/LANGUAGE.md");
    let blocks = gcs_blocks(&text);
    assert_eq!(
        blocks.len(),
        5,
        "the contract's examples changed: update examples/"
    );
    let files = [
        "fourbar",
        "brick",
        "circle",
        "slider_crank",
        "points_planes",
    ];
    for ((line, block), file) in blocks.iter().zip(files) {
        assert_clean(&format!("shared/LANGUAGE.md:{line}"), block);
        let path = root().join(format!("examples/{file}.gcs"));
        let example = std::fs::read_to_string(&path).expect("example file");
        assert_eq!(
            &example,
            block,
            "{} differs from the contract's block at line {line}",
            path.display()
        );
        assert!(
            reference.contains(block.as_str()),
            "docs/LANGUAGE.md lacks the block of line {line}"
        );
    }
}

#[test]
fn every_example_checks_clean() {
    let mut count = 0;
    for entry in std::fs::read_dir(root().join("examples")).expect("examples/") {
        let path = entry.expect("entry").path();
        if path.extension().is_some_and(|e| e == "gcs") {
            let text = std::fs::read_to_string(&path).expect("example");
            assert_clean(&path.display().to_string(), &text);
            count += 1;
        }
    }
    assert!(count >= 5, "only {count} examples found");
}
