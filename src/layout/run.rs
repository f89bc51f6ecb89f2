//! `netspec layout`: the control loop, blocks, parcels, metrics and the independent check, and
//! the files a layout is written as.

use super::field::FieldMethod;
use super::metrics::{metrics, parcel_shape, Metrics};
use super::optimise::{optimise, OptimiseOptions};
use super::parcels::{blocks, parcellate, StreetIndex};
use super::region::Region;
use super::settings::{BlockSize, Fit, Weights};
use super::split::{Selection, SplitError, SplitOptions};
use super::template::select::{choose_greedy, template_parcels, Matcher, PlaceContext};
use super::tree::{grow, match_leaves, Grown, How, PartTree};
use super::validate::{validate, Violation};
use super::{Parcel, Street};
use crate::geometry::P;
use crate::render::layout::{layout_svg, LayoutScene, ParcelShape};
use rand::rngs::Xoshiro256PlusPlus;
use rand::SeedableRng;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// How a layout is made.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayoutOptions {
    /// The cross field's construction.
    pub field: FieldMethod,
    /// Best streamline, or drawn by quality.
    pub selection: Selection,
    /// The seed (the region's own unless overridden).
    pub seed: u64,
    /// Iterations of the global optimisation (§6; the paper's 10, 0 for none).
    pub optimise: usize,
}

/// A layout, checked.
#[derive(Clone, Debug, Serialize)]
pub struct Layout {
    /// The region's name.
    pub name: String,
    /// The seed it was made with.
    pub seed: u64,
    /// The field construction.
    pub field: FieldMethod,
    /// The selection mode.
    pub selection: Selection,
    /// The region's outer ring (counter-clockwise, metres), which traffic demand is drawn in.
    pub outer: Vec<P>,
    /// The region's holes (clockwise).
    pub holes: Vec<Vec<P>>,
    /// The WGS 84 `[longitude, latitude]` the metres are measured from (a transverse Mercator
    /// centred there), when the region is on the map.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub origin: Option<[f64; 2]>,
    /// Streets.
    pub streets: Vec<Street>,
    /// Parcels.
    pub parcels: Vec<Parcel>,
    /// The §7 metrics.
    pub metrics: Metrics,
    /// What the independent check found (empty: valid).
    pub violations: Vec<Violation>,
    /// Counts of the control loop.
    pub split: SplitCounts,
    /// The global optimisation's iterations and whether its streets were kept.
    pub optimisation: Optimisation,
    /// Blocks parcelled per template (the others by the row parceller).
    pub templates: std::collections::BTreeMap<String, usize>,
    /// The settings of the control loop.
    pub settings: Settings,
    /// The tree of parts: how every part was split or settled, with its score.
    pub parts: PartTree,
    /// Seconds per stage (not written to `layout.json`, so equal seeds give equal bytes).
    #[serde(skip)]
    pub times: Times,
}

/// Counts of the control loop.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SplitCounts {
    /// Streamline candidates traced.
    pub candidates: usize,
    /// Cuts along streamlines.
    pub cuts: usize,
    /// Blocks.
    pub blocks: usize,
    /// Leaves of the tree of parts.
    pub leaves: usize,
    /// Leaves settled by a template.
    pub by_template: usize,
}

/// The settings of the control loop a layout was made with.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Settings {
    /// Templates tried on every part before it is cut (else on the leaves only).
    pub templates_first: bool,
    /// The block size.
    pub block: BlockSize,
    /// The fit thresholds.
    pub fit: Fit,
    /// The weights of the streamline scores.
    pub weights: Weights,
}

/// What the global optimisation did.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Optimisation {
    /// Iterations asked for (0: not run).
    pub iterations: usize,
    /// Whether the optimised streets were kept: they are dropped, and the split's streets used,
    /// when the layout they give fails the independent check and the split's does not.
    pub kept: bool,
}

/// Seconds per stage.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Times {
    /// The control loop: fields, candidates, cuts and template matching.
    pub split: f64,
    /// The template matching within it.
    pub matching: f64,
    /// The global optimisation.
    pub optimise: f64,
    /// Blocks and parcels.
    pub parcels: f64,
    /// Metrics and the check.
    pub check: f64,
}

