//! `netspec layout`: the control loop, blocks, parcels, metrics and the independent check, and
//! the files a layout is written as.

use super::field::FieldMethod;
use super::metrics::{metrics, parcel_shape, Metrics};
use super::optimise::{optimise, OptimiseOptions};
use super::parcels::{blocks, StreetIndex};
use super::region::Region;
use super::settings::{BlockSize, Fit, Weights};
use super::split::{Selection, SplitError, SplitOptions};
use super::template::assign::{assign, choice_parcels, Choice, Context, Unmet};
use super::template::select::{Matcher, PlaceContext};
use super::tree::{grow, match_leaves, Grown, How, PartTree};
use super::validate::{validate, Violation};
use super::{Parcel, Street};
use crate::geometry::geojson::GeoJsonWriter;
use crate::geometry::{Shape, P};
use crate::render::layout::{histograms_svg, layout_svg, registration_svg, HistogramPanel, LayoutScene, ParcelShape};
use crate::solvers::Interrupt;
use crate::spec::SettingsError;
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
    /// Uses per template (area templates included; the other parts by the row parceller).
    pub templates: std::collections::BTreeMap<String, usize>,
    /// The templates with a minimum or maximum count: the count and how often each is used.
    pub counts: Vec<Count>,
    /// Minimum counts the parts could not meet.
    pub unmet: Vec<Unmet>,
    /// The part laid out again (`--relayout`), the rest kept from the layout it was read from.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub relayout: Option<String>,
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

/// A template's count limits and its uses.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Count {
    /// The template.
    pub template: String,
    /// Its minimum.
    pub min: usize,
    /// Its maximum.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max: Option<usize>,
    /// How often it is used.
    pub used: usize,
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

impl Settings {
    /// The region's settings of the control loop.
    fn of(region: &Region) -> Settings {
        Settings {
            templates_first: region.templates_first,
            block: region.block,
            fit: region.fit,
            weights: region.weights,
        }
    }
}

/// What the global optimisation did.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Optimisation {
    /// Iterations asked for (0: not run).
    pub iterations: usize,
    /// Whether the optimised streets were kept: they are dropped, and the split's streets used,
    /// when the layout they give fails the independent check and the split's does not.
    pub kept: bool,
    /// The paper's measure of Fig. 10 on the split's streets: the template parcels' mean
    /// registration distance to their ideal (metres, §7's `p_similarity`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub registration_before: Option<f64>,
    /// The same on the optimised streets, the same templates warped again.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub registration_after: Option<f64>,
}

