//! A designed network on its mesh, drawn from a [`NetworkScene`]: plain vertex positions and
//! vertex indices (the design code builds it, `design::picture`), so this module knows nothing
//! of specs, meshes or designs.
//!
//! The mesh is light grey; active edges are coloured by their distance value (the true network
//! distance to the nearest sink) with a legend; sinks are red, point-to-point samples yellow,
//! obstacles black, forced edges and through routes green; rooms and blocks are filled with
//! their type's colour and marked with its letter (A, B, …); the title line names the spec,
//! solver, status, objective and gap. [`conflict_svg`] draws a spec without a solution with the
//! elements of each conflicting set of requirements highlighted ([`ConflictScene`]).

use super::writer::{escape, Svg};
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

/// A mesh and what lies on it, as plain data: vertices are indices into `positions`, edges
/// vertex pairs, faces vertex loops. Every list is drawn in its order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct NetworkScene {
    /// Vertex positions, model units.
    pub positions: Vec<[f64; 2]>,
    /// Every mesh edge, drawn light grey.
    pub edges: Vec<[u32; 2]>,
    /// Every face as its loop of vertices (faces are referred to by their index here).
    pub faces: Vec<Vec<u32>>,
    /// Obstacle faces (indices into `faces`), tinted dark grey.
    pub obstacle_faces: Vec<u32>,
    /// Obstacle vertices (small black dots).
    pub obstacle_vertices: Vec<u32>,
    /// Sinks (red dots).
    pub sinks: Vec<u32>,
    /// Point-to-point samples (yellow dots); `None` when the design has no point-to-point paths
    /// (then the legend does not list them).
    pub samples: Option<Vec<u32>>,
    /// Forced edges, then the edges of the through routes (dashed green).
    pub forced_edges: Vec<[u32; 2]>,
    /// Forced vertices (green dots).
    pub forced_vertices: Vec<u32>,
    /// The spec has through routes (the legend lists "forced / route" even without forced
    /// elements).
    pub through_routes: bool,
    /// Active edges with their distance value, coloured on the ramp from 0 to `distance_max`.
    pub active: Vec<ActiveEdge>,
    /// The top of the colour ramp (the legend's range is 0 to it).
    pub distance_max: f64,
    /// Rooms and blocks of the design.
    pub rooms: Vec<Room>,
    /// Room types by template index (empty when the spec tiles no rooms); the legend lists those
    /// with a room.
    pub room_types: Vec<RoomType>,
}

/// An active edge and its value on the colour ramp.
#[derive(Clone, Debug, PartialEq)]
pub struct ActiveEdge {
    /// Its vertices.
    pub edge: [u32; 2],
    /// Distance to the nearest sink (infinite: none reachable, drawn at the ramp's top).
    pub distance: f64,
}

/// A room or block of the design.
#[derive(Clone, Debug, PartialEq)]
pub struct Room {
    /// Its faces (indices into [`NetworkScene::faces`]), filled with its type's colour.
    pub faces: Vec<u32>,
    /// Its outline, drawn over the mesh.
    pub boundary_edges: Vec<[u32; 2]>,
    /// Its type (index into [`NetworkScene::room_types`], lettered by [`template_letter`]).
    pub template: usize,
    /// Where its letter goes, model units.
    pub label_at: [f64; 2],
}

/// A room type: its name and fill colour.
#[derive(Clone, Debug, PartialEq)]
pub struct RoomType {
    /// Its name.
    pub name: String,
    /// Its colour (SVG colour text).
    pub colour: String,
}

/// The conflicting sets of requirements of a spec without a solution.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConflictScene {
    /// The sets, coloured 1, 2, … in this order.
    pub conflicts: Vec<ConflictMarks>,
    /// The search finished (otherwise the legend says it stopped at its limits).
    pub complete: bool,
}

/// One conflicting set of requirements.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConflictMarks {
    /// Proven minimal (otherwise the legend says so).
    pub minimal: bool,
    /// Its requirements.
    pub requirements: Vec<RequirementMarks>,
}

/// One requirement of a conflict: its legend text and the elements it concerns.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RequirementMarks {
    /// The legend line (wrapped at about 40 characters).
    pub text: String,
    /// Vertices, ringed.
    pub vertices: Vec<u32>,
    /// Edges as vertex pairs, drawn thick.
    pub edges: Vec<[u32; 2]>,
    /// Faces (indices into [`NetworkScene::faces`]), tinted.
    pub faces: Vec<u32>,
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

