//! Real sites: `netspec site` on the central Helsinki extract (a 0.84 km² box: reading the PBF,
//! the land less its water, the major roads, the real streets, the files), and `netspec stats` on
//! the largest design of the real sites (the Onchan site's context grown for 40 steps: about
//! 800 nodes and 40 km of street, measured on the site's outline). The extracts come from
//! `scripts/setup.sh osm`, run here. Run with `cargo bench --bench site`.

use criterion::{criterion_group, criterion_main, Criterion};
use netspec::osm::areas::AreaClass;
use netspec::osm::site::{self, Area, SiteRequest};
use netspec::traffic::network::{load_whole, LoadOptions, SiteRegion};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::process::Command;

/// An extract of `scripts/setup.sh osm`, fetched once.
fn extract(name: &str) -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let ok = Command::new("bash").arg(root.join("scripts/setup.sh")).arg("osm").status().is_ok_and(|s| s.success());
    assert!(ok, "scripts/setup.sh osm failed");
    let deps = std::env::var_os("NETSPEC_DEPS").map(PathBuf::from).unwrap_or_else(|| {
        let cache = std::env::var_os("XDG_CACHE_HOME")
            .map(PathBuf::from)
            .unwrap_or_else(|| PathBuf::from(std::env::var_os("HOME").expect("HOME")).join(".cache"));
        cache.join("netspec")
    });
    deps.join("osm").join(name)
}

fn request(extract: PathBuf, bbox: [f64; 4], out: PathBuf, grow: bool) -> SiteRequest {
    SiteRequest {
        extract,
        area: Area::Bbox(bbox),
        out,
        holes: [AreaClass::Water].into(),
        major: netspec::osm::ways::MAJOR.iter().map(|s| s.to_string()).collect(),
        service: false,
        grow,
        city: false,
        largest: false,
        name: None,
        exclude: Default::default(),
    }
}

fn sites(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    let helsinki =
        request(extract("helsinki.osm.pbf"), [24.9375, 60.1666, 24.9511, 60.1766], dir.path().join("h"), true);
    let mut g = c.benchmark_group("site");
    g.sample_size(10);
    g.bench_function("site: Helsinki centre, 0.84 km² box", |b| b.iter(|| site::run(black_box(&helsinki)).unwrap()));

    let onchan = dir.path().join("onchan");
    site::run(&request(extract("isle-of-man.osm.pbf"), [-4.47, 54.172, -4.456, 54.181], onchan.clone(), true)).unwrap();
    let grow = netspec::grow::GrowRequest {
        context: onchan.join("grow.toml"),
        out: onchan.join("grown"),
        seed: None,
        steps: None,
        every: None,
        all_streets: false,
        gallery: None,
        interrupt: None,
    };
    netspec::grow::run(&grow, &mut |_, _| {}).unwrap();
    let region = SiteRegion::load(&onchan.join("site.geojson")).unwrap();
    let load = LoadOptions { region: Some(region), ..Default::default() };
    let (net, polygon) = load_whole(&onchan.join("grown"), &load).unwrap();
    let streets = netspec::measure::street_network(&net);
    let name = format!("stats: Onchan grown, {} nodes, {} streets", streets.nodes.len(), streets.edges.len());
    g.bench_function(&name, |b| {
        b.iter(|| netspec::stats::measure(black_box(&streets), polygon.as_ref(), &Default::default()))
    });
    g.finish();
}

criterion_group!(benches, sites);
criterion_main!(benches);
