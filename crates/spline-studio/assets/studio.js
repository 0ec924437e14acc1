// spline studio: the page. All geometry is computed by the server (the library); this script
// keeps the tab's state (points, knots, parameters), sends it with every request and draws
// the answers as SVG in world coordinates (y up).
"use strict";

const NS = "http://www.w3.org/2000/svg";
const $ = (id) => document.getElementById(id);
const canvas = $("canvas"), world = $("world"), strip = $("strip");
const layers = {
  extra: $("layer-extra"), curves: $("layer-curves"),
  marks: $("layer-marks"), points: $("layer-points"),
};

// The tab's state: nothing of it lives on the server.
const S = {
  mode: "bezier",
  points: [],          // [x, y] in world coordinates
  knots: null,         // B-spline mode: knots after insertions (null: clamped uniform)
  params: null,        // approximation: the parameters after correction steps
  history: [],         // undo snapshots
  view: { scale: 500, ox: 60, oy: 520 },
  answer: null,        // the last answer drawn
  curve: null,         // the exchange-format record of the curve shown (for export)
  erased: null,        // curvature mode: the eraser's answer
  eraser: false,       // whether the eraser follows the data
  eraseStale: false,   // the data changed since its answer
  erasedFeatures: null,
  correction: null,
};
// For tests and curious users: the state, whether the page is idle, how many answers drawn.
// eraseMs: the round trip of every eraser update (the browser test reads it).
const studio = { state: S, renders: 0, busy: false, pending: false, errors: 0, eraseMs: [] };
window.studio = studio;

function el(name, attrs, parent) {
  const e = document.createElementNS(NS, name);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (parent) parent.appendChild(e);
  return e;
}
function clear(g) { while (g.firstChild) g.removeChild(g.firstChild); }
function pathD(points) {
  return points.map((p, i) => (i ? "L" : "M") + p[0] + " " + p[1]).join(" ");
}
function px(n) { return n / S.view.scale; } // screen pixels → world units
// Stroke widths and dashes in screen pixels, set in world units at each drawing.
const WIDTHS = { curve: 2.5, erased: 2.5, left: 2, right: 2, plot: 1.5 };
const DASHES = { polygon: [4, 3], elevated: [2, 3] };
function stroke(e, cls) {
  const base = cls.split(" ")[0];
  e.setAttribute("stroke-width", px(WIDTHS[base] || 1.2));
  if (DASHES[base]) e.setAttribute("stroke-dasharray", DASHES[base].map(px).join(" "));
  return e;
}
function polyline(points, cls, parent, id) {
  const attrs = { d: pathD(points), class: cls };
  if (id) attrs.id = id;
  return stroke(el("path", attrs, parent || layers.curves), cls);
}
function segment(p, q, cls, parent) {
  return stroke(el("line", { x1: p[0], y1: p[1], x2: q[0], y2: q[1], class: cls }, parent || layers.extra), cls);
}
function dot(p, r, cls, parent) {
  return el("circle", { cx: p[0], cy: p[1], r: px(r), class: cls, "stroke-width": px(1) }, parent || layers.marks);
}
function setView() {
  const v = S.view;
  world.setAttribute("transform", `matrix(${v.scale} 0 0 ${-v.scale} ${v.ox} ${v.oy})`);
}
function fitView(points) {
  if (!points.length) return;
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  for (const [x, y] of points) {
    x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
  }
  const w = Math.max(x1 - x0, 1e-9), h = Math.max(y1 - y0, 1e-9);
  // A margin around the points: curvature combs, control polygons and labels drawn beyond
  // the data (an airfoil's comb at the nose) stay on the canvas.
  const scale = Math.min(560 / w, 300 / h);
  S.view = { scale, ox: 450 - scale * (x0 + x1) / 2, oy: 280 + scale * (y0 + y1) / 2 };
  setView();
}
function toWorld(event) {
  const m = world.getScreenCTM().inverse();
  const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(m);
  return [p.x, p.y];
}

