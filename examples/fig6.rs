//! Yang et al. 2013 Fig. 6 as a ratio: the parcels' registration distance after the full
//! template warp against mean-value coordinates alone, over a region's blocks
//! ([`netspec::layout::template::fig6`], docs/layout.md). Prints one JSON line.
//!
//! `cargo run --release --example fig6 -- [REGION]` (default `models/layout/lake.toml`)

use netspec::layout::region::read_region;
use netspec::layout::template::fig6::fig6;
use std::path::PathBuf;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args().nth(1).map_or_else(|| PathBuf::from("models/layout/lake.toml"), PathBuf::from);
    let region = read_region(&path)?;
    let f = fig6(&region, &region.templates)?;
    println!("{}", serde_json::to_string(&f)?);
    Ok(())
}
