//! `netspec layout` and `netspec field` (Yang et al. 2013): layouts checked by the independent
//! validator, reproducible from their seed, GeoJSON sites, and refused inputs.

use netspec::layout::field::FieldMethod;
use netspec::layout::region::read_region;
use netspec::layout::run::{layout, LayoutOptions};
use netspec::layout::split::Selection;
use netspec::layout::validate::validate;
use std::path::{Path, PathBuf};
use std::process::Command;

fn model(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("models/layout").join(name)
}

fn netspec() -> Command {
    Command::new(env!("CARGO_BIN_EXE_netspec"))
}

#[test]
fn every_example_region_is_laid_out_validly() {
    for name in ["lake.toml", "disc.toml", "irregular.geojson"] {
        let region = read_region(&model(name)).unwrap();
        let l = layout(
            &region,
            &LayoutOptions {
                field: FieldMethod::Distance,
                selection: Selection::Best,
                seed: region.seed,
                optimise: 10,
            },
        )
        .unwrap();
        // The library's own check, and the validator run again here on the returned data.
        assert_eq!(l.violations, vec![], "{name}");
        assert_eq!(validate(&region.polygon, &l.streets, &l.parcels), vec![], "{name}");
        let lu = &l.metrics.land_use;
        let sum = lu.streets + lu.residential + lu.parks + lu.other;
        assert!((sum - 100.0).abs() < 1.0, "{name}: land use sums to {sum}");
        assert!(l.split.cuts > 5 && l.metrics.parcels > 100, "{name}: {:?}", l.split);
        assert!(lu.streets > 15.0 && lu.streets < 40.0, "{name}: streets {} %", lu.streets);
    }
}

#[test]
fn same_seed_same_bytes_other_seed_other_layout() {
    let dir = tempfile::tempdir().unwrap();
    let run = |seed: &str, out: &str| {
        let o = netspec()
            .args(["layout", model("lake.toml").to_str().unwrap(), "--mode", "random", "--seed", seed, "--out"])
            .arg(dir.path().join(out))
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(String::from_utf8_lossy(&o.stdout).contains("valid"));
        std::fs::read(dir.path().join(out).join("layout.json")).unwrap()
    };
    let (a, b, c) = (run("7", "a"), run("7", "b"), run("8", "c"));
    assert_eq!(a, b, "same seed, same layout.json");
    assert_ne!(a, c, "another seed, another layout");
    for f in ["layout.svg", "layout.png", "run.json"] {
        assert!(dir.path().join("a").join(f).is_file(), "{f}");
    }
    let json: serde_json::Value = serde_json::from_slice(&a).unwrap();
    assert!(json["streets"][0]["polyline"].is_array() && json["parcels"][0]["use"].is_string());
    assert!(json["metrics"]["corner_deviation_mean"].is_number());
    // The tree of parts: every node says how it was split or settled; leaves name their parcels.
    let parts = &json["parts"];
    assert_eq!((parts["id"].as_str(), parts["how"].as_str()), (Some("0"), Some("streamline")));
    fn leaves(n: &serde_json::Value, out: &mut Vec<String>) {
        match n["children"].as_array() {
            Some(c) => c.iter().for_each(|k| leaves(k, out)),
            None => out.push(n["id"].as_str().unwrap().to_string()),
        }
    }
    let mut ids = Vec::new();
    leaves(parts, &mut ids);
    for p in json["parcels"].as_array().unwrap() {
        assert!(ids.iter().any(|id| p["part"] == id.as_str()), "{}", p["part"]);
    }
    assert!(json["settings"]["templates_first"].as_bool().unwrap());
}

#[test]
fn a_geojson_site_gives_geojson_in_wgs84_and_variations() {
    let dir = tempfile::tempdir().unwrap();
    let o = netspec()
        .args(["layout", model("irregular.geojson").to_str().unwrap(), "--variations", "2", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let gj: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("layout.geojson")).unwrap()).unwrap();
    let first = &gj["features"][0]["geometry"]["coordinates"][0];
    let (lon, lat) = (first[0].as_f64().unwrap(), first[1].as_f64().unwrap());
    assert!((lon - 11.57).abs() < 0.01 && (lat - 48.14).abs() < 0.01, "{lon} {lat}");
    assert!(dir.path().join("variation-2/layout.json").is_file());
}

