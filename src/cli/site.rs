//! `netspec site EXTRACT`: a real site from an OpenStreetMap extract.

use anyhow::Result;
use netspec::osm::areas::AreaClass;
use netspec::osm::site::{self, Area, SiteRequest};
use std::collections::BTreeSet;
use std::path::PathBuf;
use std::process::ExitCode;

/// The command line of `netspec site`.
#[derive(clap::Args)]
pub struct SiteArgs {
    /// The OpenStreetMap extract (`.osm.pbf` or `.osm` XML; netspec never downloads one).
    pub extract: PathBuf,
    /// The region as a box: west,south,east,north (WGS 84 degrees).
    #[arg(long, value_name = "W,S,E,N", value_parser = parse_bbox, allow_hyphen_values = true, conflicts_with = "polygon", required_unless_present = "polygon")]
    pub bbox: Option<[f64; 4]>,
    /// The region as a GeoJSON file whose one Polygon is its outline.
    #[arg(long, value_name = "REGION.geojson")]
    pub polygon: Option<PathBuf>,
    /// Output directory: site.geojson, map/streets.geojson (and grow.toml, city.toml).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Which areas become holes: water, park, rail (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "water", value_parser = parse_hole)]
    pub holes: Vec<AreaClass>,
    /// The `highway` classes that are the site's major roads (comma-separated).
    #[arg(long, value_delimiter = ',', default_value = "motorway,trunk,primary,secondary")]
    pub major: Vec<String>,
    /// Service roads are part of the real streets (level 4).
    #[arg(long)]
    pub service: bool,
    /// Also write grow.toml, a `netspec grow` context of the site.
    #[arg(long)]
    pub grow: bool,
    /// Also write city.toml, a `netspec city` spec of the site.
    #[arg(long)]
    pub city: bool,
    /// Keep the largest piece of land when the holes split the region (default: refuse).
    #[arg(long)]
    pub largest: bool,
    /// The site's name (default: the output directory's).
    #[arg(long)]
    pub name: Option<String>,
    /// OSM ids of ways of the major classes to leave out of the major roads (comma-separated).
    #[arg(long, value_delimiter = ',', value_name = "WAY_IDS")]
    pub exclude: Vec<i64>,
}

fn parse_bbox(s: &str) -> Result<[f64; 4], String> {
    let v: Vec<f64> =
        s.split(',').map(|x| x.trim().parse::<f64>()).collect::<Result<_, _>>().map_err(|e| format!("`{s}`: {e}"))?;
    match v[..] {
        [w, so, e, n] => Ok([w, so, e, n]),
        _ => Err(format!("expected west,south,east,north (degrees), got `{s}`")),
    }
}

fn parse_hole(s: &str) -> Result<AreaClass, String> {
    AreaClass::parse(s).ok_or_else(|| format!("`{s}` is not water, park or rail"))
}

/// Runs `netspec site` and prints what it made.
pub fn run(a: SiteArgs) -> Result<ExitCode> {
    let req = SiteRequest {
        extract: a.extract,
        area: match (a.bbox, a.polygon) {
            (Some(b), _) => Area::Bbox(b),
            (None, Some(p)) => Area::Polygon(p),
            (None, None) => anyhow::bail!("give the region with --bbox or --polygon"),
        },
        out: a.out,
        holes: a.holes.into_iter().collect::<BTreeSet<_>>(),
        major: a.major,
        service: a.service,
        grow: a.grow,
        city: a.city,
        largest: a.largest,
        name: a.name,
        exclude: a.exclude.into_iter().collect(),
    };
    let s = site::run(&req)?;
    println!(
        "site {}: region {:.3} km², land {:.3} km² ({} holes{}), origin {:.6},{:.6}",
        s.name,
        s.region_km2,
        s.land_km2,
        s.holes,
        if s.dropped.is_empty() {
            String::new()
        } else {
            format!(
                "; dropped {} piece(s) of land: {}",
                s.dropped.len(),
                s.dropped.iter().map(|a| format!("{:.2} ha", a / 1e4)).collect::<Vec<_>>().join(", ")
            )
        },
        s.origin[0],
        s.origin[1]
    );
    println!(
        "major roads {} pieces, {:.2} km · real streets {} pieces, {:.2} km inside",
        s.roads.0,
        s.roads.1 / 1e3,
        s.streets.0,
        s.streets.1 / 1e3
    );
    if s.outside_share > 0.0 {
        println!(
            "warning: {:.0} % of the region's box lies beyond the extract's nodes; streets there are missing",
            100.0 * s.outside_share
        );
    }
    if s.incomplete_areas > 0 {
        println!("warning: {} areas were left out because the extract lacks some of their nodes", s.incomplete_areas);
    }
    println!("data {}", netspec::osm::ATTRIBUTION);
    for f in &s.files {
        println!("wrote {}", f.display());
    }
    Ok(ExitCode::SUCCESS)
}
