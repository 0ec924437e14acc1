//! SVG pictures of planar curves with their control polygons, curvature combs and marked
//! points.

use nalgebra::Vector2;
use spline_geom::{PlanarCurve, comb_segments, curvature_comb, evenly_spaced_params};
use std::fmt::Write;

#[derive(Clone, Debug)]
enum Element {
    Polyline {
        points: Vec<Vector2<f64>>,
        class: String,
    },
    Dots {
        points: Vec<Vector2<f64>>,
        class: String,
    },
    Segments {
        segments: Vec<(Vector2<f64>, Vector2<f64>)>,
        class: String,
    },
}

/// An SVG picture of planar geometry, drawn with equal scales on both axes and y upwards.
///
/// ```
/// use nalgebra::Vector2;
/// use spline_geom::BSpline;
/// use spline_io::svg::SvgPlot;
/// let c = BSpline::from_knots(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Vector2::new(0.0, 0.0), Vector2::new(0.5, 1.0), Vector2::new(1.0, 0.0)])?;
/// let mut plot = SvgPlot::new();
/// plot.add_curve(&c);
/// assert!(plot.render().starts_with("<svg"));
/// # Ok::<(), spline_core::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct SvgPlot {
    elements: Vec<Element>,
    title: Option<String>,
    width: f64,
}

impl SvgPlot {
    /// An empty picture, 800 pixels wide.
    #[must_use]
    pub fn new() -> Self {
        Self {
            elements: Vec::new(),
            title: None,
            width: 800.0,
        }
    }

    /// Sets a caption drawn in the top-left corner.
    pub fn set_title(&mut self, title: impl Into<String>) {
        self.title = Some(title.into());
    }

    /// Sets the width in pixels (the height follows the aspect ratio of the drawing).
    pub fn set_width(&mut self, width: f64) {
        self.width = width;
    }

    /// Draws a polyline with a CSS class: `curve`, `curve2`, `curve3`, `polygon`, `comb`,
    /// `axis`, or `c0` … `c7` (a palette for families of functions).
    pub fn add_polyline(&mut self, points: &[Vector2<f64>], class: &str) {
        self.elements.push(Element::Polyline {
            points: points.to_vec(),
            class: class.to_owned(),
        });
    }

    /// Draws points as small dots with a CSS class (`data`, `control`, `inflection`,
    /// `extremum`).
    pub fn add_markers(&mut self, points: &[Vector2<f64>], class: &str) {
        self.elements.push(Element::Dots {
            points: points.to_vec(),
            class: class.to_owned(),
        });
    }

    /// Draws line segments with a CSS class (`comb`).
    pub fn add_segments(&mut self, segments: &[(Vector2<f64>, Vector2<f64>)], class: &str) {
        self.elements.push(Element::Segments {
            segments: segments.to_vec(),
            class: class.to_owned(),
        });
    }

    /// Draws a planar curve of any kind (class `curve`) with its control polygon and
    /// control points.
    pub fn add_curve<C: PlanarCurve<f64>>(&mut self, curve: &C) {
        self.add_curve_styled(curve, "curve");
    }

    /// [`SvgPlot::add_curve`] with another CSS class for the curve.
    ///
    /// # Panics
    /// Never: the samples lie in the domain.
    pub fn add_curve_styled<C: PlanarCurve<f64>>(&mut self, curve: &C, class: &str) {
        let polygon = curve.control_polygon();
        self.add_polyline(&polygon, "polygon");
        self.add_markers(&polygon, "control");
        let params = curve.sample_params(64);
        let points = curve.eval_many(&params).expect("samples lie in the domain");
        self.add_polyline(&points, class);
    }

    /// Draws the curvature comb of a planar curve of any kind: at `samples` parameters, a
    /// tooth along the normal of length proportional to the signed curvature, scaled so the
    /// longest tooth is a fifth of the picture; the teeth's ends are joined.
    pub fn add_curvature_comb<C: PlanarCurve<f64>>(&mut self, curve: &C, samples: usize) {
        let teeth = curvature_comb(curve, &evenly_spaced_params(curve.domain(), samples));
        let (lo, hi) = bounds(&curve.control_polygon());
        // A tooth of length 0.2 · size · |κ| / max|κ|, formed without overflow.
        let size = (hi * 0.5 - lo * 0.5).amax() * 2.0;
        let segments = comb_segments(&teeth, 0.2 * size);
        if segments.is_empty() {
            return;
        }
        let ends: Vec<_> = segments.iter().map(|s| s.1).collect();
        self.add_segments(&segments, "comb");
        self.add_polyline(&ends, "comb");
    }

