//! A designed network on its mesh.
//!
//! The mesh is light grey; active edges are coloured by the true network distance to the
//! nearest sink (computed from the design, never the solver's labels) with a legend; sinks are red,
//! point-to-point samples yellow, obstacles black, forced edges and through routes green; rooms
//! and blocks are filled with their type's colour and marked with its letter (A, B, …); the
//! title line names the spec, solver, status, objective and gap.

use super::writer::{escape, Svg};
use crate::design::{travel_distances, Network};
use crate::mesh::EdgeId;
use crate::rules::paths::PathSets;
use crate::rules::placements::Placement;
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
    const STOPS: [[f64; 3]; 5] =
        [[68., 1., 84.], [59., 82., 139.], [33., 145., 140.], [94., 201., 98.], [253., 231., 37.]];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 1.0 };
    let x = t * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let c: Vec<u8> = (0..3).map(|k| (STOPS[i][k] + f * (STOPS[i + 1][k] - STOPS[i][k])).round() as u8).collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// The mesh's frame in the picture: scale, margins, the title band and the legend column.
pub(crate) struct Frame {
    lo: [f64; 2],
    hi: [f64; 2],
    scale: f64,
    margin: f64,
    title_h: f64,
    /// Picture width and height.
    pub w: f64,
    /// Picture height.
    pub h: f64,
    /// Width of the legend column on the right.
    pub legend_w: f64,
    /// Stroke width of network edges.
    pub stroke: f64,
}

impl Frame {
    pub(crate) fn new(mesh: &crate::mesh::Mesh, legend_w: f64) -> Frame {
        let (lo, hi) = mesh.bounding_box();
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
        let scale = 640.0 / span;
        let (margin, title_h) = (24.0, 44.0);
        let w = (hi[0] - lo[0]) * scale + 2.0 * margin + legend_w;
        let h = (hi[1] - lo[1]) * scale + 2.0 * margin + title_h;
        Frame { lo, hi, scale, margin, title_h, w, h, legend_w, stroke: (scale * 0.12).clamp(1.5, 6.0) }
    }

    /// Picture coordinates of a mesh point.
    pub(crate) fn tx(&self, q: [f64; 2]) -> (f64, f64) {
        ((q[0] - self.lo[0]) * self.scale + self.margin, (self.hi[1] - q[1]) * self.scale + self.margin + self.title_h)
    }

    /// The top-left corner of the legend column.
    pub(crate) fn legend_origin(&self) -> (f64, f64) {
        (self.w - self.legend_w + 10.0, self.margin + self.title_h)
    }

