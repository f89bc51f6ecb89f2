//! An urban layout: parcels coloured by use (undesirable ones outlined in red), streets drawn at
//! their width and coloured by level, holes as water. Plain data in metres (y up).

use super::writer::{Fit, Svg};
use std::fmt::Write;

/// A parcel to draw.
#[derive(Clone, Debug, PartialEq)]
pub struct ParcelShape {
    /// Its ring.
    pub ring: Vec<[f64; 2]>,
    /// Its use (`residential`, `park`, `commercial`, `school`, `keep`, `other`).
    pub use_: String,
    /// Outlined in red.
    pub undesirable: bool,
    /// Its registration distance to its ideal (metres), for a template parcel.
    pub registration: Option<f64>,
}

/// What a layout picture shows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LayoutScene {
    /// The region's rings (outer ring first, then holes).
    pub rings: Vec<Vec<[f64; 2]>>,
    /// Parcels.
    pub parcels: Vec<ParcelShape>,
    /// Streets: centreline, width (metres), level.
    pub streets: Vec<(Vec<[f64; 2]>, f64, usize)>,
    /// A caption under the picture.
    pub caption: String,
}

fn fill(use_: &str) -> &'static str {
    match use_ {
        "residential" => "#fdd49e",
        "park" => "#a1d99b",
        "commercial" => "#bcbddc",
        "school" => "#fdae6b",
        "keep" => "#bdbdbd",
        _ => "#d9d9d9",
    }
}

const LEVEL_COLOURS: [&str; 4] = ["#252525", "#636363", "#969696", "#bdbdbd"];

/// The picture as SVG text (about 800 pixels across).
pub fn layout_svg(scene: &LayoutScene) -> String {
    draw(scene, &|p: &ParcelShape| fill(&p.use_).to_string(), true)
}

/// The top of the registration colour scale (metres; the paper's Fig. 10 bar runs to 6 m).
pub const REGISTRATION_SCALE: f64 = 5.0;

