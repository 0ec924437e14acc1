//! IGES 5.3 (Initial Graphics Exchange Specification) files in and out: fixed-format ASCII
//! files of 80-column records, B-spline curves (entity 126) and surfaces (entity 128).
//!
//! A file is five sections, each record marked by its letter in column 73 and its sequence
//! number in columns 74–80: Start (`S`, free text), Global (`G`: the delimiters, units,
//! precision…), Directory Entry (`D`: two records of ten 8-column fields per entity),
//! Parameter Data (`P`: each entity's parameters in columns 1–64, its directory-entry
//! pointer in columns 65–72) and Terminate (`T`: the record counts).
//!
//! # Reading
//! [`read_iges`] returns, in directory order, every rational B-spline curve (126) and
//! surface (128) of the file, and converts exactly to NURBS the entities whose conversion
//! is exact and simple: the line segment (110, form 0), the circular arc (100), the surface
//! of revolution (120) and the tabulated cylinder (122) when their curves convert. Every
//! other entity (the B-rep of Open CASCADE: 186, 514, 510, 508, 504, 502; trimmed surfaces
//! 144 and 142, composite curves 102, conics 104, planes 108, the analytic surfaces
//! 190–198, properties, annotations…) is skipped without error. Curves referenced by a
//! 120 or 122 are returned on their own as well.
//!
//! - [`Item::id`] is the sequence number of the entity's first directory-entry record (an odd
//!   number), [`Item::entity`] the entity type number as text (`"126"`, `"110"`…),
//!   [`Item::name`] the name of a name property (406 form 15) the entity points to, else
//!   its directory-entry label (8 columns, blanks trimmed).
//! - Curves are read as 3-D curves, planar ones too (a 126 with `PROP1 = 1` and all `z = 0`
//!   is a 3-D curve in the plane `z = 0`); a curve is polynomial ([`crate::Geometry::Curve3`]) when
//!   `PROP3 = 1` and its weights are equal, rational otherwise; likewise for surfaces.
//! - A transformation matrix (entity 124) referenced from a directory entry, and the chain
//!   of matrices the 124 itself references, is applied to the control points (affine maps
//!   commute with B-spline and NURBS evaluation, so this is exact up to rounding).
//! - A parameter range `V(0), V(1)` (surfaces: `U(0), U(1), V(0), V(1)`) narrower than the
//!   knot domain restricts the geometry to it exactly, by knot insertion; a range reaching
//!   outside the domain is intersected with the domain (writers round it).
//! - Coordinates are returned in the file's model units; the units of the Global section are
//!   checked for syntax but not applied.
//!
//! # Writing
//! [`write_iges`] writes each item as a 126 or a 128 (polynomial: `PROP3 = 1` and unit
//! weights; rational: the weights; 2-D curves as planar curves in `z = 0` with the normal
//! `(0, 0, 1)`), on its full knot domain, numbers in the shortest decimal form that reads
//! back to the same `f64` (`1.5E-7`), strings as Hollerith constants, model units
//! millimetres. The item's name goes into the 8-column label (truncated) and, when longer,
//! into a name property (406 form 15) the entity points to.
//!
//! # Errors
//! Every error is one line naming the section and the sequence number of the record:
//! `IGES line 57 (P): …` (`IGES file line 12: …` when the record's section is unknown).
//! Counts read from the file are checked against the number of parameters present before
//! anything is allocated.
//!
//! ```
//! use nalgebra::Vector3;
//! use spline_geom::BSpline;
//! use spline_io::iges::{read_iges, write_iges};
//! use spline_io::{Geometry, Item};
//! let line = BSpline::from_knots(1, vec![0.0, 0.0, 1.0, 1.0],
//!     vec![Vector3::new(0.0, 0.0, 0.0), Vector3::new(1.0, 2.0, 3.0)])?;
//! let item = Item { id: 0, name: "edge".into(), entity: String::new(), geometry: Geometry::Curve3(line) };
//! let text = write_iges(&[item.clone()])?;
//! let back = read_iges(&text)?;
//! assert_eq!(back[0].geometry, item.geometry);
//! assert_eq!((back[0].id, back[0].name.as_str(), back[0].entity.as_str()), (1, "edge", "126"));
//! # Ok::<(), spline_core::Error>(())
//! ```

mod affine;
mod directory;
mod entities;
mod layout;
mod sections;
mod tokens;
mod write;

pub use write::write_iges;

use crate::Item;
use directory::{File, parse_entries};
use entities::Read;
use sections::{check_ascii, split_sections};
use spline_core::{Error, ErrorKind, Result};
use tokens::parse_global;

/// Reads an IGES 5.3 file from bytes: as [`read_iges`], after checking that every byte is
/// ASCII.
///
/// # Errors
/// [`ErrorKind::Parse`] naming the line and column of the first byte that is not ASCII;
/// the errors of [`read_iges`].
pub fn read_iges_bytes(bytes: &[u8]) -> Result<Vec<Item>> {
    check_ascii(bytes)?;
    let text = std::str::from_utf8(bytes)
        .map_err(|_| Error::new(ErrorKind::Parse, "IGES file line 1: the file is not text"))?;
    read_iges(text)
}

/// Reads the B-spline geometry of an IGES 5.3 fixed-format ASCII file (see the
/// [module documentation](self) for what is read and how).
///
/// # Errors
/// [`ErrorKind::Parse`] with a message `IGES line N (X): …` for a malformed file: records
/// that are not 80 columns with a section letter, sections out of order or truncated
/// (the Terminate record's counts), sequence numbers out of order, bad delimiters or
/// numbers, pointers outside the file, transformation matrices referencing each other in a
/// cycle, counts that the parameters present do not match, non-ASCII text; the errors of
/// the geometry constructors (unsorted knots, non-positive weights…) prefixed with the
/// record.
pub fn read_iges(text: &str) -> Result<Vec<Item>> {
    check_ascii(text.as_bytes())?;
    let sections = split_sections(text)?;
    let delimiters = parse_global(&sections.global)?;
    let file = File {
        entries: parse_entries(&sections.directory)?,
        parameter: sections.parameter,
        delimiters,
        chains: std::cell::RefCell::default(),
    };
    let mut items = Vec::new();
    for entry in &file.entries {
        let (read, params) = file.convert(entry, 0)?;
        let geometry = match read {
            Read::Curve(c) => c.geometry(),
            Read::Patch(s) => s.geometry(),
            Read::Skipped => continue,
        };
        let mut name = entry.label.clone();
        if let (Some(mut params), 126 | 128) = (params, entry.kind) {
            if let Some(n) = file.property_name(&mut params, entry)? {
                name = n;
            }
        }
        items.push(Item {
            id: entry.seq as u64,
            name,
            entity: entry.kind.to_string(),
            geometry,
        });
    }
    Ok(items)
}
