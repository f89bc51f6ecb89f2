//! Charts of a comparison: a performance profile (fraction of runs solved within time, per
//! series) and a grouped bar chart of times on a log scale. The inputs are plain numbers and
//! labels (`compare` turns its run records into them); the output depends only on the input.

use super::writer::{escape, Svg};
use std::fmt::Write;

/// The colour of the `i`-th series (backend) in every chart.
pub fn series_color(i: usize) -> &'static str {
    const COLORS: [&str; 6] = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"];
    COLORS[i % COLORS.len()]
}

/// One series of a performance profile.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileSeries {
    /// Its name (a backend).
    pub name: String,
    /// Times of the runs it solved, seconds.
    pub solved_times: Vec<f64>,
    /// Runs in all (solved or not).
    pub runs: usize,
}

/// A performance profile as SVG: for each series (in order, coloured by [`series_color`]), the
/// fraction of its runs solved within time t, for t from 0.01 s to `limit` on a log scale
/// (`<polyline class="profile" data-solver=…>`). Series without runs are left out.
pub fn performance_profile_svg(series: &[ProfileSeries], limit: f64) -> String {
    let (w, h, left, bottom, top, right) = (640.0, 400.0, 60.0, 50.0, 30.0, 130.0);
    let (pw, ph) = (w - left - right, h - top - bottom);
    let t0 = 0.01f64;
    let limit = limit.max(t0 * 10.0);
    let x = |t: f64| left + pw * ((t.max(t0) / t0).ln() / (limit / t0).ln()).clamp(0.0, 1.0);
    let y = |f: f64| top + ph * (1.0 - f);
    let mut s = Svg::new(w, h, Some(11.0));
    s.text(left, 18.0, r#"font-size="13" font-weight="bold""#, "Performance profile: fraction solved within time");
    let _ = writeln!(s, r##"<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#888"/>"##);
    let mut tick = t0;
    while tick <= limit * 1.0001 {
        let _ = writeln!(
            s,
            r##"<line x1="{0:.1}" y1="{top}" x2="{0:.1}" y2="{1:.1}" stroke="#eee"/><text x="{0:.1}" y="{2:.1}" text-anchor="middle">{3}</text>"##,
            x(tick),
            top + ph,
            top + ph + 16.0,
            tick
        );
        tick *= 10.0;
    }
    for k in 0..=4 {
        let f = k as f64 / 4.0;
        let _ = writeln!(
            s,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="end">{:.0}%</text>"##,
            left - 6.0,
            y(f) + 4.0,
            f * 100.0
        );
    }
    s.text(left + pw / 2.0, h - 10.0, r#"text-anchor="middle""#, &format!("time (s, log scale; limit {limit} s)"));
    for (i, b) in series.iter().enumerate() {
        if b.runs == 0 {
            continue;
        }
        let mut times = b.solved_times.clone();
        times.sort_by(f64::total_cmp);
        let n = b.runs as f64;
        let mut pts = vec![format!("{:.1},{:.1}", x(t0), y(0.0))];
        for (k, t) in times.iter().enumerate() {
            pts.push(format!("{:.1},{:.1}", x(*t), y(k as f64 / n)));
            pts.push(format!("{:.1},{:.1}", x(*t), y((k + 1) as f64 / n)));
        }
        pts.push(format!("{:.1},{:.1}", x(limit), y(times.len() as f64 / n)));
        let c = series_color(i);
        let name = escape(&b.name);
        let _ = writeln!(
            s,
            r#"<polyline class="profile" data-solver="{name}" points="{}" fill="none" stroke="{c}" stroke-width="2"/>"#,
            pts.join(" ")
        );
        let ly = top + 14.0 + i as f64 * 18.0;
        let _ = writeln!(
            s,
            r#"<line x1="{:.1}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="{c}" stroke-width="3"/><text x="{:.1}" y="{:.1}">{name}</text>"#,
            w - right + 10.0,
            w - right + 30.0,
            w - right + 36.0,
            ly + 4.0
        );
    }
    s.finish()
}

/// One bar: the runs of one series on one group (several seeds give several times).
#[derive(Clone, Debug, PartialEq)]
pub struct Bar {
    /// The runs' times, seconds (at least one).
    pub times: Vec<f64>,
    /// Every run solved.
    pub solved: bool,
    /// The status of the run that explains the bar (`data-status`).
    pub status: String,
    /// That run was killed (a red cross).
    pub killed: bool,
    /// That run failed (a dashed outline instead of a fill).
    pub failed: bool,
    /// A label written up the bar (status and gap of an unsolved run), if any.
    pub label: Option<String>,
}

/// One group of bars (an instance).
#[derive(Clone, Debug, PartialEq)]
pub struct BarGroup {
    /// Its name.
    pub name: String,
    /// One bar per series, in series order (`None`: no run).
    pub bars: Vec<Option<Bar>>,
    /// A reference time drawn as a diamond (the paper's), seconds.
    pub reference: Option<f64>,
}

/// A grouped bar chart.
#[derive(Clone, Debug, PartialEq)]
pub struct BarChart {
    /// Series names (backends), in order.
    pub series: Vec<String>,
    /// The groups, in order.
    pub groups: Vec<BarGroup>,
    /// The time limit (a dashed line), seconds.
    pub limit: f64,
    /// The legend's name for the reference diamonds.
    pub reference_label: String,
    /// Groups that could not be drawn, listed under the chart.
    pub not_shown: Vec<String>,
}

/// `10^k` as text without round-off (`0.001`, `1`, `1000`).
fn pow10_label(k: i32) -> String {
    if k >= 0 {
        format!("1{}", "0".repeat(k as usize))
    } else {
        format!("0.{}1", "0".repeat((-k - 1) as usize))
    }
}

/// A grouped bar chart as SVG: one group per [`BarGroup`] (`<g class="instance"
/// data-instance=…>`), one bar per series in each (`<rect class="bar" data-instance=…
/// data-solver=… data-status=…>`), coloured by [`series_color`]. A bar's height is the lower
/// median of its times on a log scale, with a whisker from the fastest to the slowest when there
/// are several. Unsolved bars are hatched and labelled; killed ones get a red cross, failed ones a
/// dashed outline. The limit is a dashed line; reference times are diamonds. The legend lists
/// the series and only the marks the chart uses; groups not shown are listed under the chart.
pub fn bar_chart_svg(c: &BarChart) -> String {
    let limit = if c.limit.is_finite() && c.limit > 0.0 { c.limit } else { 1.0 };
    // The axis: whole decades around every time shown (bars, limit, references).
    let shown = c
        .groups
        .iter()
        .flat_map(|g| g.bars.iter().flatten().flat_map(|b| b.times.iter().copied()).chain(g.reference))
        .chain(std::iter::once(limit));
    let (tmin, tmax) =
        shown.fold((f64::INFINITY, 0.0f64), |(lo, hi), t| (if t > 0.0 { lo.min(t) } else { lo }, hi.max(t)));
    let lo_exp = tmin.max(1e-3).log10().floor() as i32;
    let hi_exp = (tmax.log10().ceil() as i32).max(lo_exp + 1);
    let (lo, hi) = (10f64.powi(lo_exp), 10f64.powi(hi_exp));

    let ns = c.series.len().max(1) as f64;
    let bar_w = 12.0;
    let group_w = ns * bar_w + 14.0;
    let (left, right, top, bottom, ph) = (60.0, 190.0, 40.0, 90.0, 300.0);
    let pw = (c.groups.len() as f64 * group_w).max(200.0);
    let (w, h) = (left + pw + right, top + ph + bottom);
    let y = |t: f64| top + ph * (1.0 - (t.clamp(lo, hi).log10() - lo_exp as f64) / (hi_exp - lo_exp) as f64);
    let base = top + ph;

    let mut defs = String::new();
    for i in 0..c.series.len() {
        let col = series_color(i);
        let _ = writeln!(
            defs,
            r#"<pattern id="hatch-{i}" width="6" height="6" patternUnits="userSpaceOnUse" patternTransform="rotate(45)"><rect width="6" height="6" fill="{col}" fill-opacity="0.2"/><line x1="1.5" y1="0" x2="1.5" y2="6" stroke="{col}" stroke-width="2"/></pattern>"#
        );
    }
    let mut s = Svg::with_defs(w, h, Some(11.0), &defs);
    s.text(left, 20.0, r#"font-size="13" font-weight="bold""#, "Solver time per instance and backend");
    let _ = writeln!(s, r##"<rect x="{left}" y="{top}" width="{pw:.1}" height="{ph}" fill="none" stroke="#888"/>"##);
    for k in lo_exp..=hi_exp {
        let ty = y(10f64.powi(k));
        let _ = writeln!(
            s,
            r##"<line x1="{left}" y1="{ty:.1}" x2="{:.1}" y2="{ty:.1}" stroke="#eee"/><text x="{:.1}" y="{:.1}" text-anchor="end">{}</text>"##,
            left + pw,
            left - 6.0,
            ty + 4.0,
            pow10_label(k)
        );
    }
    let _ = writeln!(
        s,
        r##"<text transform="translate(16 {:.1}) rotate(-90)" text-anchor="middle">solver time (s, log scale)</text>"##,
        top + ph / 2.0
    );

    let (mut any_unsolved, mut any_failed, mut any_killed) = (false, false, false);
    for (g, group) in c.groups.iter().enumerate() {
        let name = escape(&group.name);
        let gx = left + g as f64 * group_w + 7.0;
        let _ = writeln!(s, r#"<g class="instance" data-instance="{name}">"#);
        for (i, bar) in group.bars.iter().enumerate() {
            let Some(bar) = bar else { continue };
            let series = escape(&c.series[i]);
            let col = series_color(i);
            let x0 = gx + i as f64 * bar_w;
            let mut times = bar.times.clone();
            times.sort_by(f64::total_cmp);
            let t = times[(times.len() - 1) / 2];
            let top_y = y(t).min(base - 1.0);
            let fill = if bar.solved {
                format!(r#"fill="{col}""#)
            } else if bar.failed {
                any_failed = true;
                format!(r#"fill="none" stroke="{col}" stroke-dasharray="3 2""#)
            } else {
                any_unsolved = true;
                format!(r#"fill="url(#hatch-{i})" stroke="{col}" stroke-width="0.8""#)
            };
            let status = escape(&bar.status);
            let _ = writeln!(
                s,
                r#"<rect class="bar" data-instance="{name}" data-solver="{series}" data-status="{status}" data-solved="{}" data-time="{t}" x="{:.1}" y="{top_y:.1}" width="{:.1}" height="{:.1}" {fill}><title>{name} / {series}: {status} in {t:.3} s</title></rect>"#,
                bar.solved,
                x0 + 1.0,
                bar_w - 2.0,
                base - top_y,
            );
            if times.len() > 1 {
                let cx = x0 + bar_w / 2.0;
                let _ = writeln!(
                    s,
                    r##"<line class="whisker" x1="{cx:.1}" y1="{:.1}" x2="{cx:.1}" y2="{:.1}" stroke="#333"/>"##,
                    y(times[0]),
                    y(times[times.len() - 1])
                );
            }
            if bar.killed {
                any_killed = true;
                let (cx, cy) = (x0 + bar_w / 2.0, top_y - 5.0);
                let _ = writeln!(
                    s,
                    r##"<path class="killed" d="M{:.1} {:.1}L{:.1} {:.1}M{:.1} {:.1}L{:.1} {:.1}" stroke="#c00" stroke-width="2"/>"##,
                    cx - 3.5,
                    cy - 3.5,
                    cx + 3.5,
                    cy + 3.5,
                    cx - 3.5,
                    cy + 3.5,
                    cx + 3.5,
                    cy - 3.5
                );
            }
            if let Some(l) = &bar.label {
                let _ = writeln!(
                    s,
                    r#"<text class="label" transform="translate({:.1} {:.1}) rotate(-90)" font-size="9" paint-order="stroke" stroke="white" stroke-width="2.5">{}</text>"#,
                    x0 + bar_w / 2.0 + 3.0,
                    base - 4.0,
                    escape(l)
                );
            }
        }
        if let Some(p) = group.reference {
            let (cx, cy, hw) = (gx + ns * bar_w / 2.0, y(p), ns * bar_w / 2.0);
            let _ = writeln!(
                s,
                r##"<g class="paper" data-instance="{name}" data-time="{p}"><line x1="{:.1}" y1="{cy:.1}" x2="{:.1}" y2="{cy:.1}" stroke="#000" stroke-width="1"/><path d="M{cx:.1} {:.1}L{:.1} {cy:.1}L{cx:.1} {:.1}L{:.1} {cy:.1}Z" fill="#000"/></g>"##,
                cx - hw,
                cx + hw,
                cy - 4.5,
                cx + 4.5,
                cy + 4.5,
                cx - 4.5
            );
        }
        let _ = writeln!(
            s,
            r#"<text transform="translate({:.1} {:.1}) rotate(-40)" text-anchor="end">{name}</text>"#,
            gx + ns * bar_w / 2.0 + 3.0,
            base + 14.0
        );
        s.write_str("</g>\n").expect("writing to a string");
    }

    let ly = y(limit);
    let _ = writeln!(
        s,
        r##"<line class="limit" x1="{left}" y1="{ly:.1}" x2="{:.1}" y2="{ly:.1}" stroke="#000" stroke-dasharray="6 4"/><text x="{:.1}" y="{:.1}" text-anchor="end" paint-order="stroke" stroke="white" stroke-width="3">limit {limit} s</text>"##,
        left + pw,
        left + pw - 4.0,
        ly - 4.0
    );

    // Legend: the series, then only the marks used.
    let lx = left + pw + 14.0;
    let mut row_y = top + 24.0;
    for (i, b) in c.series.iter().enumerate() {
        let _ = writeln!(
            s,
            r#"<rect x="{lx:.1}" y="{:.1}" width="12" height="10" fill="{}"/>"#,
            row_y - 9.0,
            series_color(i)
        );
        s.text(lx + 18.0, row_y, "", b);
        row_y += 16.0;
    }
    row_y += 6.0;
    let any_reference = c.groups.iter().any(|g| g.reference.is_some());
    let legend = [
        (
            any_unsolved,
            r##"<rect x="{X}" y="{Y}" width="12" height="10" fill="url(#hatch-0)" stroke="#1f77b4" stroke-width="0.8"/>"##,
            "not solved (status, gap)".to_string(),
        ),
        (
            any_failed,
            r##"<rect x="{X}" y="{Y}" width="12" height="10" fill="none" stroke="#1f77b4" stroke-dasharray="3 2"/>"##,
            "failed".to_string(),
        ),
        (
            any_killed,
            r##"<path d="M{X} {Y}l10 10m-10 0l10 -10" stroke="#c00" stroke-width="2"/>"##,
            "killed at limit + grace".to_string(),
        ),
        (
            true,
            r##"<line x1="{X}" y1="{YM}" x2="{X12}" y2="{YM}" stroke="#000" stroke-dasharray="6 4"/>"##,
            "time limit".to_string(),
        ),
        (any_reference, r##"<path d="M{X6} {Y}l5 5l-5 5l-5 -5z" fill="#000"/>"##, c.reference_label.clone()),
    ];
    for (_, shape, text) in legend.iter().filter(|l| l.0) {
        let shape = shape
            .replace("{X12}", &format!("{:.1}", lx + 12.0))
            .replace("{X6}", &format!("{:.1}", lx + 6.0))
            .replace("{X}", &format!("{lx:.1}"))
            .replace("{YM}", &format!("{:.1}", row_y - 4.0))
            .replace("{Y}", &format!("{:.1}", row_y - 9.0));
        let _ = writeln!(s, "{shape}");
        s.text(lx + 18.0, row_y, "", text);
        row_y += 16.0;
    }
    if !c.not_shown.is_empty() {
        s.text(left, h - 8.0, "", &format!("Not shown (no spec yet): {}", c.not_shown.join(", ")));
    }
    s.finish()
}