/// The colour of a registration distance: blue (0) through yellow to red
/// ([`REGISTRATION_SCALE`] and beyond).
fn ramp(d: f64) -> String {
    let t = (d / REGISTRATION_SCALE).clamp(0.0, 1.0);
    let (a, b, f) = if t < 0.5 {
        ([49.0, 130.0, 189.0], [255.0, 237.0, 160.0], t * 2.0)
    } else {
        ([255.0, 237.0, 160.0], [227.0, 26.0, 28.0], t * 2.0 - 1.0)
    };
    let c: Vec<u8> = (0..3).map(|i| (a[i] + (b[i] - a[i]) * f).round() as u8).collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// The parcels coloured by their registration distance to their ideal (Yang et al. 2013
/// Figs. 6 and 10): blue 0 m to red 5 m and beyond; parcels without one (not from a template)
/// light grey.
pub fn registration_svg(scene: &LayoutScene) -> String {
    draw(scene, &|p: &ParcelShape| p.registration.map_or_else(|| "#f0f0f0".to_string(), ramp), false)
}

fn draw(scene: &LayoutScene, colour: &dyn Fn(&ParcelShape) -> String, outline_undesirable: bool) -> String {
    let fit = Fit::new(scene.rings.iter().flatten(), 760.0);
    let (margin, scale, w, h) = (fit.margin, fit.scale, fit.width, fit.height);
    let tx = |p: [f64; 2]| fit.tx(p);
    let pts =
        |r: &[[f64; 2]]| r.iter().map(|&p| tx(p)).map(|(x, y)| format!("{x:.2},{y:.2}")).collect::<Vec<_>>().join(" ");
    let mut svg = Svg::new(w, h, Some(12.0));
    if let Some(outer) = scene.rings.first() {
        let _ = writeln!(
            svg,
            r##"<polygon class="region" points="{}" fill="#ffffff" stroke="#252525" stroke-width="1"/>"##,
            pts(outer)
        );
    }
    for p in &scene.parcels {
        let _ = writeln!(
            svg,
            r##"<polygon class="parcel {}" points="{}" fill="{}" stroke="#8c6d31" stroke-width="0.4"/>"##,
            p.use_,
            pts(&p.ring),
            colour(p)
        );
    }
    for p in scene.parcels.iter().filter(|p| outline_undesirable && p.undesirable) {
        let _ = writeln!(
            svg,
            r##"<polygon class="undesirable" points="{}" fill="none" stroke="#e31a1c" stroke-width="1.2"/>"##,
            pts(&p.ring)
        );
    }
    let mut streets: Vec<&(Vec<[f64; 2]>, f64, usize)> = scene.streets.iter().collect();
    streets.sort_by_key(|s| std::cmp::Reverse(s.2));
    for (line, width, level) in streets {
        let colour = LEVEL_COLOURS[(*level).min(LEVEL_COLOURS.len() - 1)];
        let _ = writeln!(
            svg,
            r##"<polyline class="street level{level}" points="{}" fill="none" stroke="{colour}" stroke-opacity="0.55" stroke-width="{:.2}" stroke-linejoin="round"/>"##,
            pts(line),
            (width * scale).max(0.8)
        );
    }
    for hole in scene.rings.iter().skip(1) {
        let _ = writeln!(
            svg,
            r##"<polygon class="hole" points="{}" fill="#9ecae1" stroke="#3182bd" stroke-width="1"/>"##,
            pts(hole)
        );
    }
    svg.text(margin, h - 8.0, "", &scene.caption);
    svg.finish()
}

/// One histogram to draw: its title, bin edges and counts.
#[derive(Clone, Debug, PartialEq)]
pub struct HistogramPanel {
    /// The title (with the unit).
    pub title: String,
    /// Bin edges (the last bin open above).
    pub edges: Vec<f64>,
    /// Counts per bin.
    pub counts: Vec<usize>,
}

/// Histograms side by side as SVG (§7's panel: parcel sizes and deformations).
pub fn histograms_svg(panels: &[HistogramPanel], caption: &str) -> String {
    let (pw, ph, gap, top, bottom) = (260.0, 180.0, 40.0, 30.0, 60.0);
    let w = gap + panels.len() as f64 * (pw + gap);
    let mut svg = Svg::new(w, top + ph + bottom, Some(11.0));
    for (k, p) in panels.iter().enumerate() {
        let x0 = gap + k as f64 * (pw + gap);
        let max = p.counts.iter().copied().max().unwrap_or(0).max(1) as f64;
        let n = p.counts.len().max(1) as f64;
        svg.text(x0, 18.0, r#"font-weight="bold""#, &p.title);
        let _ = writeln!(svg, r##"<rect x="{x0}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>"##);
        for (i, &c) in p.counts.iter().enumerate() {
            let h = ph * c as f64 / max;
            let _ = writeln!(
                svg,
                r##"<rect class="bin" x="{:.1}" y="{:.1}" width="{:.1}" height="{h:.1}" fill="#6baed6" stroke="#2171b5" stroke-width="0.5"/>"##,
                x0 + pw * i as f64 / n,
                top + ph - h,
                pw / n
            );
        }
        for (i, e) in p.edges.iter().enumerate().step_by(5) {
            let tx = x0 + pw * i as f64 / n;
            let _ = writeln!(svg, r#"<text x="{tx:.1}" y="{:.1}" text-anchor="middle">{e}</text>"#, top + ph + 14.0);
        }
        let _ = writeln!(
            svg,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"#,
            x0 - 4.0,
            top + 10.0,
            max as usize
        );
    }
    svg.text(gap, top + ph + 44.0, "", caption);
    svg.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_parcels_streets_and_holes() {
        let sq = |x: f64, s: f64| vec![[x, x], [x + s, x], [x + s, x + s], [x, x + s]];
        let scene = LayoutScene {
            rings: vec![sq(0.0, 100.0), sq(40.0, 10.0)],
            parcels: vec![ParcelShape {
                ring: sq(5.0, 20.0),
                use_: "park".into(),
                undesirable: true,
                registration: Some(6.0),
            }],
            streets: vec![(vec![[0.0, 50.0], [100.0, 50.0]], 15.0, 1)],
            caption: "test".into(),
        };
        let svg = layout_svg(&scene);
        for class in ["parcel park", "undesirable", "street level1", "hole", "region"] {
            assert!(svg.contains(&format!("class=\"{class}\"")), "{class}");
        }
        let reg = registration_svg(&scene);
        assert!(reg.contains("#e31a1c") && !reg.contains("class=\"undesirable\""), "red beyond the scale");
        assert_eq!(ramp(0.0), "#3182bd");
    }

    #[test]
    fn histograms_draw_a_bar_per_bin() {
        let p = HistogramPanel { title: "area".into(), edges: vec![0.0, 1.0, 2.0, 3.0], counts: vec![1, 0, 4] };
        let svg = histograms_svg(&[p.clone(), p], "caption");
        assert_eq!(svg.matches("class=\"bin\"").count(), 6);
    }
}
