//! `netspec traffic DESIGN…`: every design evaluated under the same demand, each into its own
//! directory with its pictures, and a comparison when there are several.

use super::network::LoadOptions;
use super::{picture, report, DemandSettings, Sumo, TrafficError, TrafficReport};
use crate::spec::SettingsError;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// What `netspec traffic` is asked for.
#[derive(Clone, Debug)]
pub struct TrafficRequest {
    /// The designs: `netspec city`, `solve`, `layout` or `grow` output directories, or
    /// `result.json` files.
    pub designs: Vec<PathBuf>,
    /// Their names, in order (the rest default to their directory names, [`labels`]).
    pub labels: Vec<String>,
    /// The demand every design gets.
    pub demand: DemandSettings,
    /// How the designs are read.
    pub load: LoadOptions,
    /// SUMO_HOME to use (default: [`Sumo::locate`]'s search).
    pub sumo_home: Option<PathBuf>,
    /// Output directory: one design's files in it, several designs' in sub-directories named by
    /// their labels, with the comparison.
    pub out: PathBuf,
    /// Time limit of the whole evaluation, seconds (positive; `None`: no limit).
    pub time_limit: Option<f64>,
    /// The command written into `comparison.md`.
    pub command: String,
}

/// One design evaluated.
#[derive(Clone, Debug)]
pub struct Evaluated {
    /// Its label.
    pub label: String,
    /// The directory its files were written to.
    pub dir: PathBuf,
    /// The report (`traffic.json`).
    pub report: TrafficReport,
}

