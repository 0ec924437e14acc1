//! The reading context shared by the readers of splines and analytic entities: the instances
//! by `#id`, references to them resolved with the line that refers to them.

use super::instance::{Instance, Param, error_at, number};
use spline_core::Result;
use std::collections::HashMap;

/// Reading context: the instances and the names given to geometry by faces and edges.
pub(super) struct Reader<'a> {
    pub(super) instances: &'a HashMap<u64, Instance>,
}

impl Reader<'_> {
    pub(super) fn get(&self, id: u64, from: usize) -> Result<&Instance> {
        self.instances
            .get(&id)
            .ok_or_else(|| error_at(from, format!("#{id} is referenced but not defined")))
    }

    pub(super) fn point(&self, param: &Param, from: usize) -> Result<Vec<f64>> {
        let Param::Reference(id) = param else {
            return Err(error_at(from, "expected a reference to a CARTESIAN_POINT"));
        };
        let instance = self.get(*id, from)?;
        let Some(p) = instance.record("CARTESIAN_POINT") else {
            return Err(error_at(
                instance.line,
                format!("#{id} is not a CARTESIAN_POINT"),
            ));
        };
        let coords = match p {
            [_, Param::List(c)] => c,
            _ => {
                return Err(error_at(
                    instance.line,
                    format!("#{id}: CARTESIAN_POINT needs a name and a list of coordinates"),
                ));
            }
        };
        let out: Vec<f64> = coords
            .iter()
            .map(|c| {
                number(c).ok_or_else(|| {
                    error_at(
                        instance.line,
                        format!("#{id}: a coordinate is not a number"),
                    )
                })
            })
            .collect::<Result<_>>()?;
        if !(2..=3).contains(&out.len()) {
            return Err(error_at(
                instance.line,
                format!("#{id}: a point needs 2 or 3 coordinates, got {}", out.len()),
            ));
        }
        Ok(out)
    }
}
