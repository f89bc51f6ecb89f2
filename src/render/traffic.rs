//! Pictures of traffic evaluations: the network coloured by traffic volume per street, a
//! travel-time histogram, and a comparison of several designs (travel-time distributions and
//! key numbers side by side). SVG by hand, like the rest of `render`. The input is plain data
//! ([`VolumeScene`], [`TrafficNumbers`]; `traffic::picture` builds it from an evaluation).

use std::collections::BTreeMap;
use std::fmt::Write as _;

/// The numbers of one traffic evaluation that the pictures show.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TrafficNumbers {
    /// The design's name.
    pub name: String,
    /// `sumo --version`.
    pub sumo_version: String,
    /// Seconds during which trips departed.
    pub duration: f64,
    /// Through trips per hour.
    pub through_per_hour: f64,
    /// Local trips per hour.
    pub local_per_hour: f64,
    /// The demand's seed.
    pub seed: u64,
    /// Vehicles inserted.
    pub inserted: u64,
    /// Vehicles arrived.
    pub arrived: u64,
    /// Teleports.
    pub teleported: u64,
    /// Mean travel time of every vehicle that arrived, s.
    pub travel_time_mean: Option<f64>,
    /// Its 95th percentile, s.
    pub travel_time_p95: Option<f64>,
    /// Mean waiting time, s.
    pub waiting_time_mean: Option<f64>,
    /// Mean travel time of through traffic, s.
    pub through_travel_time_mean: Option<f64>,
    /// Mean travel time of local traffic, s.
    pub local_travel_time_mean: Option<f64>,
    /// Share of through traffic's distance on local streets.
    pub through_local_distance_share: Option<f64>,
    /// Through traffic's vehicle-kilometres on each level 1–4.
    pub through_km_by_level: [f64; 4],
    /// Travel times of the vehicles that arrived, s, per class (`through`, `local`).
    pub travel_times: BTreeMap<String, Vec<f64>>,
}

/// A street of a [`VolumeScene`].
#[derive(Clone, Debug, PartialEq)]
pub struct VolumeStreet {
    /// Its id (`data-street`).
    pub id: u32,
    /// Its level (1 major road … 4 cul-de-sac): the stroke width.
    pub level: u8,
    /// Its polyline, metres.
    pub shape: Vec<[f64; 2]>,
}

/// A network coloured by traffic volume.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VolumeScene {
    /// The evaluation's numbers (the title).
    pub numbers: TrafficNumbers,
    /// Lower-left and upper-right corners of what to frame.
    pub bounds: ([f64; 2], [f64; 2]),
    /// The region's boundary (drawn when it has at least three points).
    pub boundary: Vec<[f64; 2]>,
    /// The streets.
    pub streets: Vec<VolumeStreet>,
    /// Vehicles per street (both directions), by index into `streets` (a street without one: 0).
    pub volumes: Vec<f64>,
}

/// Design colours in comparisons.
const PALETTE: [&str; 8] = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"];

/// Stroke width per level (1 major … 4 cul-de-sac), pixels.
fn level_width(level: u8) -> f64 {
    [5.0, 3.6, 2.4, 1.7][(level.clamp(1, 4) - 1) as usize]
}

/// Yellow → orange → red → dark red, `t` in [0, 1].
fn heat(t: f64) -> String {
    const STOPS: [[f64; 3]; 5] =
        [[255., 237., 160.], [254., 178., 76.], [253., 141., 60.], [227., 26., 28.], [128., 0., 38.]];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 1.0 };
    let x = t * 4.0;
    let i = (x.floor() as usize).min(3);
    let f = x - i as f64;
    let c: Vec<u8> = (0..3).map(|k| (STOPS[i][k] + f * (STOPS[i + 1][k] - STOPS[i][k])).round() as u8).collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

use super::writer::escape as xml;

/// A round number ≥ `v` (1, 2 or 5 × 10ⁿ) for axis ends.
fn nice_ceil(v: f64) -> f64 {
    // Not above 0, or NaN.
    if v.is_nan() || v <= 0.0 {
        return 1.0;
    }
    let p = 10f64.powf(v.log10().floor());
    [1.0, 2.0, 5.0, 10.0].iter().map(|m| m * p).find(|&x| x >= v * (1.0 - 1e-12)).unwrap_or(10.0 * p)
}

