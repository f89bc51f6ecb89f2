//! A comparison's reports: the Markdown table, CSV, the performance profile and the bar chart
//! ([`write_report`]).

use super::makespan;
use super::manifest::{paper_seconds, Manifest};
use super::record::RunRecord;
use super::summary::{solved, summarize, BackendSummary};
use crate::render::{
    self,
    chart::{Bar, BarChart, BarGroup, ProfileSeries},
};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Why a report could not be written.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// The output folder could not be made.
    #[error("creating {}: {error}", path.display())]
    Create {
        /// The folder.
        path: PathBuf,
        /// What failed.
        error: std::io::Error,
    },
    /// A report file could not be written.
    #[error("writing {}: {error}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What failed.
        error: std::io::Error,
    },
}

fn opt(v: Option<f64>, digits: usize) -> String {
    v.map_or("-".into(), |v| format!("{v:.digits$}"))
}

/// The results table as Markdown: one row per manifest row (missing ones with their reason),
/// the paper's edges, variables and time beside ours, per backend time / status / gap.
pub fn markdown(manifest: &Manifest, records: &[RunRecord], solvers: &[String], summary: &[BackendSummary]) -> String {
    let mut s = String::from("| instance | edges (paper) | vars (paper) | paper time |");
    for b in solvers {
        let _ = write!(s, " {b} |");
    }
    s.push_str(" best objective |\n|---|---|---|---|");
    for _ in solvers {
        s.push_str("---|");
    }
    s.push_str("---|\n");
    let num = |v: Option<usize>| v.map_or("-".to_string(), |e| e.to_string());
    for row in &manifest.row {
        let i = row.name.as_str();
        let p = &row.paper;
        let rows: Vec<&RunRecord> = records.iter().filter(|r| r.instance == i).collect();
        let paper_time = p.time.clone().unwrap_or_else(|| "-".into());
        if let Some(why) = &row.missing {
            let _ = write!(s, "| {i} | - ({}) | - ({}) | {paper_time} |", num(p.edges), num(p.variables));
            for _ in solvers {
                s.push_str(" missing |");
            }
            let _ = writeln!(s, " missing: {why} |");
            continue;
        }
        let (edges, vars) = rows.first().map_or((None, None), |r| (r.edges, r.vars));
        let _ = write!(
            s,
            "| {i} | {} ({}) | {} ({}) | {paper_time} |",
            num(edges),
            num(p.edges),
            num(vars),
            num(p.variables)
        );
        for b in solvers {
            match rows.iter().find(|r| &r.solver == b) {
                Some(r) => {
                    let _ = write!(
                        s,
                        " {:.2} s {}{} gap {} |",
                        r.wall_time,
                        r.status,
                        if r.valid { "" } else { " (invalid)" },
                        opt(r.gap.map(|g| g * 100.0), 1)
                    );
                }
                None => s.push_str(" - |"),
            }
        }
        let best = rows.iter().filter(|r| r.valid).filter_map(|r| r.objective).fold(f64::INFINITY, f64::min);
        let _ = writeln!(s, " {} |", if best.is_finite() { format!("{best:.4}") } else { "-".into() });
    }
    s.push_str("\n| backend | sgm time (shift 10 s) | solved | wins |\n|---|---|---|---|\n");
    for b in summary {
        let _ = writeln!(s, "| {} | {:.2} s | {}/{} | {} |", b.solver, b.sgm_time, b.solved, b.runs, b.wins);
    }
    let failed: Vec<&RunRecord> = records.iter().filter(|r| r.error.is_some()).collect();
    if !failed.is_empty() {
        s.push_str("\nRuns that failed (no result):\n\n");
        for r in failed {
            let _ = writeln!(s, "- {} / {}: {}", r.instance, r.solver, r.error.as_deref().unwrap_or_default());
        }
    }
    s.push_str(
        "\nFigures: `profile.svg`, the performance profile (fraction solved within time, per backend); \
         `bars.svg`, solver time per instance and backend (log scale; hatched: not solved, with the \
         status and gap; the dashed line is the time limit, the diamond the paper's Gurobi time).\n",
    );
    s
}

