//! Pictures of results: an SVG drawn by hand (deterministic text, snapshot-friendly) and a PNG
//! rasterised from it with `resvg`.
//!
//! The mesh is light grey; active edges are coloured by the true network distance to the
//! nearest sink (computed from the design, never the solver's labels) with a legend; sinks are red,
//! point-to-point samples yellow, obstacles black, forced edges and through routes green; the
//! title line names the spec, solver, status, objective and gap.

pub mod traffic;

use crate::design::{travel_distances, Network};
use crate::rules::paths::PathSets;
use crate::rules::placements::Placement;
use crate::mesh::EdgeId;
use crate::spec::Problem;
use std::fmt::Write;

/// What the title line says.
#[derive(Clone, Debug, Default)]
pub struct Caption {
    /// Spec name.
    pub name: String,
    /// Solver name and version.
    pub solver: String,
    /// Termination.
    pub status: String,
    /// Objective, if any.
    pub objective: Option<f64>,
    /// Gap, if any.
    pub gap: Option<f64>,
    /// Validity verdict (`valid` or a count of violations).
    pub verdict: String,
}

/// Five-stop colour ramp (viridis-like), `t` in [0, 1].
fn ramp(t: f64) -> String {
    const STOPS: [[f64; 3]; 5] = [[68., 1., 84.], [59., 82., 139.], [33., 145., 140.], [94., 201., 98.], [253., 231., 37.]];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 1.0 };
    let x = t * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let c: Vec<u8> = (0..3).map(|k| (STOPS[i][k] + f * (STOPS[i + 1][k] - STOPS[i][k])).round() as u8).collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// Draws the network as SVG text. `placements` are the model's room placements (when tiling
