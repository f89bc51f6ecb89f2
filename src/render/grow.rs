//! A grown road network (`netspec grow`): terrain in elevation bands with contour lines, water,
//! blocks coloured by age (older darker), minor roads grey under major roads (yellow), bridges and
//! harbours, cities and nuclei; and pictures side by side (a step series, a gallery). Plain data
//! in metres (y up).

use super::writer::{Fit, Svg};
use std::fmt::Write;

/// Elevation bands on a raster of `nx × ny` cells of `cell` metres, row 0 at y = 0.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Bands {
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Cell size (metres).
    pub cell: f64,
    /// Band per cell (0 lowest).
    pub band: Vec<u8>,
}

/// A road or waterway piece.
#[derive(Clone, Debug, PartialEq)]
pub struct RoadLine {
    /// One end.
    pub a: [f64; 2],
    /// The other.
    pub b: [f64; 2],
    /// `minor`, `major`, `bridge`, `harbour` or `water`.
    pub class: &'static str,
    /// Lanes.
    pub width: f64,
}

/// What the picture shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GrowScene {
    /// Map width and height (metres).
    pub size: [f64; 2],
    /// Terrain bands.
    pub bands: Bands,
    /// Contour lines: straight pieces (metres).
    pub contours: Vec<[[f64; 2]; 2]>,
    /// Water polygons.
    pub water: Vec<Vec<[f64; 2]>>,
    /// Rivers: centre line and width (metres).
    pub rivers: Vec<(Vec<[f64; 2]>, f64)>,
    /// Forbidden areas.
    pub forbidden: Vec<Vec<[f64; 2]>>,
    /// Built-up blocks with their age in [0, 1] (0 oldest).
    pub blocks: Vec<(Vec<[f64; 2]>, f64)>,
    /// Roads and waterways.
    pub roads: Vec<RoadLine>,
    /// Neighbouring cities.
    pub cities: Vec<[f64; 2]>,
    /// Nuclei.
    pub nuclei: Vec<[f64; 2]>,
    /// Caption.
    pub caption: String,
}

const BAND_COLOURS: [&str; 8] =
    ["#edf3e4", "#e3ecd3", "#e9e5c9", "#e6dcbc", "#dfcfae", "#d6c1a0", "#ccb393", "#c2a687"];