/// The records as CSV.
pub fn csv(records: &[RunRecord]) -> String {
    let mut s = String::from("instance,solver,seed,edges,vars,rows,nonzeros,status,objective,dual_bound,gap,nodes,solver_time,wall_time,valid,killed,error\n");
    for r in records {
        let o = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
        let u = |v: Option<usize>| v.map_or(String::new(), |v| v.to_string());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.instance,
            r.solver,
            r.seed.map_or(String::new(), |v| v.to_string()),
            u(r.edges),
            u(r.vars),
            u(r.rows),
            u(r.nonzeros),
            r.status,
            o(r.objective),
            o(r.dual_bound),
            o(r.gap),
            r.nodes.map_or(String::new(), |v| v.to_string()),
            o(r.solver_time),
            r.wall_time,
            r.valid,
            r.killed,
            csv_field(r.error.as_deref().unwrap_or_default())
        );
    }
    s
}

/// A CSV field: quoted (quotes doubled) when it holds a comma, quote or line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// A performance profile as SVG ([`render::chart::performance_profile_svg`]): for each backend,
/// the fraction of runs solved (optimal and valid, or infeasible) within time t, for t from 0 to
/// the limit (log scale from 0.01 s).
pub fn performance_profile_svg(records: &[RunRecord], solvers: &[String], limit: f64) -> String {
    let series: Vec<ProfileSeries> = solvers
        .iter()
        .map(|b| {
            let mine: Vec<&RunRecord> = records.iter().filter(|r| &r.solver == b).collect();
            ProfileSeries {
                name: b.clone(),
                solved_times: mine.iter().filter(|r| solved(r)).map(|r| r.wall_time).collect(),
                runs: mine.len(),
            }
        })
        .collect();
    render::chart::performance_profile_svg(&series, limit)
}

/// The time a bar shows for one run: the solver's own time, or the child's wall time when the
/// run reports none (killed, failed).
fn bar_time(r: &RunRecord) -> f64 {
    r.solver_time.unwrap_or(r.wall_time)
}

/// A short label for a run that is not solved (or is solved without an optimum): `killed`,
/// `failed`, `invalid`, `infeasible`, or the status with the gap (`limit(time) 12.5%`).
fn run_label(r: &RunRecord) -> Option<String> {
    if r.killed {
        return Some("killed".into());
    }
    if r.status == "optimal" {
        return (!r.valid).then(|| "invalid".into());
    }
    Some(match r.gap {
        Some(g) if r.status != "failed" => format!("{} {:.1}%", r.status, g * 100.0),
        _ => r.status.clone(),
    })
}

