//! SVG pictures: planar curves with their control polygons and curvature combs
//! ([`SvgPlot`]), and shaded triangle meshes of surfaces with curves and points drawn over
//! them ([`mesh_svg`], [`mesh_svg_with`], [`feature_overlays`]).

mod mesh;
mod plot;

pub use mesh::{
    BLUE_RIDGE_COLOUR, MeshView, PARABOLIC_COLOUR, RED_RIDGE_COLOUR, SvgOverlay, UMBILIC_COLOUR,
    feature_overlays, mesh_svg, mesh_svg_with,
};
pub use plot::SvgPlot;