fn svg_open(s: &mut String, w: f64, h: f64) {
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.1} {h:.1}" font-family="DejaVu Sans, sans-serif">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
}

fn fmt_opt(v: Option<f64>, d: usize) -> String {
    v.map_or("-".into(), |v| format!("{v:.d$}"))
}

/// The network, every street coloured by the vehicles that used it (both directions) and drawn
/// as wide as its level; the title gives the demand and the main results.
pub fn volume_svg(scene: &VolumeScene) -> String {
    let r = &scene.numbers;
    let (lo, hi) = scene.bounds;
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
    let scale = 720.0 / span;
    let (margin, title_h, legend_w) = (24.0, 76.0, 190.0);
    let w = (hi[0] - lo[0]) * scale + 2.0 * margin + legend_w;
    let h = ((hi[1] - lo[1]) * scale + 2.0 * margin + title_h).max(title_h + 330.0);
    let tx = |q: [f64; 2]| ((q[0] - lo[0]) * scale + margin, (hi[1] - q[1]) * scale + margin + title_h);
    let path = |pts: &[[f64; 2]]| {
        let mut d = String::new();
        for (i, &p) in pts.iter().enumerate() {
            let (x, y) = tx(p);
            let _ = write!(d, "{}{x:.2},{y:.2}", if i == 0 { "M" } else { " L" });
        }
        d
    };
    let mut s = String::new();
    svg_open(&mut s, w, h);
    let _ = writeln!(
        s,
        r#"<text x="{margin}" y="22" font-size="15" font-weight="bold">{} — traffic volume per street (SUMO {})</text>"#,
        xml(&r.name),
        xml(&r.sumo_version)
    );
    let _ = writeln!(
        s,
        r#"<text x="{margin}" y="42" font-size="12">{:.0} s of departures: {:.0} through + {:.0} local trips/h, seed {}; inserted {}, arrived {}, teleported {}</text>"#,
        r.duration, r.through_per_hour, r.local_per_hour, r.seed, r.inserted, r.arrived, r.teleported
    );
    let _ = writeln!(
        s,
        r#"<text x="{margin}" y="60" font-size="12">travel time mean {} s, p95 {} s; through traffic on local streets: {} of its distance</text>"#,
        fmt_opt(r.travel_time_mean, 1),
        fmt_opt(r.travel_time_p95, 1),
        r.through_local_distance_share.map_or("-".into(), |v| format!("{:.1}%", 100.0 * v))
    );
    if scene.boundary.len() >= 3 {
        let _ = writeln!(
            s,
            r##"<path d="{} Z" fill="#f6f4ee" stroke="#cccccc" stroke-width="1"/>"##,
            path(&scene.boundary)
        );
    }
    let volume = &scene.volumes;
    let vmax = volume.iter().copied().fold(0.0, f64::max);
    let mut order: Vec<usize> = (0..scene.streets.len()).collect();
    // Quiet streets first, busy ones on top.
    order.sort_by(|&a, &b| volume.get(a).unwrap_or(&0.0).total_cmp(volume.get(b).unwrap_or(&0.0)).then(a.cmp(&b)));
    for k in order {
        let e = &scene.streets[k];
        let v = volume.get(k).copied().unwrap_or(0.0);
        let colour = if v > 0.0 { heat((v / vmax).sqrt()) } else { "#c8c8c8".to_string() };
        let _ = writeln!(
            s,
            r#"<path d="{}" fill="none" stroke="{colour}" stroke-width="{:.1}" stroke-linecap="round" stroke-linejoin="round" data-street="{}" data-volume="{v:.0}"/>"#,
            path(&e.shape),
            level_width(e.level),
            e.id
        );
    }
    let lx = w - legend_w + 10.0;
    let ly = margin + title_h;
    let _ = writeln!(s, r#"<text x="{lx:.1}" y="{ly:.1}" font-size="12">vehicles per street (√ scale)</text>"#);
    for k in 0..=10 {
        let _ = writeln!(
            s,
            r#"<rect x="{lx:.1}" y="{:.1}" width="18" height="14" fill="{}"/>"#,
            ly + 8.0 + k as f64 * 14.0,
            heat(k as f64 / 10.0)
        );
    }
    for k in [0, 5, 10] {
        let v = vmax * (k as f64 / 10.0).powi(2);
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" font-size="11">{v:.0}</text>"#,
            lx + 24.0,
            ly + 19.0 + k as f64 * 14.0
        );
    }
    let _ = writeln!(
        s,
        r##"<line x1="{lx:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#c8c8c8" stroke-width="3"/>"##,
        ly + 180.0,
        lx + 18.0,
        ly + 180.0
    );
    let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" font-size="11">unused</text>"#, lx + 24.0, ly + 184.0);
    for (i, label) in ["L1 major road", "L2 collector", "L3 local street", "L4 cul-de-sac"].iter().enumerate() {
        let y = ly + 206.0 + i as f64 * 20.0;
        let _ = writeln!(
            s,
            r##"<line x1="{lx:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#555555" stroke-width="{:.1}"/>"##,
            lx + 18.0,
            level_width(i as u8 + 1)
        );
        let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" font-size="11">{label}</text>"#, lx + 24.0, y + 4.0);
    }
    s.push_str("</svg>\n");
    s
}

