//! Writes the five arm models into `models/` (see `gcs_ikgeo::model`).

fn main() -> std::io::Result<()> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    for arm in &gcs_ikgeo::arms::ARMS {
        let path = dir.join(gcs_ikgeo::model::file_name(arm));
        let text = gcs_ikgeo::model::text(arm, &gcs_ikgeo::model::comment(arm));
        std::fs::write(&path, text)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
