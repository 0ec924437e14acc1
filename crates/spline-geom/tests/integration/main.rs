//! The integration tests of spline-geom, one module per former test file, linked into one
//! test binary (one link instead of one per file: the cold CI build is dominated by links).

#![allow(unreachable_pub)]

mod arclength_cost;
mod constructions;
mod constructions_surfaces;
mod curves;
mod curves_examples;
mod in_place;
mod lanes;
mod nurbs;
mod nurbs_examples;
mod periodic;
mod periodic_refine;
mod pieces;
mod rational_coons;
mod reference_surfaces;
mod surface_evaluator;
mod surface_mesh;
mod surfaces;
mod surfaces_examples;