#[test]
fn the_field_command_writes_singularities() {
    let dir = tempfile::tempdir().unwrap();
    let o = netspec()
        .args(["field", model("disc.toml").to_str().unwrap(), "--method", "smooth", "--out"])
        .arg(dir.path())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let f: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.path().join("field.json")).unwrap()).unwrap();
    let sum: f64 = f["singularities"].as_array().unwrap().iter().map(|s| s["index"].as_f64().unwrap()).sum();
    assert_eq!(sum, 1.0, "a disc's indices sum to its Euler characteristic");
    assert!(f["vertices"].as_u64().unwrap() > 100 && dir.path().join("field.png").is_file());
}

#[test]
fn bad_regions_are_refused_naming_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "hole.toml",
            "outer = [[0, 0], [100, 0], [100, 100], [0, 100]]\nholes = [[[200, 0], [300, 0], [300, 50]]]\n",
            "holes[0]",
        ),
        ("bow.toml", "outer = [[0, 0], [100, 100], [100, 0], [0, 100]]\n", "outer: the outer ring intersects itself"),
        ("road.toml", "outer = [[0, 0], [100, 0], [100, 100], [0, 100]]\nroads = [[[200, 0], [300, 0]]]\n", "roads[0]"),
        ("big.toml", "outer = [[0, 0], [1e5, 0], [1e5, 1e5], [0, 1e5]]\n", "parcels"),
        ("nan.geojson", "{\"type\": \"Polygon\", \"coordinates\": [[[0, 0], [1, 0], [1, 91], [0, 0]]]}", "features[0]"),
        (
            "zones.toml",
            "outer = [[0, 0], [100, 0], [100, 100], [0, 100]]\n[[zone]]\npolygon = [[0, 0], [50, 0], [50, 50]]\nuse = \"park\"\n\
             [[zone]]\npolygon = [[10, 0], [60, 0], [60, 50]]\nuse = \"school\"\n",
            "zone[1]: overlaps zone[0]",
        ),
        (
            "zone.geojson",
            "{\"type\": \"FeatureCollection\", \"features\": [\
             {\"type\": \"Feature\", \"properties\": {}, \"geometry\": {\"type\": \"Polygon\", \"coordinates\": [[[11, 48], [11.01, 48], [11.01, 48.01], [11, 48.01], [11, 48]]]}},\
             {\"type\": \"Feature\", \"properties\": {\"use\": \"mall\"}, \"geometry\": {\"type\": \"Polygon\", \"coordinates\": [[[11.001, 48.001], [11.002, 48.001], [11.002, 48.002], [11.001, 48.001]]]}}]}",
            "features[1]: use = \"mall\"",
        ),
    ];
    for (file, text, needle) in cases {
        let path = dir.path().join(file);
        std::fs::write(&path, text).unwrap();
        let o = netspec().args(["layout"]).arg(&path).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{file}: {err}");
        assert!(err.contains(file) && err.contains(needle), "{file}: {err}");
        assert!(!err.contains("panicked"), "{file}: {err}");
    }
}