/// Why a layout failed.
#[derive(Debug, thiserror::Error)]
pub enum LayoutError {
    /// The control loop failed.
    #[error(transparent)]
    Split(#[from] SplitError),
    /// A file could not be written.
    #[error("writing {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The picture could not be rasterised.
    #[error("layout picture: {0}")]
    Render(#[from] crate::render::RenderError),
    /// The GeoJSON could not be projected.
    #[error(transparent)]
    Site(#[from] crate::geometry::site::SiteError),
    /// The region was refused.
    #[error(transparent)]
    Region(#[from] super::region::RegionError),
    /// The field could not be built or written.
    #[error(transparent)]
    Field(#[from] super::field::FieldError),
}

/// What `netspec layout` is asked for.
#[derive(Clone, Debug, PartialEq)]
pub struct LayoutRequest {
    /// The region file (TOML or GeoJSON).
    pub region: PathBuf,
    /// The field construction.
    pub field: FieldMethod,
    /// The selection of the first layout (the others are drawn by quality).
    pub selection: Selection,
    /// The seed (default: the region's).
    pub seed: Option<u64>,
    /// How many layouts (seeds `seed`, `seed + 1`, …).
    pub variations: usize,
    /// Iterations of the global optimisation (0: none).
    pub optimise: usize,
    /// Where to write them: the first in the directory, variation `k ≥ 2` in `variation-k/`.
    pub out: Option<PathBuf>,
}

/// Reads the region, makes the layouts and writes them (with `run.json`: the seconds per stage),
/// telling `progress` which variation runs (from 0) and the share of its region settled.
pub fn run(req: &LayoutRequest, progress: &mut dyn FnMut(usize, f64)) -> Result<Vec<Layout>, LayoutError> {
    let region = super::region::read_region(&req.region)?;
    let seed = req.seed.unwrap_or(region.seed);
    let mut out = Vec::new();
    for k in 0..req.variations.max(1) {
        let selection = if k == 0 { req.selection } else { Selection::Random };
        let opts = LayoutOptions { field: req.field, selection, seed: seed + k as u64, optimise: req.optimise };
        let l = layout_with_progress(&region, &opts, &mut |f| progress(k, f))?;
        if let Some(dir) = &req.out {
            let dir = if k == 0 { dir.clone() } else { dir.join(format!("variation-{}", k + 1)) };
            write_layout(&dir, &region, &l)?;
            let run = serde_json::json!({"times": l.times, "split": l.split, "seed": l.seed});
            let path = dir.join("run.json");
            std::fs::write(&path, serde_json::to_string_pretty(&run).expect("run.json serialises") + "\n")
                .map_err(|source| LayoutError::Io { path, source })?;
        }
        out.push(l);
    }
    Ok(out)
}

/// `netspec field`: the region's cross field, written as `field.json`, `field.svg` and `field.png`
/// with a few of its streamline candidates drawn over it.
pub fn field_command(
    region: &Path,
    method: FieldMethod,
    h: Option<f64>,
    out: &Path,
) -> Result<super::field::CrossField, LayoutError> {
    let region = super::region::read_region(region)?;
    let opts = SplitOptions::for_region(&region, method, Selection::Best);
    let field =
        super::field::CrossField::new(&region.polygon, &super::field::FieldOptions { method, h: h.unwrap_or(opts.h) })?;
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(region.seed);
    // Streamlines at four times the layout's separation, so the picture stays readable.
    let sparse = super::streamline::TraceOptions { separation: 4.0 * opts.trace.separation, ..opts.trace };
    let lines: Vec<Vec<P>> = super::streamline::candidates(&field, &region.polygon, &sparse, &mut rng)
        .into_iter()
        .map(|c| c.points)
        .collect();
    super::field::write_field(out, &field, &lines)?;
    Ok(field)
}

/// Lays a region out.
pub fn layout(region: &Region, opts: &LayoutOptions) -> Result<Layout, LayoutError> {
    layout_with_progress(region, opts, &mut |_| {})
}

/// [`layout`], telling `progress` the share of the region settled by the control loop (0 to 1).
pub fn layout_with_progress(
    region: &Region,
    opts: &LayoutOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<Layout, LayoutError> {
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(opts.seed);
    let t0 = Instant::now();
    let split_opts = SplitOptions::for_region(region, opts.field, opts.selection);
    let mut matcher = Matcher::new(&region.templates, region);
    let first = region.templates_first.then_some(&mut matcher);
    let mut g = grow(region, &split_opts, first, &mut rng, progress)?;
    let split_streets: Vec<Street> =
        g.streets.iter().map(|st| Street { polyline: round(&st.polyline), ..st.clone() }).collect();
    match_leaves(&mut g, &split_streets, region, &mut matcher, false);
    let matching = matcher.seconds;
    let t1 = Instant::now();
    let optimised: Vec<Street> = optimise(
        region,
        &split_streets,
        &OptimiseOptions { iterations: opts.optimise, ..OptimiseOptions::for_region(region) },
    )
    .into_iter()
    .map(|st| Street { polyline: round(&st.polyline), ..st })
    .collect();
    let t2 = Instant::now();
    let mut kept = opts.optimise > 0;
    let mut done = if kept {
        let mut moved = g.clone();
        match_leaves(&mut moved, &optimised, region, &mut matcher, true);
        Finished::new(region, moved, optimised, opts.selection, &mut rng)
    } else {
        Finished::new(region, g.clone(), split_streets.clone(), opts.selection, &mut rng)
    };
    if kept && !done.violations.is_empty() {
        let plain = Finished::new(region, g, split_streets, opts.selection, &mut rng);
        if plain.violations.is_empty() {
            done = plain;
            kept = false;
        }
    }
    let t3 = Instant::now();
    let times = Times {
        split: (t1 - t0).as_secs_f64(),
        matching,
        optimise: (t2 - t1).as_secs_f64(),
        parcels: done.parcel_seconds,
        check: (t3 - t2).as_secs_f64() - done.parcel_seconds,
    };
    let by_template = done.grown.leaves.iter().filter(|l| done.grown.nodes[l.node].how == How::Template).count();
    let split = SplitCounts {
        candidates: done.grown.candidates,
        cuts: done.grown.cuts,
        blocks: done.blocks,
        leaves: done.grown.leaves.len(),
        by_template,
    };
    Ok(Layout {
        name: region.name.clone(),
        seed: opts.seed,
        field: opts.field,
        selection: opts.selection,
        outer: region.polygon.outer().to_vec(),
        origin: region.projection.as_ref().map(|p| p.origin()),
        holes: region.polygon.holes().to_vec(),
        parts: done.grown.tree(0),
        streets: done.streets,
        parcels: done.parcels,
        metrics: done.metrics,
        violations: done.violations,
        split,
        optimisation: Optimisation { iterations: opts.optimise, kept },
        templates: done.templates,
        settings: Settings {
            templates_first: region.templates_first,
            block: region.block,
            fit: region.fit,
            weights: region.weights,
        },
        times,
    })
}

/// Streets with their blocks, parcels (every leaf by its template, or by the row parceller),
/// metrics and check.
struct Finished {
    grown: Grown,
    streets: Vec<Street>,
    parcels: Vec<Parcel>,
    templates: std::collections::BTreeMap<String, usize>,
    blocks: usize,
    metrics: Metrics,
    violations: Vec<Violation>,
    parcel_seconds: f64,
}

impl Finished {
    fn new(
        region: &Region,
        mut grown: Grown,
        mut streets: Vec<Street>,
        selection: Selection,
        rng: &mut Xoshiro256PlusPlus,
    ) -> Finished {
        let t = Instant::now();
        let blocks = blocks(&region.polygon, &streets);
        let (parcels, extra, templates) = parcel_leaves(region, &mut grown, &streets, selection, rng);
        streets.extend(extra.into_iter().map(|st| Street { polyline: round(&st.polyline), ..st }));
        let parcels: Vec<Parcel> = parcels.into_iter().map(|p| Parcel { polygon: round(&p.polygon), ..p }).collect();
        let parcel_seconds = t.elapsed().as_secs_f64();
        let metrics = metrics(&region.polygon, &streets, &blocks, &parcels);
        let violations = validate(&region.polygon, &streets, &parcels);
        Finished { grown, streets, parcels, templates, blocks: blocks.len(), metrics, violations, parcel_seconds }
    }
}

/// The parcels of every leaf — its template's (the first accepted whose count is not used up,
/// leaves with the largest block choosing first) or the row parceller's — the template streets,
/// and the uses per template; every leaf's node records its template and energy.
fn parcel_leaves(
    region: &Region,
    g: &mut Grown,
    streets: &[Street],
    selection: Selection,
    rng: &mut Xoshiro256PlusPlus,
) -> (Vec<Parcel>, Vec<Street>, std::collections::BTreeMap<String, usize>) {
    let lib = &region.templates;
    let index = StreetIndex::new(streets);
    let ctx = PlaceContext::new(streets, region);
    let mut order: Vec<usize> = (0..g.leaves.len()).collect();
    order.sort_by(|&a, &b| {
        block_key(&g.leaves[a]).partial_cmp(&block_key(&g.leaves[b])).unwrap_or(std::cmp::Ordering::Equal)
    });
    let mut uses = std::collections::BTreeMap::new();
    let mut per_leaf: Vec<(Vec<Parcel>, Vec<Street>)> = vec![(Vec::new(), Vec::new()); g.leaves.len()];
    for k in order {
        let leaf = &g.leaves[k];
        let node = &mut g.nodes[leaf.node];
        let chosen = choose_greedy(leaf.options.clone(), lib, &uses, selection, rng);
        match (chosen, &leaf.block) {
            (Some(c), Some(block)) => {
                let t = &lib[c.template];
                let (mut parcels, new_streets) = template_parcels(block, &c, t, &ctx, &index, &node.id);
                for b in leaf.blocks.iter().skip(1) {
                    parcels.extend(rows(b, &index, region, &node.id));
                }
                *uses.entry(t.name.clone()).or_default() += 1;
                node.how = How::Template;
                node.template = Some(t.name.clone());
                node.score = Some(c.warp.energy);
                per_leaf[k] = (parcels, new_streets);
            }
            _ => {
                node.how = How::Rows;
                node.template = None;
                node.score = None;
                per_leaf[k].0 = leaf.blocks.iter().flat_map(|b| rows(b, &index, region, &node.id)).collect();
            }
        }
    }
    let (parcels, new_streets): (Vec<Vec<Parcel>>, Vec<Vec<Street>>) = per_leaf.into_iter().unzip();
    (parcels.concat(), new_streets.concat(), uses)
}

/// The row parceller's parcels of one block, in a part.
fn rows(b: &geo::Polygon<f64>, index: &StreetIndex, region: &Region, part: &str) -> Vec<Parcel> {
    parcellate(std::slice::from_ref(b), index, region.parcel.depth, region.parcel.width)
        .into_iter()
        .map(|p| Parcel { part: part.to_string(), ..p })
        .collect()
}

/// Leaves with the largest block first (ties by the block's first vertex).
fn block_key(l: &super::tree::Leaf) -> (f64, i64, i64) {
    use geo::Area;
    l.blocks.first().map_or((0.0, 0, 0), |b| {
        let c = b.exterior().0.first().map_or((0, 0), |c| ((c.x * 1e3).round() as i64, (c.y * 1e3).round() as i64));
        (-(b.unsigned_area() * 1e3).round(), c.0, c.1)
    })
}

/// Coordinates rounded to the millimetre (compact, stable files).
fn round(line: &[P]) -> Vec<P> {
    let r = |x: f64| (x * 1000.0).round() / 1000.0;
    let mut out: Vec<P> = Vec::with_capacity(line.len());
    for p in line {
        let q = [r(p[0]), r(p[1])];
        if out.last() != Some(&q) {
            out.push(q);
        }
    }
    out
}

/// Writes `layout.json`, `layout.svg`, `layout.png` and (when the region has a projection)
/// `layout.geojson` into `dir`.
pub fn write_layout(dir: &Path, region: &Region, layout: &Layout) -> Result<(), LayoutError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| LayoutError::Io { path, source }
    };
    std::fs::create_dir_all(dir).map_err(io(dir))?;
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        std::fs::write(&path, bytes).map_err(io(&path))
    };
    write("layout.json", (serde_json::to_string_pretty(layout).expect("layout serialises") + "\n").as_bytes())?;
    let svg = layout_svg(&scene(region, layout));
    write("layout.svg", svg.as_bytes())?;
    write("layout.png", &crate::render::png(&svg)?)?;
    if let Some(proj) = &region.projection {
        write(
            "layout.geojson",
            (serde_json::to_string(&geojson(proj, layout)?).expect("GeoJSON serialises") + "\n").as_bytes(),
        )?;
    }
    Ok(())
}

/// The picture's plain data.
pub fn scene(region: &Region, layout: &Layout) -> LayoutScene {
    let m = &layout.metrics;
    LayoutScene {
        rings: region.polygon.rings().map(<[P]>::to_vec).collect(),
        parcels: layout
            .parcels
            .iter()
            .map(|p| ParcelShape {
                ring: p.polygon.clone(),
                use_: serde_json::to_value(p.use_)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_default(),
                undesirable: parcel_shape(&p.polygon).undesirable(),
            })
            .collect(),
        streets: layout.streets.iter().map(|s| (s.polyline.clone(), s.width, s.level)).collect(),
        caption: format!(
            "{}: {} parcels ({} undesirable), corners {:.1}° off, area ratio {:.3}, streets {:.1} %",
            layout.name, m.parcels, m.undesirable, m.corner_deviation_mean, m.area_ratio_mean, m.land_use.streets
        ),
    }
}

fn geojson(proj: &crate::geometry::site::Projection, layout: &Layout) -> Result<serde_json::Value, LayoutError> {
    let ll = |line: &[P]| -> Result<Vec<[f64; 2]>, LayoutError> {
        line.iter()
            .map(|&p| proj.to_wgs84(p).map(|q| [(q[0] * 1e8).round() / 1e8, (q[1] * 1e8).round() / 1e8]))
            .collect::<Result<_, _>>()
            .map_err(Into::into)
    };
    let mut features = Vec::new();
    for s in &layout.streets {
        features.push(serde_json::json!({"type": "Feature",
            "properties": {"kind": "street", "level": s.level, "width": s.width},
            "geometry": {"type": "LineString", "coordinates": ll(&s.polyline)?}}));
    }
    for p in &layout.parcels {
        let mut ring = ll(&p.polygon)?;
        ring.push(ring[0]);
        features.push(serde_json::json!({"type": "Feature",
            "properties": {"kind": "parcel", "use": p.use_},
            "geometry": {"type": "Polygon", "coordinates": [ring]}}));
    }
    Ok(serde_json::json!({"type": "FeatureCollection", "features": features}))
}
