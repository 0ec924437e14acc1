//! Where the generated documents go (`cargo xtask docs`).

use std::path::Path;

/// Writes one generated document into `out_dir`.
pub(crate) fn write_doc(out_dir: &Path, name: &str, text: &str) -> Result<(), String> {
    let path = out_dir.join(name);
    std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))
}
