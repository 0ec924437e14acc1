//! The classic constructions of seed 004 §5.2 and §6: cylindrical (extruded), ruled and
//! conical surfaces (5.14)–(5.17); conic arcs (6.6)–(6.7) with the classification of
//! Proposition 6.1; circular arcs (6.8) of any sweep; the full circle both ways of the notes
//! ((6.9)–(6.10) and the equilateral triangle); surfaces of revolution (6.11)–(6.12), the
//! sphere (6.13)–(6.14) and the torus.
//!
//! Every construction is exact: the rational constructions reproduce circles and conics
//! up to rounding only.

mod arcs;
mod checks;
mod compatible;
mod coons;
mod frames;
mod placement;
mod surfaces;
mod vectors;

pub use arcs::{CircleConstruction, ConicKind, MAX_ARC_PIECES};
pub use compatible::{boolean_sum, compatible_curves, compatible_surfaces};
pub use frames::{MovingFrame, rotation_minimizing_frames};
pub use placement::{Axis, Frame};
