//! `netspec layout REGION` and `netspec field REGION`: urban layouts by domain splitting.

use anyhow::Result;
use indicatif::{ProgressBar, ProgressStyle};
use netspec::layout::field::FieldMethod;
use netspec::layout::run::{self, LayoutRequest};
use std::path::Path;
use std::process::ExitCode;

/// Exit code when a layout breaks a rule of the independent check.
const EXIT_INVALID: u8 = 3;

/// Runs the library entry point, with a bar of the area settled, and prints one line per layout.
pub fn run(req: &LayoutRequest) -> Result<ExitCode> {
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
pub fn field(region: &Path, method: FieldMethod, h: Option<f64>, out: &Path) -> Result<ExitCode> {
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
