//! Street networks side by side at one scale, each with its orientation rose under it (the
//! polar histogram of street bearings OSMnx draws: 36 bars, north up, each bar's area
//! proportional to its share), and a rose alone.

use super::city::level_style;
use super::writer::{escape, Svg};
use std::fmt::Write;

/// One network to draw.
#[derive(Clone, Debug, PartialEq)]
pub struct StreetPanel {
    /// Its title.
    pub title: String,
    /// Lines of numbers under the title.
    pub lines: Vec<String>,
    /// The region's rings (outer first, then holes), metres.
    pub region: Vec<Vec<[f64; 2]>>,
    /// Streets: level and polyline, metres.
    pub streets: Vec<(u8, Vec<[f64; 2]>)>,
    /// The 36-bin bearing histogram (bin `k` centred on `10 k`°).
    pub bins: Vec<f64>,
}

/// Pixels per metre that fit `span` metres in `px` pixels.
fn scale(span: f64, px: f64) -> f64 {
    px / span.max(1e-9)
}

/// Writes a rose of `bins` centred at `(cx, cy)` with radius `r`.
fn rose(s: &mut Svg, bins: &[f64], cx: f64, cy: f64, r: f64) {
    let _ = writeln!(s, r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{r:.1}" fill="#f7f7f7" stroke="#cccccc"/>"##);
    for (k, name) in [(0, "N"), (9, "E"), (18, "S"), (27, "W")] {
        let a = (k as f64 * 10.0).to_radians();
        let (x, y) = (cx + (r + 9.0) * a.sin(), cy - (r + 9.0) * a.cos() + 4.0);
        s.text(x, y, r##"text-anchor="middle" font-size="10" fill="#777777""##, name);
    }
    let max = bins.iter().copied().fold(0.0, f64::max);
    if max <= 0.0 {
        return;
    }
    let n = bins.len() as f64;
    for (k, &w) in bins.iter().enumerate() {
        if w <= 0.0 {
            continue;
        }
        let rr = r * (w / max).sqrt();
        let (a0, a1) = (((k as f64 - 0.5) * 360.0 / n).to_radians(), ((k as f64 + 0.5) * 360.0 / n).to_radians());
        let p = |a: f64| (cx + rr * a.sin(), cy - rr * a.cos());
        let ((x0, y0), (x1, y1)) = (p(a0), p(a1));
        let _ = writeln!(
            s,
            r##"<path d="M{cx:.1},{cy:.1} L{x0:.2},{y0:.2} A{rr:.2},{rr:.2} 0 0,1 {x1:.2},{y1:.2} Z" fill="#2171b5" fill-opacity="0.8" stroke="#08306b" stroke-width="0.5"/>"##
        );
    }
}

/// A rose alone, with a title.
pub fn rose_svg(title: &str, bins: &[f64]) -> String {
    let mut s = Svg::new(260.0, 290.0, Some(12.0));
    s.text(130.0, 20.0, r#"text-anchor="middle""#, title);
    rose(&mut s, bins, 130.0, 160.0, 100.0);
    s.finish()
}

/// The panels side by side, every one drawn at the same scale over the same `bounds` (metres,
/// lower-left and upper-right), streets outside the region faint, a rose under each.
pub fn panels_svg(panels: &[StreetPanel], bounds: ([f64; 2], [f64; 2]), panel_px: f64) -> String {
    let (lo, hi) = bounds;
    let k = scale((hi[0] - lo[0]).max(hi[1] - lo[1]), panel_px);
    let (w, h) = ((hi[0] - lo[0]) * k, (hi[1] - lo[1]) * k);
    let lines = panels.iter().map(|p| p.lines.len()).max().unwrap_or(0) as f64;
    let (margin, head) = (16.0, 22.0 + 14.0 * lines);
    let rose_r = (w.min(220.0) / 2.0 - 14.0).max(30.0);
    let width = panels.len().max(1) as f64 * (w + margin) + margin;
    let height = head + h + 2.0 * rose_r + 60.0;
    let mut s = Svg::new(width, height, Some(12.0));
    for (i, p) in panels.iter().enumerate() {
        let x0 = margin + i as f64 * (w + margin);
        let y0 = head;
        let tx = |q: [f64; 2]| (x0 + (q[0] - lo[0]) * k, y0 + (hi[1] - q[1]) * k);
        s.text(x0, 16.0, r#"font-weight="bold""#, &p.title);
        for (j, l) in p.lines.iter().enumerate() {
            s.text(x0, 32.0 + 14.0 * j as f64, r##"font-size="10" fill="#444444""##, l);
        }
        let _ = writeln!(s, r##"<g data-panel="{}">"##, escape(&p.title));
        let mut d = String::new();
        for ring in &p.region {
            for (j, &q) in ring.iter().enumerate() {
                let (x, y) = tx(q);
                let _ = write!(d, "{}{x:.1},{y:.1} ", if j == 0 { "M" } else { "L" });
            }
            d.push_str("Z ");
        }
        let _ = writeln!(s, r##"<path d="{d}" fill="#fbf8ef" fill-rule="evenodd" stroke="#bbbbbb"/>"##);
        let mut by_level: Vec<&(u8, Vec<[f64; 2]>)> = p.streets.iter().collect();
        by_level.sort_by_key(|(l, _)| std::cmp::Reverse(*l));
        for (level, line) in by_level {
            let (colour, width) = level_style(*level);
            let pts: Vec<String> = line
                .iter()
                .map(|&q| {
                    let (x, y) = tx(q);
                    format!("{x:.1},{y:.1}")
                })
                .collect();
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{colour}" stroke-width="{:.2}" stroke-linecap="round"/>"#,
                pts.join(" "),
                (width * 0.45).max(0.8)
            );
        }
        let _ = writeln!(s, "</g>");
        rose(&mut s, &p.bins, x0 + w / 2.0, y0 + h + rose_r + 30.0, rose_r);
    }
    let (bar, label) = scale_bar(k);
    let y = height - 10.0;
    let _ = writeln!(
        s,
        r##"<line x1="{margin}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#333333" stroke-width="2"/>"##,
        margin + bar
    );
    s.text(margin + bar + 6.0, y + 4.0, r#"font-size="10""#, &label);
    s.finish()
}

/// A round length for a scale bar at `k` pixels per metre: its pixels and label.
fn scale_bar(k: f64) -> (f64, String) {
    let target = 120.0 / k;
    let step = [10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 5000.0]
        .into_iter()
        .rev()
        .find(|&m| m <= target)
        .unwrap_or(10.0);
    (step * k, if step >= 1000.0 { format!("{} km", step / 1000.0) } else { format!("{step} m") })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panels_share_one_scale_and_roses_are_drawn() {
        let square = vec![[0.0, 0.0], [400.0, 0.0], [400.0, 400.0], [0.0, 400.0]];
        let mut bins = vec![0.0; 36];
        bins[0] = 400.0;
        bins[18] = 400.0;
        bins[9] = 100.0;
        bins[27] = 100.0;
        let panel = |t: &str| StreetPanel {
            title: t.into(),
            lines: vec!["12.6 km/km²".into()],
            region: vec![square.clone()],
            streets: vec![(3, vec![[0.0, 200.0], [400.0, 200.0]]), (1, vec![[200.0, 0.0], [200.0, 400.0]])],
            bins: bins.clone(),
        };
        let svg = panels_svg(&[panel("map"), panel("layout")], ([0.0, 0.0], [400.0, 400.0]), 300.0);
        assert_eq!(svg.matches("<polyline").count(), 4);
        assert_eq!(svg.matches("<path d=\"M").count(), 2 + 8, "two regions, four bars per rose");
        resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default()).unwrap();
        assert!(rose_svg("map", &bins).contains("<circle"));
        assert_eq!(scale_bar(1.0).1, "100 m");
    }
}