// ---- requests -------------------------------------------------------------------------
async function call(name, body) {
  const response = await fetch("/api/" + name, {
    method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body),
  });
  const answer = await response.json();
  if (!response.ok) throw new Error(answer.error || response.statusText);
  return answer;
}
function showError(e) {
  $("error").textContent = e ? String(e.message || e) : "";
  if (e) studio.errors += 1;
}
function status(lines) { $("status").textContent = lines.filter(Boolean).join("\n"); }
function num(id, lo, hi) {
  const v = Math.round(Number($(id).value));
  return Math.min(hi, Math.max(lo, Number.isFinite(v) ? v : lo));
}

// One request at a time; while one runs, the latest state is sent when it returns (a drag
// sends as fast as the server answers, never a backlog).
async function refresh() {
  if (studio.busy) { studio.pending = true; return; }
  studio.busy = true;
  try {
    do {
      studio.pending = false;
      try {
        await compute();
        showError(null);
      } catch (e) {
        showError(e);
        clear(layers.curves); clear(layers.marks); clear(layers.extra);
      }
      drawPoints();
      studio.renders += 1;
    } while (studio.pending);
  } finally {
    studio.busy = false;
  }
}
studio.idle = () => !studio.busy && !studio.pending;

async function compute() {
  clearStrip();
  const modes = { bezier, bspline, interpolate, approximate, curvature };
  if (S.points.length < 2) {
    clear(layers.curves); clear(layers.marks); clear(layers.extra);
    S.curve = null;
    status([`${S.points.length} point(s): click in the drawing to add points`]);
    return;
  }
  await modes[S.mode]();
}

// ---- Bézier (TDsm 1) --------------------------------------------------------------------
async function bezier() {
  const t = Number($("t").value);
  const a = await call("bezier", { control_points: S.points, t, elevate: num("elevate", 0, 20) });
  S.answer = a; S.curve = a.curve;
  clear(layers.curves); clear(layers.marks); clear(layers.extra);
  polyline(S.points, "polygon", layers.extra);
  polyline(a.samples, "curve", layers.curves, "curve-main");
  if ($("show-casteljau").checked) {
    a.casteljau.slice(1).forEach((row, level) => {
      const hue = (200 + 50 * level) % 360;
      const path = polyline(row, "casteljau", layers.extra);
      path.style.stroke = `hsl(${hue} 60% 45%)`;
      for (const p of row) dot(p, 3, "casteljau-point", layers.extra).style.fill = `hsl(${hue} 60% 45%)`;
    });
  }
  if ($("show-subdivision").checked && a.left) {
    polyline(a.left, "left", layers.extra, "subdivision-left");
    polyline(a.right, "right", layers.extra, "subdivision-right");
  }
  if (num("elevate", 0, 20) > 0) {
    polyline(a.elevated, "elevated", layers.extra, "elevated");
    for (const p of a.elevated) dot(p, 3, "elevated-point", layers.extra);
  }
  dot(a.point, 5, "marker-t");
  $("t-value").textContent = t.toFixed(3);
  status([`Bézier curve of degree ${S.points.length - 1}`,
    `x(${t.toFixed(3)}) = (${a.point[0].toFixed(4)}, ${a.point[1].toFixed(4)})`,
    num("elevate", 0, 20) ? `elevated: ${a.elevated.length} control points, same curve` : ""]);
}

