//! `cargo xtask docs`: the screenshot of `spline studio` shown in the README
//! (`docs/studio.png`), taken by the studio's browser test after it has uploaded the Clark V
//! airfoil and erased all its curvature extrema but one. Chromium is installed the same way
//! as for `cargo xtask test` when it is missing (`test_browser::ensure_chromium`).

use std::path::Path;

/// Redraws `out/studio.png`.
pub(crate) fn render(root: &Path, out: &Path) -> Result<(), String> {
    crate::test_browser::run_browser_test(root, Some(&out.join("studio.png")))
}