/// The picture as SVG text (about 800 pixels across).
pub fn grow_svg(scene: &GrowScene) -> String {
    let corners = [[0.0, 0.0], scene.size];
    let fit = Fit::new(corners.iter(), 800.0);
    let tx = |p: [f64; 2]| fit.tx(p);
    let pts =
        |r: &[[f64; 2]]| r.iter().map(|&p| tx(p)).map(|(x, y)| format!("{x:.1},{y:.1}")).collect::<Vec<_>>().join(" ");
    let mut svg = Svg::new(fit.width, fit.height, Some(12.0));
    let b = &scene.bands;
    for y in 0..b.ny {
        let mut x = 0;
        while x < b.nx {
            let v = b.band[y * b.nx + x];
            let mut e = x + 1;
            while e < b.nx && b.band[y * b.nx + e] == v {
                e += 1;
            }
            let (x0, y0) = tx([x as f64 * b.cell, ((y + 1) as f64 * b.cell).min(scene.size[1])]);
            let (x1, y1) = tx([(e as f64 * b.cell).min(scene.size[0]), y as f64 * b.cell]);
            let _ = writeln!(
                svg,
                r#"<rect x="{x0:.1}" y="{y0:.1}" width="{:.1}" height="{:.1}" fill="{}"/>"#,
                (x1 - x0) + 0.3,
                (y1 - y0) + 0.3,
                BAND_COLOURS[(v as usize).min(BAND_COLOURS.len() - 1)]
            );
            x = e;
        }
    }
    for c in &scene.contours {
        let ((x0, y0), (x1, y1)) = (tx(c[0]), tx(c[1]));
        let _ = writeln!(
            svg,
            r##"<line class="contour" x1="{x0:.1}" y1="{y0:.1}" x2="{x1:.1}" y2="{y1:.1}" stroke="#a89878" stroke-width="0.6"/>"##
        );
    }
    for w in &scene.water {
        let _ = writeln!(svg, r##"<polygon class="water" points="{}" fill="#9ecae1" stroke="none"/>"##, pts(w));
    }
    for (line, width) in &scene.rivers {
        let _ = writeln!(
            svg,
            r##"<polyline class="river" points="{}" fill="none" stroke="#9ecae1" stroke-width="{:.2}" stroke-linejoin="round" stroke-linecap="round"/>"##,
            pts(line),
            width * fit.scale
        );
    }
    for f in &scene.forbidden {
        let _ = writeln!(svg, r##"<polygon class="forbidden" points="{}" fill="#bdbdbd" stroke="none"/>"##, pts(f));
    }
    for (ring, age) in &scene.blocks {
        // Older blocks darker: from a dark brown-red to a light orange.
        let t = age.clamp(0.0, 1.0);
        let c = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
        let _ = writeln!(
            svg,
            r##"<polygon class="block" points="{}" fill="#{:02x}{:02x}{:02x}" stroke="none"/>"##,
            pts(ring),
            c(140.0, 253.0),
            c(81.0, 208.0),
            c(60.0, 162.0)
        );
    }
    let style = |class: &str, width: f64| -> (String, f64) {
        match class {
            "minor" => ("#737373".into(), 0.6),
            "major" => ("#fec44f".into(), 1.2 + 0.8 * width),
            "bridge" => ("#d95f0e".into(), 1.6 + 0.8 * width),
            "harbour" => ("#e31a1c".into(), 2.5),
            _ => ("#2171b5".into(), 1.0),
        }
    };
    for order in ["water", "minor", "major", "bridge", "harbour"] {
        for r in scene.roads.iter().filter(|r| r.class == order) {
            let (colour, w) = style(r.class, r.width);
            let ((x0, y0), (x1, y1)) = (tx(r.a), tx(r.b));
            let dash = if r.class == "water" { r#" stroke-dasharray="4 3""# } else { "" };
            let _ = writeln!(
                svg,
                r#"<line class="{}" x1="{x0:.1}" y1="{y0:.1}" x2="{x1:.1}" y2="{y1:.1}" stroke="{colour}" stroke-width="{w:.2}" stroke-linecap="round"{dash}/>"#,
                r.class
            );
        }
    }
    for &p in &scene.nuclei {
        let (x, y) = tx(p);
        let _ = writeln!(
            svg,
            r##"<circle class="nucleus" cx="{x:.1}" cy="{y:.1}" r="2.5" fill="none" stroke="#6a51a3" stroke-width="1"/>"##
        );
    }
    for &p in &scene.cities {
        let (x, y) = tx(p);
        let _ = writeln!(
            svg,
            r##"<circle class="city" cx="{x:.1}" cy="{y:.1}" r="6" fill="#cb181d" stroke="white" stroke-width="1.5"/>"##
        );
    }
    svg.text(fit.margin, fit.height - 8.0, "", &scene.caption);
    svg.finish()
}

/// Pictures side by side, `columns` to a row, each scaled to `panel` pixels across: a step
/// series (Figs. 2, 12) or a gallery (Fig. 10a). Each panel is a picture of [`grow_svg`].
pub fn strip_svg(panels: &[GrowScene], columns: usize, panel: f64) -> String {
    let columns = columns.max(1).min(panels.len().max(1));
    let rows = panels.len().div_ceil(columns).max(1);
    let pictures: Vec<(String, f64, f64)> = panels.iter().map(picture).collect();
    let aspect = pictures.iter().map(|p| p.2 / p.1).fold(0.0, f64::max).max(0.1);
    let (w, h) = (panel, panel * aspect);
    let mut svg = Svg::new(columns as f64 * w, rows as f64 * h, Some(12.0));
    for (i, (body, pw, ph)) in pictures.iter().enumerate() {
        let (x, y) = ((i % columns) as f64 * w, (i / columns) as f64 * h);
        let _ = writeln!(
            svg,
            r#"<svg x="{x:.1}" y="{y:.1}" width="{w:.1}" height="{:.1}" viewBox="0 0 {pw:.1} {ph:.1}">"#,
            w * ph / pw
        );
        let _ = svg.write_str(body);
        let _ = writeln!(svg, "</svg>");
    }
    svg.finish()
}

/// A scene's picture without its root element: the body, width and height.
fn picture(scene: &GrowScene) -> (String, f64, f64) {
    let fit = Fit::new([[0.0, 0.0], scene.size].iter(), 800.0);
    let full = grow_svg(scene);
    let start = full.find('\n').map_or(0, |i| i + 1);
    let end = full.rfind("</svg>").unwrap_or(full.len());
    (full[start..end].to_string(), fit.width, fit.height)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_every_layer() {
        let scene = GrowScene {
            size: [100.0, 100.0],
            bands: Bands { nx: 2, ny: 2, cell: 50.0, band: vec![0, 0, 1, 2] },
            contours: vec![[[0.0, 60.0], [100.0, 60.0]]],
            water: vec![vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0]]],
            rivers: vec![(vec![[0.0, 50.0], [100.0, 50.0]], 10.0)],
            forbidden: vec![],
            blocks: vec![(vec![[20.0, 20.0], [40.0, 20.0], [40.0, 40.0]], 0.5)],
            roads: vec![
                RoadLine { a: [0.0, 0.0], b: [100.0, 100.0], class: "major", width: 2.0 },
                RoadLine { a: [0.0, 100.0], b: [100.0, 0.0], class: "minor", width: 1.0 },
            ],
            cities: vec![[0.0, 0.0]],
            nuclei: vec![[50.0, 50.0]],
            caption: "test".into(),
        };
        let svg = grow_svg(&scene);
        for class in ["water", "river", "block", "major", "minor", "city", "nucleus", "contour"] {
            assert!(svg.contains(&format!("class=\"{class}\"")), "{class}");
        }
        assert!(svg.find("class=\"minor\"").unwrap() < svg.find("class=\"major\"").unwrap());
        resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
        let strip = strip_svg(&[scene.clone(), scene.clone(), scene], 2, 300.0);
        assert_eq!(strip.matches("class=\"city\"").count(), 3);
        let tree = resvg::usvg::Tree::from_str(&strip, &resvg::usvg::Options::default()).unwrap();
        assert_eq!(tree.size().width(), 600.0);
    }
}
