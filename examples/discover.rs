// The workspace's `.gcs` models, found from their folders: the one place that knows where
// models live and which of them the analysis covers. Brought in with `include!` inside a module
// by everything that needs it (`examples/build.rs`, and the generated-code, CLI, plan,
// canonicity, baseline and family tests):
//
//     mod discover {
//         include!("../../examples/discover.rs");
//     }
//
// It needs `gcs-lang` (to read each model's space), so no inner attributes here.
//
// The folders, under the workspace root:
// - `examples/`: the example models;
// - `examples/sketches/`: everyday CAD sketches, examples in every respect (kept apart so that
//   the mechanisms stay easy to find);
// - `examples/families/`: members of the generated model families at the sizes the benches
//   use, named `<family>_<n>.gcs`;
// - `tests/models/`: models that only tests use (golden generated solvers, run against the
//   interpreter); the folder may be absent.
//
// A file's stem names its solver module, its goldens and its test cases, so stems are unique
// across all the folders (asserted).

use std::path::{Path, PathBuf};

/// A folder of models.
#[allow(dead_code)] // every user needs some of this file, none all of it
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Folder {
    /// `examples/`: the example models.
    Examples,
    /// `examples/sketches/`: everyday sketches, examples in every respect.
    Sketches,
    /// `examples/families/`: members of the generated model families, `<family>_<n>.gcs`.
    Families,
    /// `tests/models/`: models that only tests use.
    TestModels,
    /// `ikgeo/models/`: ik-geo's arms, written by `ikgeo/src/model.rs` for the comparison with
    /// ik-geo; the workspace's tests use them as test models.
    Arms,
}

#[allow(dead_code)]
impl Folder {
    /// Every folder, in the order their models are listed.
    pub const ALL: [Folder; 5] = [
        Folder::Examples,
        Folder::Sketches,
        Folder::Families,
        Folder::TestModels,
        Folder::Arms,
    ];

    /// Whether its models are examples: `examples/` and `examples/sketches/`.
    pub fn is_example(self) -> bool {
        matches!(self, Folder::Examples | Folder::Sketches)
    }

    /// The folder, relative to the workspace root.
    pub fn dir(self) -> &'static str {
        match self {
            Folder::Examples => "examples",
            Folder::Sketches => "examples/sketches",
            Folder::Families => "examples/families",
            Folder::TestModels => "tests/models",
            Folder::Arms => "ikgeo/models",
        }
    }
}

/// The models the analysis does not solve yet, each with why: found everywhere, golden and
/// run nowhere, and tested to be refused with a reason until they are solved.
#[allow(dead_code)]
pub const NOT_YET: &[&str] = &[];

/// A model found on disk.
#[allow(dead_code)]
#[derive(Clone, Debug)]
pub struct Found {
    /// The file stem (`fourbar`), unique across the folders.
    pub stem: String,
    /// The folder it was found in.
    pub folder: Folder,
    /// Its path: the workspace root given to [`models`] joined with the folder and file name.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// The space its model declares, as `gcs_lang::load` reads it.
    pub space: gcs_lang::model::Space,
}

#[allow(dead_code)]
impl Found {
    /// Whether the analysis solves this model today: the one filter between "found" and
    /// "golden and run" (`check`, `explain`, `plan`, `solve`). Every model but those of
    /// [`NOT_YET`].
    pub fn is_analysed(&self) -> bool {
        !NOT_YET.contains(&self.stem.as_str())
    }


    /// The file name: `fourbar.gcs`.
    pub fn file_name(&self) -> String {
        format!("{}.gcs", self.stem)
    }

    /// The path relative to the workspace root: `examples/fourbar.gcs`.
    pub fn relative(&self) -> String {
        format!("{}/{}.gcs", self.folder.dir(), self.stem)
    }

    /// The model's leading `//` comment lines, without the slashes: what the model is.
    pub fn description(&self) -> Vec<&str> {
        self.text
            .lines()
            .map_while(|line| line.strip_prefix("//"))
            .map(|line| line.strip_prefix(' ').unwrap_or(line).trim_end())
            .collect()
    }
}

/// Every model of every folder under the workspace `root`, in name order. A model that does not
/// load is a panic showing its diagnostics (every model here checks clean), as is a stem found
/// twice or an empty `examples/`; an absent `tests/models/` has no models.
#[allow(dead_code)]
pub fn models(root: &Path) -> Vec<Found> {
    let mut found = Vec::new();
    for folder in Folder::ALL {
        let dir = root.join(folder.dir());
        let entries = match std::fs::read_dir(&dir) {
            Ok(entries) => entries,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound && folder == Folder::TestModels => {
                continue;
            }
            Err(e) => panic!("cannot read {}: {e}", dir.display()),
        };
        for entry in entries {
            let path = entry
                .unwrap_or_else(|e| panic!("cannot read {}: {e}", dir.display()))
                .path();
            if path.extension().is_none_or(|e| e != "gcs") || !path.is_file() {
                continue;
            }
            let stem = path
                .file_stem()
                .and_then(|s| s.to_str())
                .unwrap_or_else(|| panic!("{}: the file name is not UTF-8", path.display()))
                .to_string();
            let bytes = std::fs::read(&path)
                .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
            let (source, model, diags) = gcs_lang::load(&format!("{stem}.gcs"), &bytes);
            let Some(model) = model else {
                panic!(
                    "{} does not load:\n{}",
                    path.display(),
                    gcs_lang::diagnostic::render_plain(&source, &diags)
                );
            };
            found.push(Found {
                stem,
                folder,
                path,
                text: source.text().to_string(),
                space: model.space,
            });
        }
    }
    assert!(
        found.iter().any(|m| m.folder == Folder::Examples),
        "no models under {}",
        root.join("examples").display()
    );
    found.sort_by(|a, b| a.stem.cmp(&b.stem));
    for pair in found.windows(2) {
        assert!(
            pair[0].stem != pair[1].stem,
            "two models are named `{}`: {} and {} (a stem names a solver module and its goldens, \
             so it must be unique across {})",
            pair[0].stem,
            pair[0].relative(),
            pair[1].relative(),
            Folder::ALL.map(Folder::dir).join(", ")
        );
    }
    found
}

/// The models of `folder` the analysis covers ([`Found::is_analysed`]), in name order; for
/// [`Folder::Examples`], every example, the sketches' included.
#[allow(dead_code)]
pub fn analysed(root: &Path, folder: Folder) -> Vec<Found> {
    models(root)
        .into_iter()
        .filter(|m| {
            let wanted = m.folder == folder || (folder.is_example() && m.folder.is_example());
            wanted && m.is_analysed()
        })
        .collect()
}

