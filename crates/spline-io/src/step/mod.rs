//! STEP files (ISO 10303-21 exchange structure, AP214/AP242 geometry) in and out.
//!
//! # Reading
//! [`read_step`] parses the `DATA` section in one pass (time and memory linear in the size of
//! the file: the instances are kept as parsed, with their line, in a map by `#id`), then
//! returns, in the order of their instance numbers, every B-spline curve
//! (`B_SPLINE_CURVE_WITH_KNOTS`, its rational complex instance with `RATIONAL_B_SPLINE_CURVE`,
//! `BEZIER_CURVE`, `UNIFORM_CURVE`, `QUASI_UNIFORM_CURVE`) and every B-spline surface (the
//! same forms of `B_SPLINE_SURFACE`), in 2-D or 3-D. The geometry of a B-rep comes out the
//! same way: the surfaces of the faces (`ADVANCED_FACE`, named after the face) and the curves
//! of the edges (`EDGE_CURVE`, named after the edge), analytic ones converted exactly to
//! NURBS (module `analytic`: lines, circles, ellipses, planes, cylinders, cones, spheres,
//! tori, surfaces of revolution and of linear extrusion); everything that is not geometry
//! (products, contexts, units, topology, presentation) is skipped. `TRIMMED_CURVE` and
//! `RECTANGULAR_TRIMMED_SURFACE` give their basis geometry (their trims are not applied).
//!
//! - [`Item::id`] is the instance number (`#17` → 17), [`Item::entity`] the entity read
//!   (`B_SPLINE_CURVE_WITH_KNOTS`, `B_SPLINE_SURFACE_WITH_KNOTS`, …), [`Item::name`] the name
//!   of the face or edge that holds the geometry when it has one, else the geometry's own
//!   `name` attribute. Curves of the parameter planes (`PCURVE`s' definitional
//!   representations) are not returned.
//! - Curves whose points have two coordinates are 2-D, three 3-D; a rational curve or surface
//!   whose weights are all equal is still returned as rational (the file says so).
//!
//! No Part 21 crate is used: the crates on crates.io for ISO 10303-21 either generate code
//! for whole schemas (large and slow to build for the handful of geometric entities read
//! here) or stopped at syntax without line numbers in their errors; the exchange structure's
//! syntax (instances, lists, strings, enumerations, typed parameters) takes one small
//! tokenizer.
//!
//! # Writing
//! [`write_step`] writes an AP214 file (`AUTOMOTIVE_DESIGN`) as CAD systems write loose
//! geometry: one product with its definition, curves in a `GEOMETRIC_CURVE_SET` of a
//! `GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION`, surfaces in a `GEOMETRIC_SET` of a
//! `GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION`, in millimetres; B-splines as
//! `B_SPLINE_CURVE_WITH_KNOTS` / `B_SPLINE_SURFACE_WITH_KNOTS` (distinct knots with their
//! multiplicities), rational ones as the complex instance with their weights; numbers in the
//! shortest decimal form that reads back to the same `f64` (`1.5E-07`), so a round trip
//! through the file is exact. 2-D curves are written in the plane `z = 0` (CAD systems read
//! 3-D geometry only) and so read back as 3-D curves.
//!
//! # Errors
//! Every error is one line that names the line of the file (`STEP line 123: …`) and, where
//! one is concerned, the instance (`#17`). Counts are never read from the file: lists grow
//! with what the file holds; references are resolved with a depth limit (a cycle of
//! references is an error, not a hang).
//!
//! ```
//! use nalgebra::Vector3;
//! use spline_geom::BSpline;
//! use spline_io::step::{read_step, write_step};
//! use spline_io::{Geometry, Item};
//! let line = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
//!     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 2.0, 3.0)])?;
//! let item = Item { id: 0, name: "edge".into(), entity: String::new(), geometry: Geometry::Curve3(line) };
//! let text = write_step(&[item.clone()])?;
//! let back = read_step(&text)?;
//! assert_eq!(back[0].geometry, item.geometry);
//! assert_eq!(back[0].name, "edge");
//! # Ok::<(), spline_core::Error>(())
//! ```

mod analytic;
mod instance;
mod lexer;
mod parser;
mod reader;
mod splines;
mod write;