/// What [`run`] tells its observer as it goes.
#[derive(Debug)]
pub enum TrafficEvent<'a> {
    /// SUMO was found.
    Located(&'a Sumo),
    /// A design was evaluated and its files written.
    Evaluated(&'a Evaluated),
    /// The comparison of several designs was written; its Markdown table.
    Compared(&'a str),
}

/// Why `netspec traffic` failed.
#[derive(Debug, thiserror::Error)]
pub enum TrafficRunError {
    /// A setting was refused (named as the command line's flag).
    #[error(transparent)]
    Setting(#[from] SettingsError),
    /// SUMO was not found, or a design could not be read or its report written.
    #[error(transparent)]
    Traffic(Box<TrafficError>),
    /// A design's evaluation failed.
    #[error("evaluating {}", path.display())]
    Evaluate {
        /// The design.
        path: PathBuf,
        /// Why.
        #[source]
        source: Box<TrafficError>,
    },
    /// A directory could not be made.
    #[error("creating {}", path.display())]
    Create {
        /// The directory.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// A file could not be written.
    #[error("writing {}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// A picture could not be rasterised.
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
}

impl From<TrafficError> for TrafficRunError {
    fn from(e: TrafficError) -> TrafficRunError {
        TrafficRunError::Traffic(Box::new(e))
    }
}

/// A label from a design's path: its directory name (`result.json`'s parent's for a file).
fn default_label(p: &Path) -> String {
    let dir = if p.is_file() { p.parent().unwrap_or(p) } else { p };
    dir.file_name().map_or_else(|| "design".to_string(), |n| n.to_string_lossy().into_owned())
}

/// The designs' labels: the given ones in order, the rest their directory names, made distinct
/// (`name-i` for a repeat; they name the output directories).
pub fn labels(designs: &[PathBuf], given: &[String]) -> Vec<String> {
    let mut labels: Vec<String> =
        designs.iter().enumerate().map(|(i, p)| given.get(i).cloned().unwrap_or_else(|| default_label(p))).collect();
    let mut seen = BTreeSet::new();
    for (i, l) in labels.iter_mut().enumerate() {
        if !seen.insert(l.clone()) {
            *l = format!("{l}-{i}");
            seen.insert(l.clone());
        }
    }
    labels
}

/// `comparison.json`: every design's label and report.
pub fn comparison_json(designs: &[Evaluated]) -> serde_json::Value {
    serde_json::json!({ "designs": designs.iter().map(|d| serde_json::json!({ "label": d.label, "report": d.report })).collect::<Vec<_>>() })
}

fn write_file(path: PathBuf, bytes: &[u8]) -> Result<(), TrafficRunError> {
    std::fs::write(&path, bytes).map_err(|source| TrafficRunError::Write { path, source })
}

fn write_picture(dir: &Path, stem: &str, svg: &str) -> Result<(), TrafficRunError> {
    write_file(dir.join(format!("{stem}.svg")), svg.as_bytes())?;
    write_file(dir.join(format!("{stem}.png")), &crate::render::png(svg)?)
}

/// Runs `netspec traffic`: finds SUMO, checks the time limit, then evaluates every design
/// ([`super::evaluate`]) into its directory with `traffic.json`, `volume.svg/png` and
/// `traveltime.svg/png`, and with several designs writes `comparison.md`, `comparison.json` and
/// `comparison.svg/png` into the output directory, telling `observe` as it goes.
pub fn run(req: &TrafficRequest, observe: &mut dyn FnMut(TrafficEvent)) -> Result<Vec<Evaluated>, TrafficRunError> {
    let started = Instant::now();
    let mut sumo = Sumo::locate(req.sumo_home.as_deref())?;
    if let Some(limit) = req.time_limit {
        if !(limit > 0.0 && limit.is_finite()) {
            return Err(SettingsError {
                place: "--time-limit".into(),
                reason: format!("must be a positive number of seconds, got {limit}"),
            }
            .into());
        }
        // The tools stop early enough for the pictures and tables to be written within the limit.
        let tools = limit - crate::run::output_reserve(limit);
        sumo.deadline = Some(started + std::time::Duration::from_secs_f64(tools));
    }
    observe(TrafficEvent::Located(&sumo));
    let labels = labels(&req.designs, &req.labels);
    let mut done: Vec<Evaluated> = Vec::new();
    for (path, label) in req.designs.iter().zip(&labels) {
        let t0 = Instant::now();
        let net = super::network::load(path, &req.load)?;
        let load = t0.elapsed().as_secs_f64();
        // A label names a folder: made one safe path component.
        let dir =
            if req.designs.len() == 1 { req.out.clone() } else { req.out.join(crate::run::safe_component(label)) };
        std::fs::create_dir_all(&dir).map_err(|source| TrafficRunError::Create { path: dir.clone(), source })?;
        let mut rep = super::evaluate(&net, &req.demand, &sumo, &dir)
            .map_err(|e| TrafficRunError::Evaluate { path: path.clone(), source: Box::new(e) })?;
        rep.timings.load = load;
        rep.timings.total += load;
        rep.write(&dir)?;
        write_picture(&dir, "volume", &picture::volume_svg(&net, &rep))?;
        write_picture(&dir, "traveltime", &picture::histogram_svg(&rep))?;
        done.push(Evaluated { label: label.clone(), dir, report: rep });
        observe(TrafficEvent::Evaluated(done.last().expect("just pushed")));
    }
    if done.len() > 1 {
        let rows: Vec<(String, &TrafficReport)> = done.iter().map(|d| (d.label.clone(), &d.report)).collect();
        let md = report::comparison_markdown(&rows);
        write_file(
            req.out.join("comparison.md"),
            format!("# Traffic comparison\n\nCommand: `{}`\n\n![comparison](comparison.png)\n\n{md}", req.command)
                .as_bytes(),
        )?;
        let json = serde_json::to_string_pretty(&comparison_json(&done)).expect("reports serialise") + "\n";
        write_file(req.out.join("comparison.json"), json.as_bytes())?;
        write_picture(&req.out, "comparison", &picture::comparison_svg(&rows))?;
        observe(TrafficEvent::Compared(&md));
    }
    Ok(done)
}