#[test]
fn templates_parcel_some_lake_blocks_and_the_layout_still_validates() {
    let region = read_region(&model("lake.toml")).unwrap();
    let l = layout(
        &region,
        &LayoutOptions { field: FieldMethod::Distance, selection: Selection::Best, seed: 3, optimise: 0 },
    )
    .unwrap();
    assert_eq!(l.violations, vec![]);
    assert_eq!(validate(&region.polygon, &l.streets, &l.parcels), vec![]);
    let used: usize = l.templates.values().sum();
    assert!(used >= 5 && used <= l.split.blocks, "{:?}", l.templates);
    assert!(l.parcels.iter().any(|p| p.template.is_some()) && l.parcels.iter().any(|p| p.template.is_none()));
    // Counts from the template files are kept.
    for t in &region.templates {
        if let Some(k) = t.max_uses {
            assert!(l.templates.get(&t.name).copied().unwrap_or(0) <= k, "{}", t.name);
        }
    }
    // Fig. 6: the full warp registers the parcels closer to their ideal than mean-value
    // coordinates alone.
    let f = netspec::layout::template::fig6::fig6(&region, &region.templates).unwrap();
    assert!(f.matched >= 5 && f.faces > 100, "{f:?}");
    assert!(f.warp < f.mvc && f.ratio < 0.9, "{f:?}");
}

#[test]
fn a_regions_template_dir_adds_its_templates_and_bad_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let lake = std::fs::read_to_string(model("lake.toml")).unwrap();
    std::fs::write(dir.path().join("r.toml"), format!("{lake}\n[templates]\ndir = \"mine\"\n")).unwrap();
    std::fs::create_dir(dir.path().join("mine")).unwrap();
    // A user's row template replaces the built-in one of the same name.
    let row = "name = \"row\"\nkind = \"block\"\nmax_uses = 0\n[[face]]\npolygon = [[0, 0], [18, 0], [18, 30], [0, 30]]\nuse = \"commercial\"\n";
    std::fs::write(dir.path().join("mine/a.toml"), row).unwrap();
    let region = read_region(&dir.path().join("r.toml")).unwrap();
    let mine = region.templates.iter().find(|t| t.name == "row").unwrap();
    assert_eq!((mine.max_uses, region.templates.len()), (Some(0), 13));
    std::fs::write(dir.path().join("mine/b.toml"), format!("{row}class = \"fluid\"\n")).unwrap();
    let e = read_region(&dir.path().join("r.toml")).unwrap_err().to_string();
    assert!(e.contains("mine/b.toml") && e.contains("face[0].class"), "{e}");
}

/// The use of the parcels whose label points lie in a ring.
fn uses_in(parcels: &[netspec::layout::Parcel], ring: &[[f64; 2]]) -> Vec<netspec::layout::Use> {
    parcels
        .iter()
        .filter(|p| {
            let n = p.polygon.len() as f64;
            let c = p.polygon.iter().fold([0.0, 0.0], |a, q| [a[0] + q[0] / n, a[1] + q[1] / n]);
            netspec::geometry::ring_contains(ring, c)
        })
        .map(|p| p.use_)
        .collect()
}

#[test]
fn zones_keep_their_use_and_template_counts_are_met_or_reported() {
    use netspec::layout::Use;
    let region = read_region(&model("fig13.toml")).unwrap();
    let l = layout(
        &region,
        &LayoutOptions { field: FieldMethod::Distance, selection: Selection::Best, seed: region.seed, optimise: 0 },
    )
    .unwrap();
    assert_eq!(l.violations, vec![]);
    for (zone, want) in region.zones.iter().zip([Use::School, Use::Commercial, Use::Park]) {
        let uses = uses_in(&l.parcels, &zone.ring);
        assert!(!uses.is_empty() && uses.iter().all(|&u| u == want || u == Use::Other), "{}: {uses:?}", zone.name);
    }
    // The school zone is filled by the school template: a building lot and its field.
    let school = uses_in(&l.parcels, &region.zones[0].ring);
    assert!(school.iter().filter(|&&u| u == Use::School).count() >= 2, "{school:?}");
    // Every minimum is met or reported, never dropped.
    for c in &l.counts {
        let reported = l.unmet.iter().any(|u| u.template == c.template && u.used == c.used && u.min == c.min);
        assert!(c.used >= c.min || reported, "{c:?} {:?}", l.unmet);
    }
    let used = |name: &str| l.templates.get(name).copied().unwrap_or(0);
    assert!(used("townhouses") + used("apartments") + used("mixed") >= 3, "{:?}", l.templates);
}