// ---- B-spline -------------------------------------------------------------------------
async function bspline() {
  const insert = S.insert;
  S.insert = undefined;
  const degree = num("degree", 1, 10);
  const body = { degree, control_points: S.points };
  if (S.knots && S.knots.length === S.points.length + degree + 1) body.knots = S.knots;
  if (insert !== undefined) body.insert = insert;
  const a = await call("bspline", body);
  if (insert !== undefined) {
    S.points = a.curve.control_points;
    S.knots = a.curve.knots;
  }
  S.answer = a; S.curve = a.curve;
  clear(layers.curves); clear(layers.marks); clear(layers.extra);
  polyline(S.points, "polygon", layers.extra);
  polyline(a.samples, "curve", layers.curves, "curve-main");
  for (const k of a.knots) {
    const r = px(4);
    el("rect", { x: k.point[0] - r, y: k.point[1] - r, width: 2 * r, height: 2 * r, class: "knot", "stroke-width": px(1) }, layers.marks);
  }
  drawKnotLine(a);
  status([`degree ${degree}, ${S.points.length} control points`,
    "knots: [" + a.curve.knots.map((u) => +u.toFixed(4)).join(", ") + "]"]);
}
function drawKnotLine(a) {
  const [u0, u1] = a.domain;
  const x = (u) => 40 + 820 * (u - u0) / (u1 - u0);
  el("line", { x1: 40, y1: 60, x2: 860, y2: 60, class: "axis", id: "knot-axis" }, strip);
  for (const k of a.knots) {
    el("line", { x1: x(k.u), y1: 60 - 6 * k.multiplicity, x2: x(k.u), y2: 60 + 6 * k.multiplicity, class: "tick" }, strip);
    const label = el("text", { x: x(k.u), y: 100, "text-anchor": "middle", class: "tick-label" }, strip);
    label.textContent = (+k.u.toFixed(3)) + (k.multiplicity > 1 ? ` (×${k.multiplicity})` : "");
  }
  const label = el("text", { x: 450, y: 20, "text-anchor": "middle", class: "tick-label" }, strip);
  label.textContent = "knot vector: click to insert a knot";
  strip.onclick = (e) => {
    const r = strip.getBoundingClientRect();
    const u = u0 + (u1 - u0) * (e.clientX - r.left - 40) / 820;
    if (u > u0 && u < u1) {
      snapshot();
      S.insert = u;
      refresh();
    }
  };
}

// ---- interpolation (TDsm 2) -------------------------------------------------------------
async function interpolate() {
  const choice = $("interp-degree").value;
  const parametrizations = [...document.querySelectorAll(".interp-param")]
    .filter((c) => c.checked).map((c) => c.value);
  const body = { points: S.points, parametrizations };
  if (choice !== "bezier") body.degree = Number(choice);
  const a = await call("interpolate", body);
  S.answer = a;
  clear(layers.curves); clear(layers.marks); clear(layers.extra);
  const lines = [choice === "bezier" ? `Bézier curves of degree ${S.points.length - 1}` : `B-splines of degree ${choice}, averaged knots`];
  for (const fit of a.fits) {
    polyline(fit.samples, "curve " + fit.parametrization, layers.curves, "curve-" + fit.parametrization);
    lines.push(`${fit.parametrization}: t = [${fit.params.map((t) => t.toFixed(3)).join(", ")}]`);
  }
  S.curve = a.fits.length ? a.fits[a.fits.length - 1].curve : null;
  status(lines);
}

