//! A city's streets: sub-regions tinted, streets by level (width and colour), the level-1 roads
//! as given, obstacles and explicit sinks, region names, a legend of what is drawn, and the
//! metrics. The input is plain geometry (`urban` builds it), in model units.

use super::writer::Svg;
use std::fmt::Write;

/// Level colours and stroke widths (pixels) for pictures.
const LEVEL_STYLE: [(&str, f64); 5] =
    [("#999999", 1.0), ("#252525", 5.0), ("#d94801", 3.4), ("#2171b5", 2.2), ("#41ab5d", 1.5)];

/// The colour and stroke width of a street level.
pub fn level_style(level: u8) -> (&'static str, f64) {
    LEVEL_STYLE[(level as usize).min(4)]
}

/// A sub-region.
#[derive(Clone, Debug, PartialEq)]
pub struct RegionShape {
    /// Its index (tint and `data-region`).
    pub index: usize,
    /// Its name.
    pub name: String,
    /// Outer ring.
    pub outer: Vec<[f64; 2]>,
    /// Holes.
    pub holes: Vec<Vec<[f64; 2]>>,
    /// Where its name goes.
    pub label_point: [f64; 2],
    /// Some level ended without a network (the name is red, marked "incomplete").
    pub incomplete: bool,
}

/// Everything a city picture shows.
#[derive(Clone, Debug, PartialEq)]
pub struct CityPicture {
    /// The title line.
    pub title: String,
    /// The lines under it (the metrics).
    pub subtitle: Vec<String>,
    /// Lower-left and upper-right corners of the domain.
    pub bounds: ([f64; 2], [f64; 2]),
    /// Sub-regions.
    pub regions: Vec<RegionShape>,
    /// Level 1 (major roads and the domain boundary) as segments.
    pub major: Vec<[[f64; 2]; 2]>,
    /// Streets of levels ≥ 2: level and polyline.
    pub streets: Vec<(u8, Vec<[f64; 2]>)>,
    /// Obstacle polygons (e.g. a historic site).
    pub obstacles: Vec<Vec<[f64; 2]>>,
    /// Explicit sinks (where streets must lead, e.g. existing intersections).
    pub sinks: Vec<[f64; 2]>,
}

/// The city picture as SVG text.
pub fn city_svg(c: &CityPicture) -> String {
    let (lo, hi) = c.bounds;
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
    let scale = 900.0 / span;
    let (margin, legend_w) = (24.0, 170.0);
    let title_h = 44.0 + 16.0 * c.subtitle.len() as f64;
    let w = (hi[0] - lo[0]) * scale + 2.0 * margin + legend_w;
    let h = ((hi[1] - lo[1]) * scale + 2.0 * margin + title_h).max(title_h + 200.0);
    let tx = |q: [f64; 2]| ((q[0] - lo[0]) * scale + margin, (hi[1] - q[1]) * scale + margin + title_h);
    let path = |pts: &[[f64; 2]], close: bool| -> String {
        let mut d = String::new();
        for (i, &p) in pts.iter().enumerate() {
            let (x, y) = tx(p);
            let _ = write!(d, "{}{x:.2},{y:.2}", if i == 0 { "M" } else { " L" });
        }
        if close {
            d.push_str(" Z");
        }
        d
    };
    let mut s = Svg::new(w, h, None);
    s.text(margin, 22.0, r#"font-size="15" font-weight="bold""#, &c.title);
    for (i, line) in c.subtitle.iter().enumerate() {
        s.text(margin, 42.0 + 16.0 * i as f64, r#"font-size="12""#, line);
    }
    const TINTS: [&str; 6] = ["#f7f4ea", "#eef3f8", "#f3eef6", "#eef6ee", "#f8efea", "#f0f0f0"];
    for r in &c.regions {
        let mut d = path(&r.outer, true);
        for hole in &r.holes {
            d.push(' ');
            d.push_str(&path(hole, true));
        }
        let _ = writeln!(
            s,
            r#"<path d="{d}" fill="{}" fill-rule="evenodd" stroke="none" data-region="{}"/>"#,
            TINTS[r.index % TINTS.len()],
            r.index
        );
    }
    for o in &c.obstacles {
        let _ = writeln!(
            s,
            r##"<path class="obstacle" d="{}" fill="#333" fill-opacity="0.45" stroke="#333" stroke-width="1"/>"##,
            path(o, true)
        );
    }
    let (colour, width) = level_style(1);
    let mut d = String::new();
    for seg in &c.major {
        d.push_str(&path(seg, false));
        d.push(' ');
    }
    let _ = writeln!(
        s,
        r#"<path d="{}" fill="none" stroke="{colour}" stroke-width="{width}" stroke-linecap="round" data-level="1"/>"#,
        d.trim_end()
    );
    let mut order: Vec<&(u8, Vec<[f64; 2]>)> = c.streets.iter().collect();
    order.sort_by_key(|sn| std::cmp::Reverse(sn.0));
    for (level, pts) in order {
        let (colour, width) = level_style(*level);
        let _ = writeln!(
            s,
            r#"<path d="{}" fill="none" stroke="{colour}" stroke-width="{width}" stroke-linecap="round" stroke-linejoin="round" data-level="{level}"/>"#,
            path(pts, false)
        );
    }
    for &p in &c.sinks {
        let (x, y) = tx(p);
        let _ = writeln!(
            s,
            r##"<circle class="sink" cx="{x:.2}" cy="{y:.2}" r="5" fill="#e02424" stroke="#222" stroke-width="0.8"/>"##
        );
    }
    for r in &c.regions {
        let (x, y) = tx(r.label_point);
        let attrs = format!(
            r#"font-size="11" text-anchor="middle" fill="{}" stroke="white" stroke-width="3" paint-order="stroke""#,
            if r.incomplete { "#b30000" } else { "#333333" }
        );
        s.text(x, y, &attrs, &format!("{}{}", r.name, if r.incomplete { " (incomplete)" } else { "" }));
    }
    // Legend: the levels drawn, then obstacles and sinks if any.
    let lx = w - legend_w + 10.0;
    let mut ly = title_h + margin + 10.0;
    let present = |level: u8| level == 1 || c.streets.iter().any(|(l, _)| *l == level);
    for (level, label) in [
        (1u8, "level 1: major roads"),
        (2, "level 2: collectors"),
        (3, "level 3: local roads"),
        (4, "level 4: cul-de-sacs"),
    ] {
        if !present(level) {
            continue;
        }
        let (colour, width) = level_style(level);
        let _ = writeln!(
            s,
            r#"<line x1="{lx}" y1="{ly}" x2="{}" y2="{ly}" stroke="{colour}" stroke-width="{width}"/>"#,
            lx + 30.0
        );
        s.text(lx + 36.0, ly + 4.0, r#"font-size="11""#, label);
        ly += 22.0;
    }
    if !c.obstacles.is_empty() {
        let _ = writeln!(
            s,
            r##"<rect x="{lx}" y="{}" width="30" height="12" fill="#333" fill-opacity="0.45" stroke="#333"/>"##,
            ly - 6.0
        );
        s.text(lx + 36.0, ly + 4.0, r#"font-size="11""#, "obstacle");
        ly += 22.0;
    }
    if !c.sinks.is_empty() {
        let _ = writeln!(
            s,
            r##"<circle cx="{}" cy="{ly}" r="5" fill="#e02424" stroke="#222" stroke-width="0.8"/>"##,
            lx + 15.0
        );
        s.text(lx + 36.0, ly + 4.0, r#"font-size="11""#, "sink (given)");
    }
    s.finish()
}