#[test]
fn a_part_is_laid_out_again_with_the_rest_kept() {
    let dir = tempfile::tempdir().unwrap();
    let lake = model("lake.toml");
    let first = dir.path().join("first");
    let o = netspec().args(["layout", lake.to_str().unwrap(), "--out"]).arg(&first).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let before: serde_json::Value = serde_json::from_slice(&std::fs::read(first.join("layout.json")).unwrap()).unwrap();
    // The first part cut along a streamline, below the root.
    let part = before["parts"]["children"][1]["id"].as_str().unwrap().to_string();
    let again = dir.path().join("again");
    let o = netspec()
        .args(["layout", lake.to_str().unwrap(), "--mode", "random", "--seed", "9", "--relayout", &part, "--from"])
        .arg(first.join("layout.json"))
        .arg("--out")
        .arg(&again)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let after: serde_json::Value = serde_json::from_slice(&std::fs::read(again.join("layout.json")).unwrap()).unwrap();
    assert_eq!(after["relayout"], part.as_str());
    assert_eq!(after["violations"].as_array().unwrap().len(), 0);
    let within = |p: &serde_json::Value| {
        let id = p["part"].as_str().unwrap_or("");
        id == part || id.starts_with(&format!("{part}."))
    };
    let outside = |l: &serde_json::Value, key: &str| -> Vec<serde_json::Value> {
        l[key].as_array().unwrap().iter().filter(|p| !within(p)).cloned().collect()
    };
    for key in ["parcels", "streets"] {
        let (a, b) = (outside(&before, key), outside(&after, key));
        assert!(!a.is_empty() && a.iter().all(|p| b.contains(p)), "{key} outside {part} are kept");
    }
    assert_ne!(before["parcels"], after["parcels"], "the part is laid out anew");
    assert!(after["parcels"].as_array().unwrap().iter().any(within));
    // An unknown part is refused, naming the file and the part.
    let o = netspec()
        .args(["layout", lake.to_str().unwrap(), "--relayout", "0.9.9", "--from"])
        .arg(first.join("layout.json"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("layout.json") && err.contains("no part 0.9.9"), "{err}");
}

/// A request out of range is refused before any work, naming the flag; a triggered interrupt
/// makes the first layout only.
#[test]
fn requests_are_checked_and_an_interrupt_stops_the_variations() {
    use netspec::layout::run::{run, LayoutError, LayoutRequest};
    let req = LayoutRequest {
        region: model("fig7.toml"),
        field: FieldMethod::Distance,
        selection: Selection::Best,
        seed: None,
        variations: 3,
        optimise: 0,
        out: None,
        relayout: None,
        interrupt: None,
    };
    assert_eq!(req.validate(), Ok(()));
    for (bad, text) in [
        (LayoutRequest { variations: 0, ..req.clone() }, "--variations must be 1 to 1000, got 0"),
        (LayoutRequest { optimise: 101, ..req.clone() }, "--optimise must be 0 to 100, got 101"),
        (
            LayoutRequest { relayout: Some(("layout.json".into(), "0".into())), ..req.clone() },
            "--variations cannot be used with a relayout",
        ),
        (LayoutRequest { region: "no-such-region.toml".into(), variations: 0, ..req.clone() }, "--variations"),
    ] {
        let e = run(&bad, &mut |_, _| {}).unwrap_err();
        assert!(matches!(e, LayoutError::Setting(_)), "{e}");
        assert!(e.to_string().starts_with(text), "{e}");
    }
    let e = netspec::layout::run::field_command(&model("fig7.toml"), FieldMethod::Distance, Some(0.0), Path::new("x"))
        .unwrap_err();
    assert_eq!(e.to_string(), "--h must be a positive number of metres, got 0");

    let interrupt = netspec::solvers::Interrupt::new();
    interrupt.trigger();
    let made = run(&LayoutRequest { interrupt: Some(interrupt), ..req.clone() }, &mut |_, _| {}).unwrap();
    assert_eq!(made.len(), 1);
    assert_eq!(run(&req, &mut |_, _| {}).unwrap().len(), 3);
}