/// rooms); the chosen ones (`net.rooms`) are filled with their template's colour.
pub fn svg(p: &Problem, net: &Network, paths: Option<&PathSets>, placements: Option<&[Placement]>, caption: &Caption) -> String {
    let mesh = &p.mesh;
    let (lo, hi) = mesh.bounding_box();
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
    let scale = 640.0 / span;
    let margin = 24.0;
    let title_h = 44.0;
    let legend_w = 150.0;
    let w = (hi[0] - lo[0]) * scale + 2.0 * margin + legend_w;
    let h = (hi[1] - lo[1]) * scale + 2.0 * margin + title_h;
    let tx = |q: [f64; 2]| ((q[0] - lo[0]) * scale + margin, (hi[1] - q[1]) * scale + margin + title_h);
    let stroke = (scale * 0.12).clamp(1.5, 6.0);
    let mut s = String::new();
    let _ = writeln!(s, r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.1} {h:.1}" font-family="DejaVu Sans, sans-serif">"#);
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let obj = caption.objective.map_or("-".into(), |o| format!("{o:.4}"));
    let gap = caption.gap.map_or("-".into(), |g| format!("{:.2}%", g * 100.0));
    let _ = writeln!(s, r#"<text x="{margin}" y="20" font-size="15" font-weight="bold">{}</text>"#, xml(&caption.name));
    let _ = writeln!(
        s,
        r#"<text x="{margin}" y="38" font-size="12">{} · {} · objective {obj} · gap {gap} · {}</text>"#,
        xml(&caption.solver),
        xml(&caption.status),
        xml(&caption.verdict)
    );
    let face_points = |f: crate::mesh::FaceId| {
        let pts: Vec<String> = mesh.face_vertices(f).iter().map(|&v| {
            let (x, y) = tx(mesh.position(v));
            format!("{x:.2},{y:.2}")
        }).collect();
        pts.join(" ")
    };
    // Rooms.
    if let (Some(rooms), Some(pls)) = (&p.rooms, placements) {
        for &k in &net.rooms {
            let pl = &pls[k];
            for &f in &pl.faces {
                let _ = writeln!(s, r#"<polygon points="{}" fill="{}" stroke="none"/>"#, face_points(f), xml(&rooms.colors[pl.template]));
            }
        }
    }
    // Obstacle faces.
    for f in mesh.faces().filter(|f| p.is_obstacle_face[f.index()]) {
        let _ = writeln!(s, r##"<polygon points="{}" fill="#333" fill-opacity="0.55"/>"##, face_points(f));
    }
    // Mesh.
    let _ = writeln!(s, r##"<g stroke="#d6d6d6" stroke-width="1">"##);
    for e in mesh.edges() {
        let (a, b) = mesh.edge_vertices(e);
        let ((x1, y1), (x2, y2)) = (tx(mesh.position(a)), tx(mesh.position(b)));
        let _ = writeln!(s, r#"<line x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}"/>"#);
    }
    let _ = writeln!(s, "</g>");
    // Room outlines (their boundary edges), over the mesh.
    if let (Some(_), Some(pls)) = (&p.rooms, placements) {
        for &k in &net.rooms {
            for e in &pls[k].boundary_edges {
                let (a, b) = mesh.edge_vertices(*e);
                let ((x1, y1), (x2, y2)) = (tx(mesh.position(a)), tx(mesh.position(b)));
                let _ = writeln!(s, r##"<line x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}" stroke="#555" stroke-width="1.5"/>"##);
            }
        }
    }
    // Colour by the true network distance to the nearest sink (never the solver's labels,
    // which only (2) defines and which are not distances off the optimum).
    let travel = travel_distances(mesh, net, &p.is_sink);
    let mut edge_d = vec![f64::NAN; mesh.num_edges()];
    for e in net.active_edges() {
        if edge_d[e.index()].is_nan() {
            let (a, b) = mesh.edge_vertices(e);
            edge_d[e.index()] = travel[a.index()].max(travel[b.index()]);
        }
    }
    let dmax = net.active_edges().iter().map(|e| edge_d[e.index()]).filter(|d| d.is_finite()).fold(0.0, f64::max);
    let _ = writeln!(s, r#"<g stroke-width="{stroke:.2}" stroke-linecap="round">"#);
    for e in net.active_edges() {
        let (a, b) = mesh.edge_vertices(e);
        let ((x1, y1), (x2, y2)) = (tx(mesh.position(a)), tx(mesh.position(b)));
        let t = if dmax > 0.0 { edge_d[e.index()] / dmax } else { 0.0 };
        let _ = writeln!(s, r#"<line x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}" stroke="{}"/>"#, ramp(t));
    }
    let _ = writeln!(s, "</g>");
    // Forced edges and through routes.
    let mut forced: Vec<EdgeId> = p.forced_edges.clone();
    for r in &p.through_routes {
        for w2 in r.windows(2) {
            if let Some(hh) = mesh.half_edge_between(w2[0], w2[1]) {
                forced.push(mesh.he_edge(hh));
            }
        }
    }
    if !forced.is_empty() {
        let _ = writeln!(s, r##"<g stroke="#17a34a" stroke-width="{:.2}" stroke-dasharray="4 3" fill="none">"##, stroke * 0.5);
        for e in forced {
            let (a, b) = mesh.edge_vertices(e);
            let ((x1, y1), (x2, y2)) = (tx(mesh.position(a)), tx(mesh.position(b)));
            let _ = writeln!(s, r#"<line x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}"/>"#);
        }
        let _ = writeln!(s, "</g>");
    }
    // Points.
    let r = (stroke * 1.2).max(3.0);
    let dot = |s: &mut String, v: crate::mesh::VertexId, fill: &str, rr: f64| {
        let (x, y) = tx(mesh.position(v));
        let _ = writeln!(s, r##"<circle cx="{x:.2}" cy="{y:.2}" r="{rr:.2}" fill="{fill}" stroke="#222" stroke-width="0.6"/>"##);
    };
    for v in mesh.vertices().filter(|v| p.is_obstacle_vertex[v.index()]) {
        dot(&mut s, v, "#000", r * 0.6);
    }
    for v in mesh.vertices().filter(|v| p.is_sink[v.index()]) {
        dot(&mut s, v, "#e02424", r);
    }
    if let Some(ps) = paths {
        for &(_, v) in &ps.samples {
            dot(&mut s, v, "#facc15", r);
        }
    }
    for &v in &p.forced_vertices {
        dot(&mut s, v, "#17a34a", r);
    }
    // Legend.
    let lx = w - legend_w + 10.0;
    let ly = margin + title_h;
    let _ = writeln!(s, r#"<text x="{lx:.1}" y="{:.1}" font-size="12">{}</text>"#, ly, "distance to sink");
    for k in 0..=10 {
        let t = k as f64 / 10.0;
        let _ = writeln!(s, r#"<rect x="{lx:.1}" y="{:.1}" width="18" height="14" fill="{}"/>"#, ly + 8.0 + k as f64 * 14.0, ramp(t));
    }
    let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" font-size="11">0</text>"#, lx + 24.0, ly + 19.0);
    let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" font-size="11">{dmax:.2}</text>"#, lx + 24.0, ly + 19.0 + 140.0);
    let items = [("#e02424", "sink"), ("#facc15", "p2p sample"), ("#000", "obstacle"), ("#17a34a", "forced / route")];
    for (i, (c, label)) in items.iter().enumerate() {
        let y = ly + 185.0 + i as f64 * 18.0;
        let _ = writeln!(s, r##"<circle cx="{:.1}" cy="{:.1}" r="5" fill="{c}" stroke="#222" stroke-width="0.6"/>"##, lx + 6.0, y - 4.0);
        let _ = writeln!(s, r#"<text x="{:.1}" y="{y:.1}" font-size="11">{label}</text>"#, lx + 18.0);
    }
    if let Some(rooms) = &p.rooms {
        for (i, t) in rooms.templates.iter().enumerate() {
            let y = ly + 265.0 + i as f64 * 18.0;
            let _ = writeln!(s, r##"<rect x="{:.1}" y="{:.1}" width="12" height="12" fill="{}" stroke="#555"/>"##, lx, y - 10.0, xml(&rooms.colors[i]));
            let _ = writeln!(s, r#"<text x="{:.1}" y="{y:.1}" font-size="11">{}</text>"#, lx + 18.0, xml(&t.name));
        }
    }
    s.push_str("</svg>\n");
    s
}

fn xml(t: &str) -> String {
    t.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}

/// Why a PNG could not be made.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The SVG did not parse (a bug).
    #[error("SVG: {0}")]
    Svg(String),
    /// Rasterising or encoding failed.
    #[error("PNG: {0}")]
    Png(String),
}

/// Rasterises SVG text to PNG bytes (system fonts for the text).
pub fn png(svg_text: &str) -> Result<Vec<u8>, RenderError> {
    let mut opt = resvg::usvg::Options::default();
    opt.fontdb_mut().load_system_fonts();
    let tree = resvg::usvg::Tree::from_str(svg_text, &opt).map_err(|e| RenderError::Svg(e.to_string()))?;
    let size = tree.size().to_int_size();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height()).ok_or_else(|| RenderError::Png("empty picture".into()))?;
    resvg::render(&tree, resvg::tiny_skia::Transform::default(), &mut pixmap.as_mut());
    pixmap.encode_png().map_err(|e| RenderError::Png(e.to_string()))
}