// ---- approximation (TDsm 3) -------------------------------------------------------------
function approximationRequest(correct) {
  const bezierCurve = $("approx-bezier").checked;
  const body = {
    points: S.points, degree: num("approx-degree", 1, 20),
    parametrization: $("approx-param").value, correct,
  };
  if (bezierCurve) body.bezier = true; else body.control_points = num("approx-n", 2, 500);
  if (S.params && S.params.length === S.points.length) body.params = S.params;
  if (!bezierCurve && S.params && S.knots && S.mode === "approximate") body.knots = S.knots;
  return body;
}
async function approximate() {
  const correct = S.correct || 0;
  S.correct = 0;
  const a = await call("approximate", approximationRequest(correct));
  if (correct) {
    S.params = a.params; S.knots = a.curve.knots; S.correction = a.correction;
  }
  S.answer = a; S.curve = a.curve;
  clear(layers.curves); clear(layers.marks); clear(layers.extra);
  polyline(a.curve.control_points, "fit-polygon", layers.extra);
  if ($("show-projections").checked) {
    a.projections.forEach((f, k) => {
      segment(S.points[k], f, "projection");
    });
  }
  polyline(a.samples, "curve", layers.curves, "curve-main");
  const c = S.correction;
  status([`${S.points.length} points, ${a.curve.control_points.length} control points, degree ${a.curve.degree}`,
    `max deviation ${a.max_deviation.toExponential(3)}, rms ${a.rms.toExponential(3)}`,
    S.params ? "parameters: corrected" : `parameters: ${$("approx-param").value}`,
    c ? `correction: ${c.iterations} sweep(s), converged: ${c.converged}` : "",
    c && c.angle_error !== null ? `max angle error |π/2 − α| = ${c.angle_error.toExponential(2)}` : "",
    c && c.errors.length ? `Σ‖D‖²: ${c.errors[0].toExponential(4)} → ${c.errors[c.errors.length - 1].toExponential(4)}` : ""]);
}

// ---- curvature: comb, plot, features, eraser --------------------------------------------
async function curvature() {
  let curve;
  if ($("curv-source").value === "bspline") {
    if (S.points.length < 4) throw new Error("a cubic needs at least 4 control points");
    curve = (await call("bspline", { degree: 3, control_points: S.points })).curve;
  } else {
    curve = (await call("approximate", {
      points: S.points, degree: 3, control_points: num("curv-n", 4, 500),
    })).curve;
  }
  const a = await call("features", { curve });
  S.answer = a; S.curve = a.curve;
  clear(layers.curves); clear(layers.marks); clear(layers.extra);
  drawComb(a);
  polyline(a.samples, "curve", layers.curves, "curve-main");
  for (const f of a.inflections) dot(f.point, 5, "inflection");
  for (const f of a.curvature_extrema) dot(f.point, 5, "extremum");
  const plots = [[a, "plot"]];
  // The eraser follows the data: after a change it runs again from its last answer.
  if (S.eraser && (S.eraseStale || !S.erased)) await runEraser();
  if (S.erased) {
    polyline(S.erased.samples, "erased", layers.curves, "curve-erased");
    for (const e of S.erased.extrema) dot(e.point, 6, "erased-extremum");
    if (S.erasedFeatures) plots.push([S.erasedFeatures, "plot after"]);
  }
  drawCurvaturePlot(plots);
  status([`${a.inflections.length} inflection(s) (green), ${a.curvature_extrema.length} curvature extrema (red)`,
    S.erased ? `erased (orange): ${S.erased.extrema.length} extrema, max deviation ${S.erased.max_deviation.toExponential(3)}` : "",
    S.erased ? `curve → data polyline ${S.erased.max_deviation_to_data.toExponential(3)}` : ""]);
}
function drawComb(a) {
  const kmax = a.comb.reduce((m, t) => Math.max(m, Math.abs(t[3])), 0);
  if (!(kmax > 0)) return;
  const size = 460 / S.view.scale;
  const s = Number($("comb-scale").value) * size / kmax;
  const tips = a.comb.map(([, x, y, k, nx, ny]) => [x - s * k * nx, y - s * k * ny]);
  a.comb.forEach(([, x, y], i) => {
    segment([x, y], tips[i], "comb");
  });
  polyline(tips, "envelope", layers.extra);
}
function drawCurvaturePlot(plots) {
  let [u0, u1, k0, k1] = [Infinity, -Infinity, 0, 0];
  for (const [a] of plots) for (const t of a.comb) {
    u0 = Math.min(u0, t[0]); u1 = Math.max(u1, t[0]); k0 = Math.min(k0, t[3]); k1 = Math.max(k1, t[3]);
  }
  if (!(u1 > u0) || !(k1 > k0)) return;
  const x = (u) => 40 + 820 * (u - u0) / (u1 - u0);
  const y = (k) => 115 - 100 * (k - k0) / (k1 - k0);
  el("line", { x1: 40, x2: 860, y1: y(0), y2: y(0), class: "zero" }, strip);
  for (const [a, cls] of plots) {
    el("path", { d: pathD(a.comb.map((t) => [x(t[0]), y(t[3])])), class: cls }, strip);
    for (const f of a.curvature_extrema) {
      el("circle", { cx: x(f.u), cy: y(f.curvature), r: 3.5, class: cls.includes("after") ? "erased-extremum" : "extremum" }, strip);
    }
    for (const f of a.inflections) el("circle", { cx: x(f.u), cy: y(0), r: 3.5, class: "inflection" }, strip);
  }
  const label = el("text", { x: 450, y: 12, "text-anchor": "middle", class: "tick-label" }, strip);
  label.textContent = `signed curvature κ(u), ${k0.toPrecision(3)} … ${k1.toPrecision(3)}`;
}
// The eraser, from its previous answer where there is one (its `warm` record: a dragged
// point is followed in a fraction of the time of a fresh start).
async function runEraser() {
  const request = {
    points: S.points, control_points: num("curv-n", 4, 500), extrema: num("erase-k", 1, 9),
  };
  if (S.erased && S.erased.warm) request.warm = S.erased.warm;
  const started = performance.now();
  const e = await call("erase", request);
  studio.eraseMs.push(performance.now() - started);
  S.erased = e;
  S.eraseStale = false;
  S.erasedFeatures = await call("features", { curve: e.curve });
}
async function erase() {
  showError(null);
  S.eraser = true; S.erased = null; S.erasedFeatures = null;
  refresh();
}