    /// The SVG document.
    ///
    /// # Panics
    /// Never.
    #[must_use]
    pub fn render(&self) -> String {
        let all: Vec<Vector2<f64>> = self
            .elements
            .iter()
            .flat_map(|e| match e {
                Element::Polyline { points, .. } | Element::Dots { points, .. } => points.clone(),
                Element::Segments { segments, .. } => {
                    segments.iter().flat_map(|s| [s.0, s.1]).collect()
                }
            })
            .filter(|p| p.x.is_finite() && p.y.is_finite())
            .collect();
        let (lo, hi) = if all.is_empty() {
            (Vector2::zeros(), Vector2::new(1.0, 1.0))
        } else {
            bounds(&all)
        };
        // Half extents (no overflow for coordinates near ±1e308) and a scale relative to
        // them, so that pictures of curves of size 1e-300 or 1e300 look like those of size 1.
        let half = hi * 0.5 - lo * 0.5;
        let span = half.x.max(half.y * 0.25);
        let span = if span > 0.0 && span.is_finite() {
            span
        } else {
            1.0
        };
        let margin = 20.0;
        let scale = (self.width - 2.0 * margin) / span;
        let top = if self.title.is_some() {
            margin + 24.0
        } else {
            margin
        };
        let height = ((half.y / span) * (self.width - 2.0 * margin) + margin + top).max(80.0);
        let map = |p: &Vector2<f64>| {
            let x = margin + (p.x * 0.5 - lo.x * 0.5) * scale;
            let y = height - margin - (p.y * 0.5 - lo.y * 0.5) * scale;
            format!("{x:.2},{y:.2}")
        };
        let finite = |p: &&Vector2<f64>| p.x.is_finite() && p.y.is_finite();
        let mut out = String::new();
        let _ = writeln!(
            out,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{height:.0}" viewBox="0 0 {w:.0} {height:.0}">"#,
            w = self.width
        );
        out.push_str(
            "<style>\n\
             .curve{fill:none;stroke:#1f5fbf;stroke-width:2}\n\
             .curve2{fill:none;stroke:#c0392b;stroke-width:1.5}\n\
             .curve3{fill:none;stroke:#27ae60;stroke-width:1.5;stroke-dasharray:6 3}\n\
             .polygon{fill:none;stroke:#999;stroke-width:1;stroke-dasharray:4 3}\n\
             .control{fill:#666}\n.data{fill:#e67e22}\n\
             .comb{fill:none;stroke:#8e44ad;stroke-width:0.6}\n\
             .inflection{fill:#c0392b}\n.extremum{fill:#27ae60}\n\
             .c0{fill:none;stroke:#1f77b4;stroke-width:2}\n.c1{fill:none;stroke:#ff7f0e;stroke-width:2}\n\
             .c2{fill:none;stroke:#2ca02c;stroke-width:2}\n.c3{fill:none;stroke:#d62728;stroke-width:2}\n\
             .c4{fill:none;stroke:#9467bd;stroke-width:2}\n.c5{fill:none;stroke:#8c564b;stroke-width:2}\n\
             .c6{fill:none;stroke:#e377c2;stroke-width:2}\n.c7{fill:none;stroke:#7f7f7f;stroke-width:2}\n\
             .axis{fill:none;stroke:#444;stroke-width:0.8}\n\
             text{font:14px sans-serif;fill:#333}\n</style>\n",
        );
        out.push_str(r#"<rect width="100%" height="100%" fill="white"/>"#);
        out.push('\n');
        for e in &self.elements {
            match e {
                Element::Polyline { points, class } => {
                    let pts: Vec<String> = points.iter().filter(finite).map(map).collect();
                    let _ = writeln!(
                        out,
                        r#"<polyline class="{class}" points="{}"/>"#,
                        pts.join(" ")
                    );
                }
                Element::Dots { points, class } => {
                    let r = if class == "data" || class == "control" {
                        2.5
                    } else {
                        4.5
                    };
                    for p in points.iter().filter(finite) {
                        let xy = map(p);
                        let (x, y) = xy.split_once(',').expect("x,y");
                        let _ = writeln!(
                            out,
                            r#"<circle class="{class}" cx="{x}" cy="{y}" r="{r}"/>"#
                        );
                    }
                }
                Element::Segments { segments, class } => {
                    let mut d = String::new();
                    for (a, b) in segments.iter().filter(|(a, b)| finite(&a) && finite(&b)) {
                        let _ = write!(d, "M{}L{}", map(a), map(b));
                    }
                    let _ = writeln!(out, r#"<path class="{class}" d="{d}"/>"#);
                }
            }
        }
        if let Some(title) = &self.title {
            let escaped = title
                .replace('&', "&amp;")
                .replace('<', "&lt;")
                .replace('>', "&gt;");
            let _ = writeln!(out, r#"<text x="{margin}" y="16">{escaped}</text>"#);
        }
        out.push_str("</svg>\n");
        out
    }
}

fn bounds(points: &[Vector2<f64>]) -> (Vector2<f64>, Vector2<f64>) {
    let mut lo = Vector2::repeat(f64::INFINITY);
    let mut hi = Vector2::repeat(f64::NEG_INFINITY);
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    (lo, hi)
}
