//! An urban layout: parcels coloured by use (undesirable ones outlined in red), streets drawn at
//! their width and coloured by level, holes as water. Plain data in metres (y up).

use super::writer::{Fit, Svg};
use std::fmt::Write;

/// A parcel to draw.
#[derive(Clone, Debug, PartialEq)]
pub struct ParcelShape {
    /// Its ring.
    pub ring: Vec<[f64; 2]>,
    /// Its use (`residential`, `park`, `commercial`, `other`).
    pub use_: String,
    /// Outlined in red.
    pub undesirable: bool,
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
        _ => "#d9d9d9",
    }
}

const LEVEL_COLOURS: [&str; 4] = ["#252525", "#636363", "#969696", "#bdbdbd"];

/// The picture as SVG text (about 800 pixels across).
pub fn layout_svg(scene: &LayoutScene) -> String {
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
            fill(&p.use_)
        );
    }
    for p in scene.parcels.iter().filter(|p| p.undesirable) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_parcels_streets_and_holes() {
        let sq = |x: f64, s: f64| vec![[x, x], [x + s, x], [x + s, x + s], [x, x + s]];
        let scene = LayoutScene {
            rings: vec![sq(0.0, 100.0), sq(40.0, 10.0)],
            parcels: vec![ParcelShape { ring: sq(5.0, 20.0), use_: "park".into(), undesirable: true }],
            streets: vec![(vec![[0.0, 50.0], [100.0, 50.0]], 15.0, 1)],
            caption: "test".into(),
        };
        let svg = layout_svg(&scene);
        for class in ["parcel park", "undesirable", "street level1", "hole", "region"] {
            assert!(svg.contains(&format!("class=\"{class}\"")), "{class}");
        }
    }
}