/// The scene's frame in the picture: scale, margins, the title band and the legend column.
struct Frame<'a> {
    scene: &'a NetworkScene,
    lo: [f64; 2],
    hi: [f64; 2],
    scale: f64,
    margin: f64,
    title_h: f64,
    /// Picture width.
    w: f64,
    /// Picture height.
    h: f64,
    /// Width of the legend column on the right.
    legend_w: f64,
    /// Stroke width of network edges.
    stroke: f64,
}

impl Frame<'_> {
    fn new(scene: &NetworkScene, legend_w: f64) -> Frame<'_> {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in &scene.positions {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
        let scale = 640.0 / span;
        let (margin, title_h) = (24.0, 44.0);
        let w = (hi[0] - lo[0]) * scale + 2.0 * margin + legend_w;
        let h = (hi[1] - lo[1]) * scale + 2.0 * margin + title_h;
        Frame { scene, lo, hi, scale, margin, title_h, w, h, legend_w, stroke: (scale * 0.12).clamp(1.5, 6.0) }
    }

    /// Picture coordinates of a model point.
    fn tx(&self, q: [f64; 2]) -> (f64, f64) {
        ((q[0] - self.lo[0]) * self.scale + self.margin, (self.hi[1] - q[1]) * self.scale + self.margin + self.title_h)
    }

    /// Picture coordinates of vertex `v`.
    fn at(&self, v: u32) -> (f64, f64) {
        self.tx(self.scene.positions[v as usize])
    }

    /// The top-left corner of the legend column.
    fn legend_origin(&self) -> (f64, f64) {
        (self.w - self.legend_w + 10.0, self.margin + self.title_h)
    }

    /// The two title lines.
    fn title(&self, s: &mut Svg, name: &str, line: &str) {
        s.text(self.margin, 20.0, r#"font-size="15" font-weight="bold""#, name);
        s.text(self.margin, 38.0, r#"font-size="12""#, line);
    }

    fn face_points(&self, f: u32) -> String {
        let pts: Vec<String> = self.scene.faces[f as usize]
            .iter()
            .map(|&v| {
                let (x, y) = self.at(v);
                format!("{x:.2},{y:.2}")
            })
            .collect();
        pts.join(" ")
    }

    fn edge_line(&self, [a, b]: [u32; 2], attrs: &str) -> String {
        let ((x1, y1), (x2, y2)) = (self.at(a), self.at(b));
        let sep = if attrs.is_empty() { "" } else { " " };
        format!(r#"<line x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}"{sep}{attrs}/>"#)
    }

    /// The mesh in light grey and the obstacle faces in dark grey.
    fn mesh_and_obstacles(&self, s: &mut Svg) {
        for &f in &self.scene.obstacle_faces {
            let _ = writeln!(s, r##"<polygon points="{}" fill="#333" fill-opacity="0.55"/>"##, self.face_points(f));
        }
        let _ = writeln!(s, r##"<g stroke="#d6d6d6" stroke-width="1">"##);
        for &e in &self.scene.edges {
            let _ = writeln!(s, "{}", self.edge_line(e, ""));
        }
        let _ = writeln!(s, "</g>");
    }

    /// Forced edges and through routes, dashed green.
    fn forced_edges(&self, s: &mut Svg) {
        if !self.scene.forced_edges.is_empty() {
            let _ = writeln!(
                s,
                r##"<g stroke="#17a34a" stroke-width="{:.2}" stroke-dasharray="4 3" fill="none">"##,
                self.stroke * 0.5
            );
            for &e in &self.scene.forced_edges {
                let _ = writeln!(s, "{}", self.edge_line(e, ""));
            }
            let _ = writeln!(s, "</g>");
        }
    }

    /// A dot on vertex `v`.
    fn dot(&self, s: &mut Svg, v: u32, fill: &str, r: f64) {
        let (x, y) = self.at(v);
        let _ = writeln!(
            s,
            r##"<circle cx="{x:.2}" cy="{y:.2}" r="{r:.2}" fill="{fill}" stroke="#222" stroke-width="0.6"/>"##
        );
    }

    /// The legend's point items (sink, p2p sample, obstacle, forced / route) that the picture
    /// shows, from `ly` on; returns the next line's `ly`.
    fn point_legend(&self, s: &mut Svg, lx: f64, mut ly: f64, samples: bool) -> f64 {
        for (c, label) in point_legend(self.scene, samples) {
            let _ = writeln!(
                s,
                r##"<circle cx="{:.1}" cy="{:.1}" r="5" fill="{c}" stroke="#222" stroke-width="0.6"/>"##,
                lx + 6.0,
                ly - 4.0
            );
            s.text(lx + 18.0, ly, r#"font-size="11""#, label);
            ly += 18.0;
        }
        ly
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
fn point_legend(scene: &NetworkScene, samples: bool) -> Vec<(&'static str, &'static str)> {
    let mut items = vec![("#e02424", "sink")];
    if samples {
        items.push(("#facc15", "p2p sample"));
    }
    if !scene.obstacle_vertices.is_empty() || !scene.obstacle_faces.is_empty() {
        items.push(("#000", "obstacle"));
    }
    if !scene.forced_edges.is_empty() || !scene.forced_vertices.is_empty() || scene.through_routes {
        items.push(("#17a34a", "forced / route"));
    }
    items
}

/// Where each vertex of the scene lands in the picture [`svg`] draws (picture coordinates), for
/// pointing at vertices and edges of the drawing.
pub fn picture_points(scene: &NetworkScene) -> Vec<[f64; 2]> {
    let fr = Frame::new(scene, 150.0);
    (0..scene.positions.len() as u32).map(|v| fr.at(v)).map(|(x, y)| [x, y]).collect()
}

/// Draws the network as SVG text: rooms filled with their type's colour and marked with its
/// letter ([`template_letter`]), active edges on the distance ramp, the points. The legend lists
/// only what is drawn.
pub fn svg(scene: &NetworkScene, caption: &Caption) -> String {
    let fr = Frame::new(scene, 150.0);
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
    for room in &scene.rooms {
        for &f in &room.faces {
            let _ = writeln!(
                s,
                r#"<polygon points="{}" fill="{}" stroke="none"/>"#,
                fr.face_points(f),
                escape(&scene.room_types[room.template].colour)
            );
        }
    }
    fr.mesh_and_obstacles(&mut s);
    // Room outlines (their boundary edges), over the mesh, and each room's letter.
    for room in &scene.rooms {
        for &e in &room.boundary_edges {
            let _ = writeln!(s, "{}", fr.edge_line(e, r##"stroke="#555" stroke-width="1.5""##));
        }
    }
    for room in &scene.rooms {
        let pts = room.faces.iter().flat_map(|&f| scene.faces[f as usize].iter().map(|&v| scene.positions[v as usize]));
        let (lo, hi) = pts.fold(([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]), |(lo, hi), q| {
            ([lo[0].min(q[0]), lo[1].min(q[1])], [hi[0].max(q[0]), hi[1].max(q[1])])
        });
        let size = ((hi[0] - lo[0]).min(hi[1] - lo[1]) * fr.scale * 0.3).min(14.0);
        if size >= 5.0 {
            let (x, y) = fr.tx(room.label_at);
            s.text(
                x,
                y + size * 0.35,
                &format!(
                    r##"class="room-type" font-size="{size:.1}" text-anchor="middle" fill="#333" fill-opacity="0.75""##
                ),
                &template_letter(room.template),
            );
        }
    }
    // Active edges on the ramp.
    let dmax = scene.distance_max;
    let _ = writeln!(s, r#"<g stroke-width="{stroke:.2}" stroke-linecap="round">"#);
    for a in &scene.active {
        let t = if dmax > 0.0 { a.distance / dmax } else { 0.0 };
        let _ = writeln!(s, "{}", fr.edge_line(a.edge, &format!(r#"stroke="{}""#, ramp(t))));
    }
    let _ = writeln!(s, "</g>");
    fr.forced_edges(&mut s);
    // Points.
    let r = (stroke * 1.2).max(3.0);
    for &v in &scene.obstacle_vertices {
        fr.dot(&mut s, v, "#000", r * 0.6);
    }
    for &v in &scene.sinks {
        fr.dot(&mut s, v, "#e02424", r);
    }
    for &v in scene.samples.iter().flatten() {
        fr.dot(&mut s, v, "#facc15", r);
    }
    for &v in &scene.forced_vertices {
        fr.dot(&mut s, v, "#17a34a", r);
    }
    // Legend: only what is drawn.
    let (lx, mut ly) = fr.legend_origin();
    if !scene.active.is_empty() {
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
    ly = fr.point_legend(&mut s, lx, ly, scene.samples.is_some());
    ly += 8.0;
    for (i, t) in scene.room_types.iter().enumerate() {
        if !scene.rooms.iter().any(|room| room.template == i) {
            continue;
        }
        let _ = writeln!(
            s,
            r##"<rect x="{:.1}" y="{:.1}" width="12" height="12" fill="{}" stroke="#555"/>"##,
            lx,
            ly - 10.0,
            escape(&t.colour)
        );
        s.text(lx + 6.0, ly - 0.5, r##"font-size="9" text-anchor="middle" fill="#333""##, &template_letter(i));
        s.text(lx + 18.0, ly, r#"font-size="11""#, &t.name);
        ly += 18.0;
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

/// A spec without a solution (`scene`: its mesh, obstacles, sinks, forced elements and through
/// routes, drawn as in [`svg`]), with the elements of each conflicting set of requirements
/// highlighted in the conflict's colour (`class="conflict" data-conflict="k"`: faces tinted,
/// edges thick, vertices ringed) and every requirement of each set listed in the legend
/// (requirements without a place, such as coverage, only there).
pub fn conflict_svg(scene: &NetworkScene, conflicts: &ConflictScene, caption: &Caption) -> String {
    let fr = Frame::new(scene, 270.0);
    let stroke = fr.stroke;
    let legend_h: f64 = conflicts
        .conflicts
        .iter()
        .map(|c| 24.0 + 13.0 * c.requirements.iter().map(|r| wrap(&r.text, 40).len()).sum::<usize>() as f64)
        .sum::<f64>()
        + 22.0
        + 18.0 * point_legend(scene, false).len() as f64;
    let mut s = Svg::new(fr.w, fr.h.max(fr.legend_origin().1 + legend_h + 10.0), None);
    let n = conflicts.conflicts.len();
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
    // Tinted faces first, under the mesh.
    for (k, c) in conflicts.conflicts.iter().enumerate() {
        let col = CONFLICT_COLORS[k % CONFLICT_COLORS.len()];
        for r in &c.requirements {
            for &f in &r.faces {
                let _ = writeln!(
                    s,
                    r#"<polygon class="conflict" data-conflict="{}" points="{}" fill="{col}" fill-opacity="0.3"/>"#,
                    k + 1,
                    fr.face_points(f)
                );
            }
        }
    }
    fr.mesh_and_obstacles(&mut s);
    fr.forced_edges(&mut s);
    // The conflicts' edges and vertices.
    let r = (stroke * 1.2).max(3.0);
    for (k, c) in conflicts.conflicts.iter().enumerate() {
        let col = CONFLICT_COLORS[k % CONFLICT_COLORS.len()];
        // Later conflicts drawn thinner, so shared elements show every colour.
        let width = stroke * (1.6 - 0.25 * k.min(4) as f64);
        for req in &c.requirements {
            for &[a, b] in &req.edges {
                let ((x1, y1), (x2, y2)) = (fr.at(a), fr.at(b));
                let _ = writeln!(
                    s,
                    r#"<line class="conflict" data-conflict="{}" x1="{x1:.2}" y1="{y1:.2}" x2="{x2:.2}" y2="{y2:.2}" stroke="{col}" stroke-width="{width:.2}" stroke-linecap="round" stroke-opacity="0.85"/>"#,
                    k + 1
                );
            }
        }
    }
    for &v in &scene.obstacle_vertices {
        fr.dot(&mut s, v, "#000", r * 0.6);
    }
    for &v in &scene.sinks {
        fr.dot(&mut s, v, "#e02424", r);
    }
    for &v in &scene.forced_vertices {
        fr.dot(&mut s, v, "#17a34a", r);
    }
    for (k, c) in conflicts.conflicts.iter().enumerate() {
        let col = CONFLICT_COLORS[k % CONFLICT_COLORS.len()];
        for req in &c.requirements {
            for &v in &req.vertices {
                let (x, y) = fr.at(v);
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
    for (k, c) in conflicts.conflicts.iter().enumerate() {
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
            for (i, line) in wrap(&req.text, 40).iter().enumerate() {
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
    if !conflicts.complete {
        s.text(lx, ly, r#"font-size="10" font-style="italic""#, "search stopped at its limits");
        ly += 16.0;
    }
    ly += 6.0;
    fr.point_legend(&mut s, lx, ly, false);
    s.finish()
}
