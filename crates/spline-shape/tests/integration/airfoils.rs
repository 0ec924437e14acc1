//! The shipped airfoils (`data/airfoils/`) as the eraser's tests read them.

use nalgebra::Vector2;
use spline_io::points::parse_points;

/// The points of `data/airfoils/{path}.dat`.
pub(crate) fn airfoil(path: &str) -> Vec<Vector2<f64>> {
    let path = format!(
        "{}/../../data/airfoils/{path}.dat",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap();
    parse_points(&text)
        .unwrap()
        .into_iter()
        .map(|p| Vector2::new(p[0], p[1]))
        .collect()
}
