//! `spline studio`: the interactive curve-design labs of seed 003 (ENSIMAG TDsm 1–3) as a
//! local web page over the library.
//!
//! [`run`] serves one page — HTML, JavaScript and SVG embedded in the binary, no build step,
//! nothing fetched from the network — and the JSON endpoints of [`api`], bound to loopback
//! unless the caller says otherwise. On the page one places points with the mouse, drags and
//! deletes them, undoes, and switches between the labs:
//!
//! - **Bézier** (TD1): the curve by de Casteljau's algorithm, the construction at a
//!   parameter moved by a slider, the subdivision there, degree elevation;
//! - **B-spline**: the degree, the knot vector drawn under the curve, knot insertion by a
//!   click on it;
//! - **interpolation** (TD2): uniform, chord-length and centripetal parameters side by side
//!   (a Bézier curve of degree `n`, or a B-spline of a chosen degree);
//! - **approximation** (TD3): least squares with `N` control points (or a Bézier curve of a
//!   chosen degree), parameter correction one sweep at a time or until convergence, with the
//!   projections `x(t_k)` of the data drawn;
//! - **curvature**: the comb and the curvature plot, inflections and curvature extrema
//!   marked, and the selective eraser of extrema (thesis ch. 6) before and after;
//! - loading an airfoil `.dat`, a point file or a JSON curve, exporting JSON and SVG.
//!
//! The page keeps its own state (points, knots, parameters) and sends it with each
//! request, so the server is stateless and every tab independent.
//!
//! ```no_run
//! spline_studio::run("127.0.0.1", 8765, |addr| println!("http://{addr}/"))?;
//! # Ok::<(), std::io::Error>(())
//! ```

pub mod api;
mod labs;
mod server;
mod values;

pub use server::{MAX_BODY, router, run};