/// A grouped bar chart as SVG: one group per manifest row that has a spec (`<g class="instance"
/// data-instance=…>`), one bar per backend in each (`<rect class="bar" data-instance=…
/// data-solver=… data-status=…>`), coloured as in [`performance_profile_svg`]. A bar's height is
/// the solver's own time on a log scale (the child's wall time for runs that report none); with
/// several seeds, the lower median, with a whisker from the fastest to the slowest seed. Runs not
/// solved (see [`summarize`]) are hatched and labelled with their status and gap; killed runs
/// also get a red cross, failed ones a dashed outline. The time limit is a dashed line; the
/// paper's Gurobi time, where the manifest gives one number, a diamond. Rows without a spec are
/// listed under the chart. The output depends only on the arguments.
pub fn bar_chart_svg(manifest: &Manifest, records: &[RunRecord], solvers: &[String], limit: f64) -> String {
    let groups = manifest
        .row
        .iter()
        .filter(|r| r.spec.is_some())
        .map(|row| BarGroup {
            name: row.name.clone(),
            bars: solvers
                .iter()
                .map(|b| {
                    let runs: Vec<&RunRecord> =
                        records.iter().filter(|r| r.instance == row.name && &r.solver == b).collect();
                    if runs.is_empty() {
                        return None;
                    }
                    // The run that explains the bar: the first not solved, else the first.
                    let shown = runs.iter().find(|r| !solved(r)).unwrap_or(&runs[0]);
                    let unsolved = runs.iter().filter(|r| !solved(r)).count();
                    Some(Bar {
                        times: runs.iter().map(|r| bar_time(r)).collect(),
                        solved: unsolved == 0,
                        status: if shown.killed { "killed".into() } else { shown.status.clone() },
                        killed: shown.killed,
                        failed: shown.status == "failed" && !shown.killed,
                        label: run_label(shown).map(|l| {
                            if runs.len() > 1 && unsolved > 0 {
                                format!("{unsolved}/{} {l}", runs.len())
                            } else {
                                l
                            }
                        }),
                    })
                })
                .collect(),
            reference: paper_seconds(&row.paper),
        })
        .collect();
    render::chart::bar_chart_svg(&BarChart {
        series: solvers.to_vec(),
        groups,
        limit,
        reference_label: "paper (Gurobi 2014)".into(),
        not_shown: manifest.row.iter().filter(|r| r.spec.is_none()).map(|r| r.name.clone()).collect(),
    })
}

/// What a comparison's report is made of ([`write_report`]).
pub struct Report<'a> {
    /// The rows.
    pub manifest: &'a Manifest,
    /// Every run's record.
    pub records: &'a [RunRecord],
    /// The columns (a backend, or a backend and a formulation).
    pub columns: &'a [String],
    /// The time limit (the longest, when rows had their own).
    pub time_limit: f64,
    /// The runs, for the header (`time limit 60 s, grace 10 s`).
    pub what: &'a str,
    /// The command line that made them.
    pub command: &'a [String],
    /// Stored in `results.json`.
    pub settings: serde_json::Value,
    /// Makespan estimates to add (`--makespan`), if any.
    pub makespan: &'a [makespan::Estimate],
}

/// Writes a comparison's reports to `out` (`results.md`, `.csv`, `.json`, `profile.svg`,
/// `bars.svg`) and returns the Markdown table.
pub fn write_report(out: &Path, r: Report) -> Result<String, ReportError> {
    let Report { manifest, records, columns, time_limit, what, command, settings, makespan } = r;
    std::fs::create_dir_all(out).map_err(|error| ReportError::Create { path: out.into(), error })?;
    let summary = summarize(records, columns, time_limit);
    let md = markdown(manifest, records, columns, &summary) + &makespan::markdown(makespan);
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let header = format!(
        "netspec {} compare, {what}; {cpu}, {} cores\n\nCommand: `{}`\n\n",
        env!("CARGO_PKG_VERSION"),
        std::thread::available_parallelism().map_or(0, |n| n.get()),
        command.join(" ")
    );
    let write = |name: &str, text: String| {
        std::fs::write(out.join(name), text).map_err(|error| ReportError::Write { path: out.join(name), error })
    };
    write("results.md", header + &md)?;
    write("results.csv", csv(records))?;
    write("profile.svg", performance_profile_svg(records, columns, time_limit))?;
    write("bars.svg", bar_chart_svg(manifest, records, columns, time_limit))?;
    let mut all = serde_json::json!({
        "netspec_version": env!("CARGO_PKG_VERSION"),
        "command": command,
        "cpu": cpu,
        "settings": settings,
        "records": records,
        "summary": summary,
    });
    if !makespan.is_empty() {
        all["makespan"] = serde_json::to_value(makespan).expect("estimates serialise");
    }
    write("results.json", serde_json::to_string_pretty(&all).expect("records serialise") + "\n")?;
    Ok(md)
}