    /// The two title lines.
    pub(crate) fn title(&self, s: &mut Svg, name: &str, line: &str) {
        s.text(self.margin, 20.0, r#"font-size="15" font-weight="bold""#, name);
        s.text(self.margin, 38.0, r#"font-size="12""#, line);
    }

    pub(crate) fn face_points(&self, mesh: &crate::mesh::Mesh, f: crate::mesh::FaceId) -> String {
        let pts: Vec<String> = mesh
            .face_vertices(f)
            .iter()
            .map(|&v| {
                let (x, y) = self.tx(mesh.position(v));
                format!("{x:.2},{y:.2}")
            })
            .collect();
        pts.join(" ")
    }

    pub(crate) fn edge_line(&self, mesh: &crate::mesh::Mesh, e: EdgeId, attrs: &str) -> String {
        let (a, b) = mesh.edge_vertices(e);
        let ((x1, y1), (x2, y2)) = (self.tx(mesh.position(a)), self.tx(mesh.position(b)));
        let sep = if attrs.is_empty() { "" } else { " " };
        format!(r#"<line x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}"{sep}{attrs}/>"#)
    }

    /// The mesh in light grey and the obstacle faces in dark grey.
    pub(crate) fn mesh_and_obstacles(&self, s: &mut Svg, p: &Problem) {
        let mesh = &p.mesh;
        for f in mesh.faces().filter(|f| p.is_obstacle_face[f.index()]) {
            let _ =
                writeln!(s, r##"<polygon points="{}" fill="#333" fill-opacity="0.55"/>"##, self.face_points(mesh, f));
        }
        let _ = writeln!(s, r##"<g stroke="#d6d6d6" stroke-width="1">"##);
        for e in mesh.edges() {
            let _ = writeln!(s, "{}", self.edge_line(mesh, e, ""));
        }
        let _ = writeln!(s, "</g>");
    }

    /// A dot on vertex `v`.
    pub(crate) fn dot(&self, s: &mut Svg, mesh: &crate::mesh::Mesh, v: crate::mesh::VertexId, fill: &str, r: f64) {
        let (x, y) = self.tx(mesh.position(v));
        let _ = writeln!(
            s,
            r##"<circle cx="{x:.2}" cy="{y:.2}" r="{r:.2}" fill="{fill}" stroke="#222" stroke-width="0.6"/>"##
        );
    }
}

/// The letter that marks rooms of template `t` (A, B, …, Z, then A1, B1, …).
pub fn template_letter(t: usize) -> String {
    let letter = (b'A' + (t % 26) as u8) as char;
    if t < 26 {
        letter.to_string()
    } else {
        format!("{letter}{}", t / 26)
    }
}

/// The legend's point items (sink, p2p sample, obstacle, forced / route) that the picture shows.
pub(crate) fn point_legend(p: &Problem, paths: bool) -> Vec<(&'static str, &'static str)> {
    let mut items = vec![("#e02424", "sink")];
    if paths {
        items.push(("#facc15", "p2p sample"));
    }
    if p.is_obstacle_vertex.iter().any(|&o| o) || p.is_obstacle_face.iter().any(|&o| o) {
        items.push(("#000", "obstacle"));
    }
    if !p.forced_edges.is_empty() || !p.forced_vertices.is_empty() || !p.through_routes.is_empty() {
        items.push(("#17a34a", "forced / route"));
    }
    items
}

/// Draws the network as SVG text. `placements` are the model's room placements (when tiling
/// rooms); the chosen ones (`net.rooms`) are filled with their template's colour and marked with
/// its letter ([`template_letter`]). The legend lists only what is drawn.
pub fn svg(
    p: &Problem,
    net: &Network,
    paths: Option<&PathSets>,
    placements: Option<&[Placement]>,
    caption: &Caption,
) -> String {
    let mesh = &p.mesh;
    let fr = Frame::new(mesh, 150.0);
    let stroke = fr.stroke;
    let mut s = Svg::new(fr.w, fr.h, None);
    let obj = caption.objective.map_or("-".into(), |o| format!("{o:.4}"));
    let gap = caption.gap.map_or("-".into(), |g| format!("{:.2}%", g * 100.0));
    fr.title(
        &mut s,
        &caption.name,
        &format!("{} · {} · objective {obj} · gap {gap} · {}", caption.solver, caption.status, caption.verdict),
    );
    // Rooms.
    let chosen: Vec<&Placement> = match (&p.rooms, placements) {
        (Some(_), Some(pls)) => net.rooms.iter().map(|&k| &pls[k]).collect(),
        _ => Vec::new(),
    };
    if let Some(rooms) = &p.rooms {
        for pl in &chosen {
            for &f in &pl.faces {
                let _ = writeln!(
                    s,
                    r#"<polygon points="{}" fill="{}" stroke="none"/>"#,
                    fr.face_points(mesh, f),
                    escape(&rooms.colors[pl.template])
                );
            }
        }
    }
    fr.mesh_and_obstacles(&mut s, p);
    // Room outlines (their boundary edges), over the mesh, and each room's letter.
    for pl in &chosen {
        for &e in &pl.boundary_edges {
            let _ = writeln!(s, "{}", fr.edge_line(mesh, e, r##"stroke="#555" stroke-width="1.5""##));
        }
    }
    for pl in &chosen {
        let pts: Vec<[f64; 2]> =
            pl.faces.iter().flat_map(|&f| mesh.face_vertices(f).iter().map(|&v| mesh.position(v))).collect();
        let (lo, hi) = pts.iter().fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), q| {
            ([lo[0].min(q[0]), lo[1].min(q[1])], [hi[0].max(q[0]), hi[1].max(q[1])])
        });
        let size = ((hi[0] - lo[0]).min(hi[1] - lo[1]) * fr.scale * 0.3).min(14.0);
        // The label sits at the room's bounding-box centre, or on its face nearest to it when
        // the centre is outside the room (L and T shapes).
        let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
        let polygon = |f: crate::mesh::FaceId| -> Vec<[f64; 2]> {
            mesh.face_vertices(f).iter().map(|&v| mesh.position(v)).collect()
        };
        let at = if pl.faces.iter().any(|&f| crate::mesh::point_in_polygon(centre, &polygon(f))) {
            centre
        } else {
            pl.faces
                .iter()
                .map(|&f| mesh.face_centroid(f))
                .min_by(|a, b| crate::mesh::geom::dist(*a, centre).total_cmp(&crate::mesh::geom::dist(*b, centre)))
                .unwrap_or(centre)
        };
        if size >= 5.0 {
            let (x, y) = fr.tx(at);
            s.text(
                x,
                y + size * 0.35,
                &format!(
                    r##"class="room-type" font-size="{size:.1}" text-anchor="middle" fill="#333" fill-opacity="0.75""##
                ),
                &template_letter(pl.template),
            );
        }
    }
    // Colour by the true network distance to the nearest sink (never the solver's labels,
    // which only (2) defines and which are not distances off the optimum).
    let travel = travel_distances(mesh, net, &p.is_sink);
    let mut edge_d = vec![f64::NAN; mesh.num_edges()];
    let active = net.active_edges();
    for &e in &active {
        if edge_d[e.index()].is_nan() {
            let (a, b) = mesh.edge_vertices(e);
            edge_d[e.index()] = travel[a.index()].max(travel[b.index()]);
        }
    }
    let dmax = active.iter().map(|e| edge_d[e.index()]).filter(|d| d.is_finite()).fold(0.0, f64::max);
    let _ = writeln!(s, r#"<g stroke-width="{stroke:.2}" stroke-linecap="round">"#);
    for &e in &active {
        let t = if dmax > 0.0 { edge_d[e.index()] / dmax } else { 0.0 };
        let _ = writeln!(s, "{}", fr.edge_line(mesh, e, &format!(r#"stroke="{}""#, ramp(t))));
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
        let _ = writeln!(
            s,
            r##"<g stroke="#17a34a" stroke-width="{:.2}" stroke-dasharray="4 3" fill="none">"##,
            stroke * 0.5
        );
        for e in forced {
            let _ = writeln!(s, "{}", fr.edge_line(mesh, e, ""));
        }
        let _ = writeln!(s, "</g>");
    }
    // Points.
    let r = (stroke * 1.2).max(3.0);
    for v in mesh.vertices().filter(|v| p.is_obstacle_vertex[v.index()]) {
        fr.dot(&mut s, mesh, v, "#000", r * 0.6);
    }
    for v in mesh.vertices().filter(|v| p.is_sink[v.index()]) {
        fr.dot(&mut s, mesh, v, "#e02424", r);
    }
    if let Some(ps) = paths {
        for &(_, v) in &ps.samples {
            fr.dot(&mut s, mesh, v, "#facc15", r);
        }
    }
    for &v in &p.forced_vertices {
        fr.dot(&mut s, mesh, v, "#17a34a", r);
    }
    // Legend: only what is drawn.
    let (lx, mut ly) = fr.legend_origin();
    if !active.is_empty() {
        s.text(lx, ly, r#"font-size="12""#, "distance to sink");
        for k in 0..=10 {
            let t = k as f64 / 10.0;
            let _ = writeln!(
                s,
                r#"<rect x="{lx:.1}" y="{:.1}" width="18" height="14" fill="{}"/>"#,
                ly + 8.0 + k as f64 * 14.0,
                ramp(t)
            );
        }
        s.text(lx + 24.0, ly + 19.0, r#"font-size="11""#, "0");
        s.text(lx + 24.0, ly + 159.0, r#"font-size="11""#, &format!("{dmax:.2}"));
        ly += 185.0;
    } else {
        ly += 14.0;
    }
    for (c, label) in point_legend(p, paths.is_some()) {
        let _ = writeln!(
            s,
            r##"<circle cx="{:.1}" cy="{:.1}" r="5" fill="{c}" stroke="#222" stroke-width="0.6"/>"##,
            lx + 6.0,
            ly - 4.0
        );
        s.text(lx + 18.0, ly, r#"font-size="11""#, label);
        ly += 18.0;
    }
    if let Some(rooms) = &p.rooms {
        ly += 8.0;
        for (i, t) in rooms.templates.iter().enumerate() {
            if !chosen.iter().any(|pl| pl.template == i) {
                continue;
            }
            let _ = writeln!(
                s,
                r##"<rect x="{:.1}" y="{:.1}" width="12" height="12" fill="{}" stroke="#555"/>"##,
                lx,
                ly - 10.0,
                escape(&rooms.colors[i])
            );
            s.text(lx + 6.0, ly - 0.5, r##"font-size="9" text-anchor="middle" fill="#333""##, &template_letter(i));
            s.text(lx + 18.0, ly, r#"font-size="11""#, &t.name);
            ly += 18.0;
        }
    }
    s.finish()
}

/// Colours of conflicts 1, 2, … in [`conflict_svg`].
const CONFLICT_COLORS: [&str; 6] = ["#d61f69", "#f97316", "#2563eb", "#0d9488", "#7c3aed", "#a16207"];

/// Splits `text` into lines of at most about `width` characters, at spaces.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(l) if l.chars().count() + 1 + word.chars().count() <= width => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// A spec without a solution, with the elements of each conflicting set of requirements
/// highlighted in the conflict's colour (`class="conflict" data-conflict="k"`: faces tinted,
/// edges thick, vertices ringed) and every requirement of each set listed in the legend
/// (requirements without a place, such as coverage, only there). Obstacles, sinks, forced
/// elements and through routes are drawn as in [`svg`].
pub fn conflict_svg(p: &Problem, explanation: &crate::explain::Explanation, caption: &Caption) -> String {
    let mesh = &p.mesh;
    let fr = Frame::new(mesh, 270.0);
    let stroke = fr.stroke;
    let legend_h: f64 = explanation
        .conflicts
        .iter()
        .map(|c| 24.0 + 13.0 * c.requirements.iter().map(|r| wrap(&r.field_text(), 40).len()).sum::<usize>() as f64)
        .sum::<f64>()
        + 22.0
        + 18.0 * point_legend(p, false).len() as f64;
    let mut s = Svg::new(fr.w, fr.h.max(fr.legend_origin().1 + legend_h + 10.0), None);
    let n = explanation.conflicts.len();
    fr.title(
        &mut s,
        &caption.name,
        &format!(
            "{} · {} · {n} conflicting set{} of requirements",
            caption.solver,
            caption.status,
            if n == 1 { "" } else { "s" }
        ),
    );
    let pos = |v: u32| fr.tx(mesh.position(crate::mesh::VertexId(v)));
    // Tinted faces first, under the mesh.
    for (k, c) in explanation.conflicts.iter().enumerate() {
        let col = CONFLICT_COLORS[k % CONFLICT_COLORS.len()];
        for r in &c.requirements {
            for &f in &r.faces {
                let _ = writeln!(
                    s,
                    r#"<polygon class="conflict" data-conflict="{}" points="{}" fill="{col}" fill-opacity="0.3"/>"#,
                    k + 1,
                    fr.face_points(mesh, crate::mesh::FaceId(f))
                );
            }
        }
    }
    fr.mesh_and_obstacles(&mut s, p);
    // Forced edges and through routes, sinks, forced and obstacle vertices, as in `svg`.
    let mut forced: Vec<EdgeId> = p.forced_edges.clone();
    for r in &p.through_routes {
        forced.extend(r.windows(2).filter_map(|w| mesh.half_edge_between(w[0], w[1])).map(|h| mesh.he_edge(h)));
    }
    if !forced.is_empty() {
        let _ = writeln!(
            s,
            r##"<g stroke="#17a34a" stroke-width="{:.2}" stroke-dasharray="4 3" fill="none">"##,
            stroke * 0.5
        );
        for e in forced {
            let _ = writeln!(s, "{}", fr.edge_line(mesh, e, ""));
        }
        let _ = writeln!(s, "</g>");
    }
    // The conflicts' edges and vertices.
    let r = (stroke * 1.2).max(3.0);
    for (k, c) in explanation.conflicts.iter().enumerate() {
        let col = CONFLICT_COLORS[k % CONFLICT_COLORS.len()];
        // Later conflicts drawn thinner, so shared elements show every colour.
        let width = stroke * (1.6 - 0.25 * k.min(4) as f64);
        for req in &c.requirements {
            for &[a, b] in &req.edges {
                let ((x1, y1), (x2, y2)) = (pos(a), pos(b));
                let _ = writeln!(
                    s,
                    r#"<line class="conflict" data-conflict="{}" x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}" stroke="{col}" stroke-width="{width:.2}" stroke-linecap="round" stroke-opacity="0.85"/>"#,
                    k + 1
                );
            }
        }
    }
    for v in mesh.vertices().filter(|v| p.is_obstacle_vertex[v.index()]) {
        fr.dot(&mut s, mesh, v, "#000", r * 0.6);
    }
    for v in mesh.vertices().filter(|v| p.is_sink[v.index()]) {
        fr.dot(&mut s, mesh, v, "#e02424", r);
    }
    for &v in &p.forced_vertices {
        fr.dot(&mut s, mesh, v, "#17a34a", r);
    }
    for (k, c) in explanation.conflicts.iter().enumerate() {
        let col = CONFLICT_COLORS[k % CONFLICT_COLORS.len()];
        for req in &c.requirements {
            for &v in &req.vertices {
                let (x, y) = pos(v);
                let _ = writeln!(
                    s,
                    r#"<circle class="conflict" data-conflict="{}" cx="{x:.2}" cy="{y:.2}" r="{:.2}" fill="none" stroke="{col}" stroke-width="2.5"/>"#,
                    k + 1,
                    r * (1.7 + 0.5 * k.min(4) as f64)
                );
            }
        }
    }
    // Legend: each conflict and its requirements, then the point items drawn.
    let (lx, mut ly) = fr.legend_origin();
    for (k, c) in explanation.conflicts.iter().enumerate() {
        let col = CONFLICT_COLORS[k % CONFLICT_COLORS.len()];
        let _ = writeln!(s, r#"<rect x="{lx:.1}" y="{:.1}" width="14" height="12" fill="{col}"/>"#, ly - 10.0);
        s.text(
            lx + 20.0,
            ly,
            r#"font-size="12" font-weight="bold""#,
            &format!("conflict {}{}", k + 1, if c.minimal { "" } else { " (not proven minimal)" }),
        );
        ly += 16.0;
        for req in &c.requirements {
            for (i, line) in wrap(&req.field_text(), 40).iter().enumerate() {
                s.text(
                    lx + if i == 0 { 8.0 } else { 16.0 },
                    ly,
                    r#"font-size="10""#,
                    &if i == 0 { format!("• {line}") } else { line.clone() },
                );
                ly += 13.0;
            }
        }
        ly += 8.0;
    }
    if !explanation.complete {
        s.text(lx, ly, r#"font-size="10" font-style="italic""#, "search stopped at its limits");
        ly += 16.0;
    }
    ly += 6.0;
    for (c, label) in point_legend(p, false) {
        let _ = writeln!(
            s,
            r##"<circle cx="{:.1}" cy="{:.1}" r="5" fill="{c}" stroke="#222" stroke-width="0.6"/>"##,
            lx + 6.0,
            ly - 4.0
        );
        s.text(lx + 18.0, ly, r#"font-size="11""#, label);
        ly += 18.0;
    }
    s.finish()
}