/// Seconds per stage.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Times {
    /// The control loop: fields, candidates, cuts and template matching.
    pub split: f64,
    /// The template matching within it.
    pub matching: f64,
    /// The choice of templates with their counts (backtracking).
    pub backtracking: f64,
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
    /// The layout to relay out was refused.
    #[error(transparent)]
    Relayout(#[from] super::relayout::RelayoutError),
    /// A setting of the request was refused (named as the command line's flag).
    #[error(transparent)]
    Setting(#[from] SettingsError),
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
    /// `--from LAYOUT.json --relayout PART`: lay that part of that layout out again, the rest kept.
    pub relayout: Option<(PathBuf, String)>,
    /// A request to stop early: once triggered, no further variation is started (the ones made
    /// are written and returned; the first is always made).
    pub interrupt: Option<Interrupt>,
}

/// Most layouts one request makes.
pub const MAX_VARIATIONS: usize = 1000;

/// Most iterations of the global optimisation.
pub const MAX_OPTIMISE: usize = 100;

impl LayoutRequest {
    /// Refuses settings out of range, each named as the command line's flag: `variations` in
    /// 1..=[`MAX_VARIATIONS`], `optimise` at most [`MAX_OPTIMISE`], and a relayout with either
    /// (it makes one layout, not optimised).
    pub fn validate(&self) -> Result<(), SettingsError> {
        let refuse = |place: &str, reason: String| Err(SettingsError { place: place.into(), reason });
        if !(1..=MAX_VARIATIONS).contains(&self.variations) {
            return refuse("--variations", format!("must be 1 to {MAX_VARIATIONS}, got {}", self.variations));
        }
        if self.optimise > MAX_OPTIMISE {
            return refuse("--optimise", format!("must be 0 to {MAX_OPTIMISE}, got {}", self.optimise));
        }
        if self.relayout.is_some() && (self.variations > 1 || self.optimise > 0) {
            let place = if self.variations > 1 { "--variations" } else { "--optimise" };
            return refuse(place, "cannot be used with a relayout".into());
        }
        Ok(())
    }
}

/// Refuses a triangle size of the field that is not a positive number of metres.
pub fn check_field_h(h: Option<f64>) -> Result<(), SettingsError> {
    match h.filter(|h| !(h.is_finite() && *h > 0.0)) {
        Some(h) => {
            Err(SettingsError { place: "--h".into(), reason: format!("must be a positive number of metres, got {h}") })
        }
        None => Ok(()),
    }
}

/// Checks the request ([`LayoutRequest::validate`]), reads the region, makes the layouts and
/// writes them (with `run.json`: the seconds per stage), telling `progress` which variation runs
/// (from 0) and the share of its region settled. A triggered interrupt stops before the next
/// variation.
pub fn run(req: &LayoutRequest, progress: &mut dyn FnMut(usize, f64)) -> Result<Vec<Layout>, LayoutError> {
    req.validate()?;
    let region = super::region::read_region(&req.region)?;
    let seed = req.seed.unwrap_or(region.seed);
    let mut out = Vec::new();
    for k in 0..req.variations.max(1) {
        if k > 0 && req.interrupt.as_ref().is_some_and(Interrupt::is_triggered) {
            break;
        }
        let selection = if k == 0 { req.selection } else { Selection::Random };
        let opts = LayoutOptions { field: req.field, selection, seed: seed + k as u64, optimise: req.optimise };
        let l = match &req.relayout {
            Some((from, part)) => relayout_with_progress(&region, from, part, &opts, &mut |f| progress(k, f))?,
            None => layout_with_progress(&region, &opts, &mut |f| progress(k, f))?,
        };
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
/// with a few of its streamline candidates drawn over it. `h` is the triangle size in metres
/// (default: the layout's), refused unless positive ([`check_field_h`]).
pub fn field_command(
    region: &Path,
    method: FieldMethod,
    h: Option<f64>,
    out: &Path,
) -> Result<super::field::CrossField, LayoutError> {
    check_field_h(h)?;
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
    let plain = Finished::new(region, g.clone(), split_streets, &mut matcher, opts.selection, &mut rng);
    let (done, optimisation) = if opts.optimise > 0 {
        let mut moved = g;
        match_leaves(&mut moved, &optimised, region, &mut matcher, true);
        let after = Finished::new(region, moved, optimised, &mut matcher, opts.selection, &mut rng);
        let mut o = Optimisation {
            iterations: opts.optimise,
            kept: true,
            registration_before: plain.metrics.similarity_mean,
            registration_after: after.metrics.similarity_mean,
        };
        if !after.violations.is_empty() && plain.violations.is_empty() {
            o.kept = false;
            (plain, o)
        } else {
            (after, o)
        }
    } else {
        (plain, Optimisation { iterations: 0, kept: false, registration_before: None, registration_after: None })
    };
    let times = Times {
        split: (t1 - t0).as_secs_f64(),
        matching,
        backtracking: done.assign_seconds,
        optimise: (t2 - t1).as_secs_f64(),
        parcels: done.parcel_seconds,
        check: done.check_seconds,
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
        optimisation,
        counts: counts(region, &done.templates),
        relayout: None,
        unmet: done.unmet,
        templates: done.templates,
        settings: Settings::of(region),
        times,
    })
}

/// The templates with a minimum or maximum, with their uses.
fn counts(region: &Region, uses: &std::collections::BTreeMap<String, usize>) -> Vec<Count> {
    region
        .templates
        .iter()
        .filter(|t| t.min_uses > 0 || t.max_uses.is_some())
        .map(|t| Count {
            template: t.name.clone(),
            min: t.min_uses,
            max: t.max_uses,
            used: uses.get(&t.name).copied().unwrap_or(0),
        })
        .collect()
}

/// Lays out part `part` of the layout in `from` again with everything else kept (`--relayout`):
/// its streets and parcels are dropped, the part is grown again among the kept streets (the
/// region's zones inside it set apart), its leaves take templates with the kept uses counted,
/// and its new subtree replaces the old one in `parts`.
pub fn relayout_with_progress(
    region: &Region,
    from: &Path,
    part: &str,
    opts: &LayoutOptions,
    progress: &mut dyn FnMut(f64),
) -> Result<Layout, LayoutError> {
    use super::relayout::{leaf_ids, read, replace, uses_outside, within};
    let r = read(from, part)?;
    let kept_streets: Vec<Street> = r.file.streets.iter().filter(|s| !within(&s.part, part)).cloned().collect();
    let kept_parcels: Vec<Parcel> = r.file.parcels.iter().filter(|p| !within(&p.part, part)).cloned().collect();
    let used = uses_outside(&r.file.parts, part);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(opts.seed);
    let t0 = Instant::now();
    let split_opts = SplitOptions::for_region(region, opts.field, opts.selection);
    let mut matcher = Matcher::new(&region.templates, region);
    let first = region.templates_first.then_some(&mut matcher);
    let root = super::tree::Node::new(part.to_string(), r.level, &r.label, r.polygon.clone());
    let mut g = super::tree::grow_part(region, &split_opts, first, root, kept_streets, &mut rng, progress)?;
    let mut streets: Vec<Street> =
        g.streets.iter().map(|st| Street { polyline: round(&st.polyline), ..st.clone() }).collect();
    match_leaves(&mut g, &streets, region, &mut matcher, false);
    let matching = matcher.seconds;
    let t1 = Instant::now();
    let p = parcel_leaves(region, &mut g, &streets, &mut matcher, &used, opts.selection, &mut rng);
    streets.extend(p.streets.into_iter().map(|st| Street { polyline: round(&st.polyline), ..st }));
    let mut parcels = kept_parcels;
    parcels.extend(p.parcels.into_iter().map(rounded_parcel));
    let parts = replace(&r.file.parts, &g.tree(0));
    let mut leaves = std::collections::BTreeSet::new();
    leaf_ids(&parts, &mut leaves);
    // The blocks of the split, as a fresh layout measures them: template streets left out.
    let split_only: Vec<Street> = streets.iter().filter(|s| !leaves.contains(&s.part)).cloned().collect();
    let bl = blocks(&region.polygon, &split_only);
    let t2 = Instant::now();
    let metrics = metrics(&region.polygon, &streets, &bl, &parcels);
    let violations = validate(&region.polygon, &streets, &parcels);
    let templates = uses_outside(&parts, "");
    let by_template = count_leaves(&parts, How::Template);
    let times = Times {
        split: (t1 - t0).as_secs_f64(),
        matching,
        backtracking: p.seconds,
        optimise: 0.0,
        parcels: (t2 - t1).as_secs_f64(),
        check: t2.elapsed().as_secs_f64(),
    };
    Ok(Layout {
        name: region.name.clone(),
        seed: opts.seed,
        field: opts.field,
        selection: opts.selection,
        outer: region.polygon.outer().to_vec(),
        origin: region.projection.as_ref().map(|p| p.origin()),
        holes: region.polygon.holes().to_vec(),
        split: SplitCounts {
            candidates: g.candidates,
            cuts: g.cuts,
            blocks: bl.len(),
            leaves: leaves.len(),
            by_template,
        },
        parts,
        streets,
        parcels,
        metrics,
        violations,
        optimisation: Optimisation { iterations: 0, kept: false, registration_before: None, registration_after: None },
        counts: counts(region, &templates),
        unmet: p.unmet,
        relayout: Some(part.to_string()),
        templates,
        settings: Settings::of(region),
        times,
    })
}

/// The leaves of a tree settled one way.
fn count_leaves(t: &PartTree, how: How) -> usize {
    if t.children.is_empty() {
        usize::from(t.how == how)
    } else {
        t.children.iter().map(|c| count_leaves(c, how)).sum()
    }
}

/// Streets with their blocks, parcels (every leaf by its template, or by the row parceller),
/// metrics and check.
struct Finished {
    grown: Grown,
    streets: Vec<Street>,
    parcels: Vec<Parcel>,
    templates: std::collections::BTreeMap<String, usize>,
    unmet: Vec<Unmet>,
    blocks: usize,
    metrics: Metrics,
    violations: Vec<Violation>,
    parcel_seconds: f64,
    assign_seconds: f64,
    check_seconds: f64,
}

impl Finished {
    fn new(
        region: &Region,
        mut grown: Grown,
        mut streets: Vec<Street>,
        matcher: &mut Matcher,
        selection: Selection,
        rng: &mut Xoshiro256PlusPlus,
    ) -> Finished {
        let t = Instant::now();
        let blocks = blocks(&region.polygon, &streets);
        let p = parcel_leaves(region, &mut grown, &streets, matcher, &Default::default(), selection, rng);
        streets.extend(p.streets.into_iter().map(|st| Street { polyline: round(&st.polyline), ..st }));
        let parcels: Vec<Parcel> = p.parcels.into_iter().map(rounded_parcel).collect();
        let parcel_seconds = t.elapsed().as_secs_f64();
        let metrics = metrics(&region.polygon, &streets, &blocks, &parcels);
        let violations = validate(&region.polygon, &streets, &parcels);
        let check_seconds = t.elapsed().as_secs_f64() - parcel_seconds;
        Finished {
            grown,
            streets,
            parcels,
            templates: p.uses,
            unmet: p.unmet,
            blocks: blocks.len(),
            metrics,
            violations,
            parcel_seconds,
            assign_seconds: p.seconds,
            check_seconds,
        }
    }
}

/// What the leaves are parcelled into.
struct LeafParcels {
    parcels: Vec<Parcel>,
    streets: Vec<Street>,
    uses: std::collections::BTreeMap<String, usize>,
    unmet: Vec<Unmet>,
    /// Seconds of the assignment.
    seconds: f64,
}

/// The parcels of every leaf — by the template the assignment chose for it (with its counts met
/// by backtracking), or by the row parceller — and the template streets; every leaf's node records
/// its template, energy and nested area templates.
fn parcel_leaves(
    region: &Region,
    g: &mut Grown,
    streets: &[Street],
    matcher: &mut Matcher,
    used: &std::collections::BTreeMap<String, usize>,
    selection: Selection,
    rng: &mut Xoshiro256PlusPlus,
) -> LeafParcels {
    let lib = &region.templates;
    let index = StreetIndex::new(streets);
    let ctx = PlaceContext::new(streets, region);
    let mut order: Vec<usize> = (0..g.leaves.len()).collect();
    order.sort_by(|&a, &b| {
        block_key(&g.leaves[a]).partial_cmp(&block_key(&g.leaves[b])).unwrap_or(std::cmp::Ordering::Equal)
    });
    let t0 = Instant::now();
    let slots = order
        .iter()
        .map(|&k| {
            let l = &g.leaves[k];
            l.block.clone().filter(|_| !l.options.is_empty()).map(|b| (b, l.options.clone()))
        })
        .collect();
    let ctx_a = Context { used, index: &index, merge: region.parcel.depth / 3.0 };
    let a = assign(slots, matcher, &ctx_a, selection, rng);
    let seconds = t0.elapsed().as_secs_f64();
    let mut per_leaf: Vec<(Vec<Parcel>, Vec<Street>)> = vec![(Vec::new(), Vec::new()); g.leaves.len()];
    for (choice, &k) in a.parts.iter().zip(&order) {
        let leaf = &g.leaves[k];
        let node = &mut g.nodes[leaf.node];
        match choice {
            Some(ch) => {
                let (mut parcels, new_streets) = choice_parcels(ch, lib, &ctx, &index, &node.id);
                for b in leaf.blocks.iter().skip(1) {
                    parcels.extend(fallback(b, &index, region, &node.id).0);
                }
                node.how = How::Template;
                node.template = Some(lib[ch.candidate.template].name.clone());
                node.score = Some(ch.candidate.warp.energy);
                node.nested = nested(ch, lib);
                per_leaf[k] = (parcels, new_streets);
            }
            None => {
                node.template = None;
                node.score = None;
                node.nested = Vec::new();
                per_leaf[k].0 = match super::zone::ZoneUse::from_label(&node.label) {
                    Some(z) => {
                        node.how = How::Zone;
                        let whole =
                            |b: &Shape| Parcel { part: node.id.clone(), ..Parcel::new(b.ring(), z.parcel_use()) };
                        leaf.blocks.iter().map(whole).collect()
                    }
                    None => {
                        let mut how = How::Rows;
                        let mut parcels = Vec::new();
                        for b in &leaf.blocks {
                            let (p, h) = fallback(b, &index, region, &node.id);
                            parcels.extend(p);
                            if h == How::Skeleton {
                                how = h;
                            }
                        }
                        node.how = how;
                        parcels
                    }
                };
            }
        }
    }
    let (parcels, new_streets): (Vec<Vec<Parcel>>, Vec<Vec<Street>>) = per_leaf.into_iter().unzip();
    LeafParcels { parcels: parcels.concat(), streets: new_streets.concat(), uses: a.uses, unmet: a.unmet, seconds }
}

/// The area templates in a choice, depth first.
fn nested(ch: &Choice, lib: &[super::template::Template]) -> Vec<String> {
    ch.areas
        .iter()
        .filter_map(|(_, c)| c.as_deref())
        .flat_map(|c| std::iter::once(lib[c.candidate.template].name.clone()).chain(nested(c, lib)))
        .collect()
}

/// The fallback's parcels of one block where no template is accepted ([`super::fallback`]).
fn fallback(b: &Shape, index: &StreetIndex, region: &Region, part: &str) -> (Vec<Parcel>, How) {
    super::fallback::parcel_block(b, index, region.parcel.depth, region.parcel.width, part)
}

/// Leaves with the largest block first (ties by the block's first vertex).
fn block_key(l: &super::tree::Leaf) -> (f64, i64, i64) {
    l.blocks.first().map_or((0.0, 0, 0), |b| {
        let c = b.rings()[0].first().map_or((0, 0), |c| ((c[0] * 1e3).round() as i64, (c[1] * 1e3).round() as i64));
        (-(b.area() * 1e3).round(), c.0, c.1)
    })
}

/// A parcel with its coordinates and registration rounded to the millimetre, its ideal area to
/// the square centimetre.
fn rounded_parcel(p: Parcel) -> Parcel {
    Parcel {
        polygon: round(&p.polygon),
        registration: p.registration.map(|r| (r * 1000.0).round() / 1000.0),
        ideal: p.ideal.map(|a| (a * 100.0).round() / 100.0),
        ..p
    }
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
    let sc = scene(region, layout);
    let svg = layout_svg(&sc);
    write("layout.svg", svg.as_bytes())?;
    write("layout.png", &crate::render::png(&svg)?)?;
    let m = &layout.metrics;
    let reg = registration_svg(&LayoutScene {
        caption: match m.similarity_mean {
            Some(d) => format!(
                "{}: {} template parcels by registration distance to their ideal, 0 (blue) to 5 m (red); mean {d:.3} m",
                layout.name, m.template_parcels
            ),
            None => format!("{}: no template parcels", layout.name),
        },
        ..sc
    });
    write("registration.svg", reg.as_bytes())?;
    write("registration.png", &crate::render::png(&reg)?)?;
    let h = &m.histograms;
    let panel = |title: &str, h: &super::metrics::Histogram| HistogramPanel {
        title: title.to_string(),
        edges: h.edges.clone(),
        counts: h.counts.clone(),
    };
    let hist = histograms_svg(
        &[
            panel("parcel area (m²)", &h.area),
            panel("mean corner deviation (°)", &h.corner_deviation),
            panel("registration distance (m)", &h.registration),
        ],
        &format!("{}: {} parcels ({} from templates)", layout.name, m.parcels, m.template_parcels),
    );
    write("histograms.svg", hist.as_bytes())?;
    write("histograms.png", &crate::render::png(&hist)?)?;
    if let Some(proj) = &region.projection {
        write("layout.geojson", geojson(proj, layout)?.as_bytes())?;
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
                registration: p.registration,
            })
            .collect(),
        streets: layout.streets.iter().map(|s| (s.polyline.clone(), s.width, s.level)).collect(),
        caption: format!(
            "{}: {} parcels ({} undesirable), corners {:.1}° off, area ratio {:.3}, streets {:.1} %",
            layout.name, m.parcels, m.undesirable, m.corner_deviation_mean, m.area_ratio_mean, m.land_use.streets
        ),
    }
}

/// The streets and parcels in WGS 84 ([`GeoJsonWriter`]).
fn geojson(proj: &crate::geometry::site::Projection, layout: &Layout) -> Result<String, LayoutError> {
    let mut w = GeoJsonWriter::new(proj);
    for s in &layout.streets {
        w.line(&s.polyline, serde_json::json!({"kind": "street", "level": s.level, "width": s.width}))?;
    }
    for p in &layout.parcels {
        w.polygon([p.polygon.as_slice()], serde_json::json!({"kind": "parcel", "use": p.use_}))?;
    }
    Ok(w.to_json(serde_json::Value::Null))
}