function clearStrip() { clear(strip); strip.onclick = null; }

// ---- points: add, drag, delete, undo --------------------------------------------------
function snapshot() {
  S.history.push(JSON.stringify({ points: S.points, knots: S.knots, params: S.params }));
  if (S.history.length > 200) S.history.shift();
}
function undo() {
  const last = S.history.pop();
  if (!last) return;
  const s = JSON.parse(last);
  S.points = s.points; S.knots = s.knots; S.params = s.params; S.eraseStale = true;
  refresh();
}
function pointsChanged() { S.knots = null; S.params = null; S.correction = null; S.eraseStale = true; }
function drawPoints() {
  clear(layers.points);
  const data = ["interpolate", "approximate", "curvature"].includes(S.mode);
  S.points.forEach((p, i) => {
    const c = dot(p, data ? 4 : 6, data ? "point data" : "point", layers.points);
    c.dataset.index = i;
  });
}
let drag = null;
canvas.addEventListener("pointerdown", (e) => {
  if (e.button !== 0) return;
  const index = e.target.dataset && e.target.dataset.index;
  if (index !== undefined) {
    if (e.shiftKey) { removePoint(Number(index)); return; }
    snapshot();
    drag = { index: Number(index) };
    canvas.setPointerCapture(e.pointerId);
    e.preventDefault();
    return;
  }
  snapshot();
  S.points.push(toWorld(e));
  pointsChanged();
  drawPoints();
  refresh();
});
canvas.addEventListener("pointermove", (e) => {
  if (!drag) return;
  S.points[drag.index] = toWorld(e);
  S.params = null; S.correction = null; S.eraseStale = true;
  if (S.mode !== "bspline") S.knots = null;
  drawPoints();
  refresh();
});
const endDrag = () => { drag = null; };
canvas.addEventListener("pointerup", endDrag);
canvas.addEventListener("pointercancel", endDrag);
canvas.addEventListener("contextmenu", (e) => {
  const index = e.target.dataset && e.target.dataset.index;
  e.preventDefault();
  if (index !== undefined) removePoint(Number(index));
});
function removePoint(i) {
  snapshot();
  S.points.splice(i, 1);
  pointsChanged();
  drawPoints();
  refresh();
}
document.addEventListener("keydown", (e) => {
  if ((e.ctrlKey || e.metaKey) && e.key === "z") { e.preventDefault(); undo(); }
});