/// Bins of width `width` from 0 holding `v` (counts).
fn histogram(v: &[f64], width: f64, bins: usize) -> Vec<usize> {
    let mut c = vec![0; bins];
    for &x in v {
        let i = ((x / width).floor().max(0.0) as usize).min(bins - 1);
        c[i] += 1;
    }
    c
}

/// Travel times of the vehicles that arrived, through and local traffic stacked, with the mean
/// and the 95th percentile marked.
pub fn histogram_svg(r: &TrafficNumbers) -> String {
    let empty = Vec::new();
    let through = r.travel_times.get("through").unwrap_or(&empty);
    let local = r.travel_times.get("local").unwrap_or(&empty);
    let max = through.iter().chain(local).copied().fold(0.0, f64::max);
    let width = nice_ceil((max / 30.0).max(1.0));
    // A multiple of five bins, so the axis ticks fall on bin edges.
    let bins = ((max / width).floor() as usize + 1).div_ceil(5).max(1) * 5;
    let (ht, hl) = (histogram(through, width, bins), histogram(local, width, bins));
    let top = nice_ceil((0..bins).map(|i| ht[i] + hl[i]).max().unwrap_or(0) as f64);
    let (w, h) = (760.0, 420.0);
    let (x0, y0, pw, ph) = (70.0, 60.0, 640.0, 300.0);
    let mut s = String::new();
    svg_open(&mut s, w, h);
    let _ = writeln!(
        s,
        r#"<text x="20" y="24" font-size="15" font-weight="bold">{} — travel times of {} vehicles</text>"#,
        xml(&r.name),
        through.len() + local.len()
    );
    let _ = writeln!(
        s,
        r#"<text x="20" y="44" font-size="12">mean {} s, p95 {} s (through: {} s, local: {} s); bins of {width} s</text>"#,
        fmt_opt(r.travel_time_mean, 1),
        fmt_opt(r.travel_time_p95, 1),
        fmt_opt(r.through_travel_time_mean, 1),
        fmt_opt(r.local_travel_time_mean, 1)
    );
    let bx = |t: f64| x0 + t / (bins as f64 * width) * pw;
    let by = |c: f64| y0 + ph - c / top * ph;
    for i in 0..bins {
        let x = bx(i as f64 * width);
        let bw = pw / bins as f64 - 1.0;
        let (a, b) = (ht[i] as f64, hl[i] as f64);
        if a > 0.0 {
            let _ = writeln!(
                s,
                r##"<rect x="{x:.2}" y="{:.2}" width="{bw:.2}" height="{:.2}" fill="#d62728"/>"##,
                by(a),
                y0 + ph - by(a)
            );
        }
        if b > 0.0 {
            let _ = writeln!(
                s,
                r##"<rect x="{x:.2}" y="{:.2}" width="{bw:.2}" height="{:.2}" fill="#1f77b4"/>"##,
                by(a + b),
                by(a) - by(a + b)
            );
        }
    }
    axes(&mut s, x0, y0, pw, ph, bins as f64 * width, top, "travel time (s)", "vehicles");
    for (label, v, dash) in [("mean", r.travel_time_mean, "5 3"), ("p95", r.travel_time_p95, "2 2")] {
        if let Some(v) = v {
            let x = bx(v);
            let _ = writeln!(
                s,
                r##"<line x1="{x:.2}" y1="{y0}" x2="{x:.2}" y2="{:.2}" stroke="#222" stroke-dasharray="{dash}"/>"##,
                y0 + ph
            );
            let _ = writeln!(s, r#"<text x="{:.2}" y="{:.2}" font-size="11">{label}</text>"#, x + 3.0, y0 + 12.0);
        }
    }
    for (i, (c, label)) in [("#d62728", "through"), ("#1f77b4", "local")].iter().enumerate() {
        let y = y0 + 10.0 + i as f64 * 18.0;
        let _ = writeln!(s, r#"<rect x="{:.1}" y="{:.1}" width="12" height="12" fill="{c}"/>"#, x0 + pw - 90.0, y);
        let _ = writeln!(s, r#"<text x="{:.1}" y="{:.1}" font-size="11">{label}</text>"#, x0 + pw - 72.0, y + 10.0);
    }
    s.push_str("</svg>\n");
    s
}

/// Axes with five ticks each.
#[allow(clippy::too_many_arguments)]
fn axes(s: &mut String, x0: f64, y0: f64, pw: f64, ph: f64, xmax: f64, ymax: f64, xlabel: &str, ylabel: &str) {
    let _ = writeln!(
        s,
        r##"<path d="M{x0},{y0} L{x0},{:.1} L{:.1},{:.1}" fill="none" stroke="#333"/>"##,
        y0 + ph,
        x0 + pw,
        y0 + ph
    );
    for k in 0..=5 {
        let f = k as f64 / 5.0;
        let (x, y) = (x0 + f * pw, y0 + ph - f * ph);
        let _ = writeln!(
            s,
            r##"<line x1="{x:.1}" y1="{:.1}" x2="{x:.1}" y2="{:.1}" stroke="#333"/>"##,
            y0 + ph,
            y0 + ph + 4.0
        );
        let _ = writeln!(
            s,
            r#"<text x="{x:.1}" y="{:.1}" font-size="10" text-anchor="middle">{}</text>"#,
            y0 + ph + 16.0,
            tick(f * xmax)
        );
        let _ = writeln!(s, r##"<line x1="{:.1}" y1="{y:.1}" x2="{x0}" y2="{y:.1}" stroke="#333"/>"##, x0 - 4.0);
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" font-size="10" text-anchor="end">{}</text>"#,
            x0 - 6.0,
            y + 3.0,
            tick(f * ymax)
        );
    }
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" font-size="11" text-anchor="middle">{xlabel}</text>"#,
        x0 + pw / 2.0,
        y0 + ph + 32.0
    );
    let _ = writeln!(
        s,
        r#"<text x="{:.1}" y="{:.1}" font-size="11" text-anchor="middle" transform="rotate(-90 {:.1} {:.1})">{ylabel}</text>"#,
        x0 - 44.0,
        y0 + ph / 2.0,
        x0 - 44.0,
        y0 + ph / 2.0
    );
}

fn tick(v: f64) -> String {
    if v == v.round() {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

/// Several designs under one demand: the travel-time distribution of each (cumulative share of
/// vehicles) next to bars of mean and 95th-percentile travel time, mean waiting time and the
/// share of through traffic's distance on local streets.
pub fn comparison_svg(rows: &[(String, &TrafficNumbers)]) -> String {
    let (w, h) = (1220.0, 520.0);
    let mut s = String::new();
    svg_open(&mut s, w, h);
    let title = rows.iter().map(|(l, _)| l.as_str()).collect::<Vec<_>>().join(" vs ");
    let _ = writeln!(s, r#"<text x="20" y="24" font-size="15" font-weight="bold">{}</text>"#, xml(&title));
    if let Some((_, r)) = rows.first() {
        let _ = writeln!(
            s,
            r#"<text x="20" y="44" font-size="12">same demand: {:.0} s of departures, {:.0} through + {:.0} local trips/h, seed {}; SUMO {}</text>"#,
            r.duration,
            r.through_per_hour,
            r.local_per_hour,
            r.seed,
            xml(&r.sumo_version)
        );
    }
    // Left: cumulative distributions.
    let (x0, y0, pw, ph) = (70.0, 80.0, 420.0, 360.0);
    let tmax = nice_ceil(rows.iter().flat_map(|(_, r)| r.travel_times.values().flatten()).copied().fold(0.0, f64::max));
    let _ = writeln!(
        s,
        r#"<text x="{x0}" y="{:.1}" font-size="12" font-weight="bold">share of vehicles arrived within a travel time</text>"#,
        y0 - 10.0
    );
    for (i, (label, r)) in rows.iter().enumerate() {
        let mut v: Vec<f64> = r.travel_times.values().flatten().copied().collect();
        v.sort_by(f64::total_cmp);
        let n = v.len().max(1) as f64;
        let mut d = format!("M{x0:.2},{:.2}", y0 + ph);
        for (k, t) in v.iter().enumerate() {
            let x = x0 + t / tmax * pw;
            let _ = write!(
                d,
                " L{x:.2},{:.2} L{x:.2},{:.2}",
                y0 + ph - k as f64 / n * ph,
                y0 + ph - (k + 1) as f64 / n * ph
            );
        }
        let c = PALETTE[i % PALETTE.len()];
        let _ = writeln!(s, r#"<path d="{d}" fill="none" stroke="{c}" stroke-width="2"/>"#);
        let ly = y0 + ph - 20.0 - (rows.len() - 1 - i) as f64 * 18.0;
        let _ =
            writeln!(s, r#"<rect x="{:.1}" y="{:.1}" width="12" height="12" fill="{c}"/>"#, x0 + pw - 150.0, ly - 10.0);
        let _ = writeln!(s, r#"<text x="{:.1}" y="{ly:.1}" font-size="11">{}</text>"#, x0 + pw - 134.0, xml(label));
    }
    axes(&mut s, x0, y0, pw, ph, tmax, 100.0, "travel time (s)", "% of vehicles");
    // Right: bar panels.
    type Metric = fn(&TrafficNumbers) -> Option<f64>;
    let panels: [(&str, Metric); 4] = [
        ("mean travel time (s)", |r| r.travel_time_mean),
        ("p95 travel time (s)", |r| r.travel_time_p95),
        ("mean waiting time (s)", |r| r.waiting_time_mean),
        ("through traffic inside the region (% of its km)", |r| {
            let k = &r.through_km_by_level;
            let total: f64 = k.iter().sum();
            (total > 0.0).then(|| 100.0 * (total - k[0]) / total)
        }),
    ];
    let (px0, py0, pw2, ph2) = (580.0, 80.0, 260.0, 150.0);
    for (k, (title, f)) in panels.iter().enumerate() {
        let (x, y) = (px0 + (k % 2) as f64 * (pw2 + 60.0), py0 + (k / 2) as f64 * (ph2 + 80.0));
        let _ = writeln!(
            s,
            r#"<text x="{x:.1}" y="{:.1}" font-size="11" font-weight="bold">{}</text>"#,
            y - 10.0,
            xml(title)
        );
        let vals: Vec<Option<f64>> = rows.iter().map(|(_, r)| f(r)).collect();
        let top = nice_ceil(vals.iter().flatten().copied().fold(0.0, f64::max));
        let bw = pw2 / rows.len().max(1) as f64;
        for (i, v) in vals.iter().enumerate() {
            let bx = x + i as f64 * bw + 0.15 * bw;
            match v {
                Some(v) => {
                    let bh = v / top * ph2;
                    let _ = writeln!(
                        s,
                        r#"<rect x="{bx:.1}" y="{:.1}" width="{:.1}" height="{bh:.1}" fill="{}"/>"#,
                        y + ph2 - bh,
                        0.7 * bw,
                        PALETTE[i % PALETTE.len()]
                    );
                    let _ = writeln!(
                        s,
                        r#"<text x="{:.1}" y="{:.1}" font-size="10" text-anchor="middle">{v:.1}</text>"#,
                        bx + 0.35 * bw,
                        y + ph2 - bh - 3.0
                    );
                }
                None => {
                    let _ = writeln!(
                        s,
                        r#"<text x="{:.1}" y="{:.1}" font-size="10" text-anchor="middle">n/a</text>"#,
                        bx + 0.35 * bw,
                        y + ph2 - 3.0
                    );
                }
            }
        }
        let _ = writeln!(
            s,
            r##"<path d="M{x:.1},{y:.1} L{x:.1},{:.1} L{:.1},{:.1}" fill="none" stroke="#333"/>"##,
            y + ph2,
            x + pw2,
            y + ph2
        );
        let _ = writeln!(
            s,
            r#"<text x="{:.1}" y="{:.1}" font-size="10" text-anchor="end">{}</text>"#,
            x - 4.0,
            y + 8.0,
            tick(top)
        );
    }
    s.push_str("</svg>\n");
    s
}