pub use write::write_step;

use crate::Item;
use instance::{Instance, Param, underlying};
use reader::Reader;
use spline_core::{Error, Result};
use std::collections::{BTreeMap, HashMap};

/// Every B-spline curve and surface of a STEP file; see the [module](self) documentation.
///
/// # Errors
/// [`ErrorKind::Parse`] with the line (and instance) for what cannot be read: broken syntax,
/// a truncated file, a reference to an undefined instance, B-spline data that do not form a
/// valid spline (wrong counts, bad knots, non-positive weights).
///
/// [`ErrorKind::Parse`]: spline_core::ErrorKind::Parse
pub fn read_step(text: &str) -> Result<Vec<Item>> {
    read_step_bytes(text.as_bytes())
}

/// [`read_step`] on bytes: a byte outside ASCII is reported with its line.
///
/// # Errors
/// As [`read_step`].
pub fn read_step_bytes(bytes: &[u8]) -> Result<Vec<Item>> {
    let instances = parser::parse(bytes)?;
    let reader = Reader {
        instances: &instances,
    };
    // Names from the topology: faces name their surfaces, edges their curves.
    let mut names: HashMap<u64, String> = HashMap::new();
    for instance in instances.values() {
        for (entity, at) in [("ADVANCED_FACE", 2), ("FACE_SURFACE", 2), ("EDGE_CURVE", 3)] {
            if let Some(p) = instance.record(entity) {
                if let (Some(Param::Text(name)), Some(Param::Reference(g))) = (p.first(), p.get(at))
                {
                    if !name.is_empty() {
                        if let Some(target) = underlying(&instances, *g) {
                            names.entry(target).or_insert_with(|| name.clone());
                        }
                    }
                }
            }
        }
    }
    // Curves in the parameter planes of surfaces (the PCURVEs' definitional
    // representations) are not geometry of the model.
    let mut parametric: std::collections::HashSet<u64> = std::collections::HashSet::new();
    // Likewise the profiles of swept surfaces, which are part of the surface's definition
    // (an edge that runs along one has a curve of its own).
    for instance in instances.values() {
        for swept in ["SURFACE_OF_REVOLUTION", "SURFACE_OF_LINEAR_EXTRUSION"] {
            if let Some([_, Param::Reference(r), ..]) = instance.record(swept) {
                parametric.insert(*r);
            }
        }
    }
    for instance in instances.values() {
        if let Some([_, Param::List(items), ..]) = instance.record("DEFINITIONAL_REPRESENTATION") {
            parametric.extend(items.iter().filter_map(|i| match i {
                Param::Reference(r) => Some(*r),
                _ => None,
            }));
        }
    }
    let ordered: BTreeMap<u64, &Instance> = instances
        .iter()
        .filter(|(k, _)| !parametric.contains(k))
        .map(|(k, v)| (*k, v))
        .collect();
    let mut out = Vec::new();
    for (&id, instance) in &ordered {
        if let Some(parts) = splines::curve_parts(instance)? {
            let geometry =
                splines::read_curve(&reader, instance, &parts).map_err(|e| add_instance(e, id))?;
            let name = names.get(&id).cloned().unwrap_or(parts.name);
            out.push(Item {
                id,
                name,
                entity: parts.entity.to_string(),
                geometry,
            });
        } else if let Some((geometry, own, entity)) =
            splines::read_surface(&reader, instance).map_err(|e| add_instance(e, id))?
        {
            let name = names.get(&id).cloned().unwrap_or(own);
            out.push(Item {
                id,
                name,
                entity: entity.to_string(),
                geometry,
            });
        }
    }
    out.extend(analytic::analytic_items(&reader, &names)?);
    out.sort_by_key(|item| item.id);
    Ok(out)
}

/// Adds the instance to a message that names only the line.
fn add_instance(e: Error, id: u64) -> Error {
    let message = e.to_string();
    if message.contains(&format!("#{id}")) {
        return e;
    }
    match message.split_once(": ") {
        Some((head, rest)) if head.starts_with("STEP line") => {
            Error::new(e.kind(), format!("{head}: #{id}: {rest}"))
        }
        _ => e,
    }
}
