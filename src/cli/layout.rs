//! `netspec layout REGION` and `netspec field REGION`: urban layouts by domain splitting.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use netspec::layout::field::FieldMethod;
use netspec::layout::run::{self, LayoutRequest};
use netspec::layout::split::Selection;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Exit code when a layout breaks a rule of the independent check.
const EXIT_INVALID: u8 = 3;

/// `netspec layout`'s arguments.
#[derive(clap::Args)]
pub struct LayoutArgs {
    /// The region file.
    region: PathBuf,
    /// Seed of every random choice (default: the region's `seed`).
    #[arg(long)]
    seed: Option<u64>,
    /// Layouts to make: the first by --mode, the others drawn by quality with seeds seed+1, ….
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=1000))]
    variations: u64,
    /// The cross field: `smooth` (boundary-aligned and smooth) or `distance` (aligned with the
    /// gradient of the distance to the boundary, the paper's most used).
    #[arg(long, default_value = "distance", value_name = "FIELD")]
    field: FieldMethod,
    /// Streamline choice: `best` (the highest quality, comparison mode) or `random` (drawn with
    /// probability proportional to quality, variation mode).
    #[arg(long, default_value = "best", value_name = "MODE")]
    mode: Selection,
    /// Iterations of the global optimisation of the streets (fairness and strip fitting,
    /// the paper's §6, which runs 10); 0 for none. Off by default: on most example regions
    /// it raises the registration distance and the corner deviation (docs/layout.md).
    #[arg(long, value_name = "N", default_value_t = 0, value_parser = clap::value_parser!(u64).range(0..=100))]
    optimise: u64,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// A layout.json of this region to lay a part of out again (with --relayout).
    #[arg(long, value_name = "LAYOUT.json", requires = "relayout")]
    from: Option<PathBuf>,
    /// The part (an id of the `parts` tree in --from's layout.json) to lay out again, the rest
    /// kept as it is.
    #[arg(long, value_name = "PART", requires = "from", conflicts_with_all = ["optimise", "variations"])]
    relayout: Option<String>,
}

impl From<LayoutArgs> for LayoutRequest {
    fn from(a: LayoutArgs) -> LayoutRequest {
        LayoutRequest {
            region: a.region,
            field: a.field,
            selection: a.mode,
            seed: a.seed,
            variations: a.variations as usize,
            optimise: a.optimise as usize,
            out: a.out,
            relayout: a.from.zip(a.relayout),
            interrupt: None,
        }
    }
}

impl LayoutArgs {
    /// Lays the region out.
    pub fn run(self) -> Result<ExitCode> {
        run(&self.into())
    }
}

/// `netspec field`'s arguments.
#[derive(clap::Args)]
pub struct FieldArgs {
    /// The region file (TOML or GeoJSON).
    region: PathBuf,
    /// The construction: `smooth` or `distance`.
    #[arg(long, default_value = "distance", value_name = "FIELD")]
    method: FieldMethod,
    /// Triangle size in metres (default: a third of the parcel depth).
    #[arg(long)]
    h: Option<f64>,
    /// Output directory.
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
}

impl FieldArgs {
    /// Writes the field.
    pub fn run(self) -> Result<ExitCode> {
        field(&self.region, self.method, self.h, &self.out)
    }
}

/// Runs the library entry point, with a bar of the area settled, and prints one line per layout.
fn run(req: &LayoutRequest) -> Result<ExitCode> {
    let bar = ProgressBar::new(1000);
    bar.set_style(
        ProgressStyle::with_template("{prefix} {bar:30} {percent:>3}% of the area {elapsed}").expect("static template"),
    );
    let n = req.variations.max(1);
    let layouts = run::run(req, &mut |k, f| {
        bar.set_prefix(format!("layout {}/{n}", k + 1));
        bar.set_position((f * 1000.0).round() as u64);
    });
    bar.finish_and_clear();
    let layouts = layouts?;
    let mut valid = true;
    for l in &layouts {
        let m = &l.metrics;
        println!(
            "{} seed {}: {} cuts ({} candidates) · {} blocks, {} of {} parts by template · {} parcels ({} undesirable) · corners {:.2}° · area ratio {:.3} · streets {:.1} % · {:.2} s split, {:.2} s parcels, {:.2} s check · {}",
            l.name,
            l.seed,
            l.split.cuts,
            l.split.candidates,
            l.split.blocks,
            l.split.by_template,
            l.split.leaves,
            m.parcels,
            m.undesirable,
            m.corner_deviation_mean,
            m.area_ratio_mean,
            m.land_use.streets,
            l.times.split,
            l.times.parcels,
            l.times.check,
            if l.violations.is_empty() { "valid".to_string() } else { format!("INVALID: {}", l.violations[0]) }
        );
        valid &= l.violations.is_empty();
    }
    if let Some(dir) = &req.out {
        println!("wrote {}", dir.join("layout.json").display());
    }
    Ok(if valid { ExitCode::SUCCESS } else { ExitCode::from(EXIT_INVALID) })
}

/// `netspec field`: writes the field and prints its singularities.
fn field(region: &Path, method: FieldMethod, h: Option<f64>, out: &Path) -> Result<ExitCode> {
    let f = run::field_command(region, method, h, out)?;
    let sum: f64 = f.singularities().iter().map(|s| s.index).sum();
    println!(
        "{} field · {} vertices · {} singularities (index sum {:+.2}) · wrote {}",
        method.name(),
        f.vertices().len(),
        f.singularities().len(),
        sum,
        out.join("field.json").display()
    );
    Ok(ExitCode::SUCCESS)
}