// ---- modes and controls ---------------------------------------------------------------
function setMode(mode) {
  S.mode = mode;
  S.knots = null; S.params = null; S.correction = null;
  for (const b of document.querySelectorAll("#modes button")) b.classList.toggle("active", b.dataset.mode === mode);
  for (const s of document.querySelectorAll("#panel section")) s.classList.toggle("active", s.dataset.mode === mode);
  refresh();
}
for (const b of document.querySelectorAll("#modes button")) b.addEventListener("click", () => setMode(b.dataset.mode));
for (const id of ["t", "show-casteljau", "show-subdivision", "elevate", "interp-degree", "show-projections", "comb-scale"]) {
  $(id).addEventListener("input", refresh);
}
for (const c of document.querySelectorAll(".interp-param")) c.addEventListener("change", refresh);
for (const id of ["degree", "approx-bezier", "approx-degree", "approx-n", "approx-param", "curv-source", "curv-n"]) {
  $(id).addEventListener("change", () => { S.knots = null; S.params = null; S.correction = null; S.erased = null; refresh(); });
}
$("undo").addEventListener("click", undo);
$("clear").addEventListener("click", () => { snapshot(); S.points = []; pointsChanged(); refresh(); });
$("uniform-knots").addEventListener("click", () => { snapshot(); S.knots = null; refresh(); });
$("apply-elevation").addEventListener("click", () => {
  if (!S.answer || !S.answer.elevated) return;
  snapshot(); S.points = S.answer.elevated; $("elevate").value = 0; refresh();
});
$("apply-subdivision").addEventListener("click", () => {
  if (!S.answer || !S.answer.left) return;
  snapshot(); S.points = S.answer.left; fitView(S.points); refresh();
});
function correct(sweeps) { S.correct = sweeps; refresh(); }
$("correct-step").addEventListener("click", () => correct(1));
$("correct-converge").addEventListener("click", () => correct(500));
$("correct-reset").addEventListener("click", () => { S.params = null; S.knots = null; S.correction = null; refresh(); });
$("erase").addEventListener("click", erase);
$("erase-clear").addEventListener("click", () => { S.eraser = false; S.erased = null; S.erasedFeatures = null; refresh(); });

// ---- files ----------------------------------------------------------------------------
$("file").addEventListener("change", async (e) => {
  const file = e.target.files[0];
  if (!file) return;
  try {
    const a = await call("load", { text: await file.text() });
    snapshot();
    S.points = a.points;
    pointsChanged();
    fitView(S.points);
    if (a.curve) {
      $("degree").value = a.degree;
      setMode("bspline");
      S.knots = a.curve.knots;
    } else if (S.mode === "bezier" || S.mode === "bspline") {
      setMode("approximate");
    }
    refresh();
  } catch (err) { showError(err); }
  e.target.value = "";
});
function download(name, type, text) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([text], { type }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}
$("export-json").addEventListener("click", () => {
  if (S.curve) download("curve.json", "application/json", JSON.stringify(S.curve) + "\n");
  else showError("no curve to export yet");
});
$("export-svg").addEventListener("click", () => {
  const text = new XMLSerializer().serializeToString(canvas);
  download("studio.svg", "image/svg+xml", `<?xml version="1.0" encoding="UTF-8"?>\n${text}\n`);
});

// The page opens on an example (a cubic Bézier curve in the default view) rather than blank;
// "Clear" empties it.
const EXAMPLE = [[0.1, 0.2], [0.45, 0.85], [1.05, 0.05], [1.55, 0.65]];
S.points = EXAMPLE.map((p) => p.slice());
setView();
setMode("bezier");
