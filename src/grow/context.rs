//! The historical context file (TOML): the map, its terrain and water, the cities, and the time
//! table of the growth parameters. Every key but `size` has a default (the paper's where it gives
//! one, else netspec's, docs/grow.md); unknown keys are refused and every error names its field
//! (`water[1].river`).

use super::GrowError;
use crate::geometry::{polyline_length, ring_area2, P};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// Bytes of working memory per lattice vertex (terrain, classes, built-up raster, the search's
/// distance, predecessor and heap share): the basis of the up-front memory check.
pub const BYTES_PER_VERTEX: u64 = 48;
/// The largest working memory a map may need (8 GiB).
pub const MAX_BYTES: u64 = 8 << 30;

/// How far outside the map a `[[road]]` point may lie and still be taken as on its edge
/// (metres): the road graph's snap, for coordinates clipped to the map in floating point.
pub const ROAD_EDGE_SLACK: f64 = 0.5;

/// A historical context with its per-city input.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Context {
    /// Map width and height (metres); the map is `[0, W] × [0, H]`.
    pub size: [f64; 2],
    /// Lattice spacing ℓ (metres).
    #[serde(default = "d_spacing")]
    pub spacing: f64,
    /// Lattice edge radius r (land edges join vertices up to r steps apart along each axis).
    #[serde(default = "d_radius")]
    pub radius: u32,
    /// Seed of every random choice.
    #[serde(default = "d_seed")]
    pub seed: u64,
    /// Time steps after the initial network.
    #[serde(default = "d_steps")]
    pub steps: u32,
    /// WGS 84 `[lon, lat]` of the map's origin `(0, 0)`: with it, `network.geojson` is written.
    #[serde(default)]
    pub origin: Option<[f64; 2]>,
    /// The centre settlement (default: the map's centre).
    #[serde(default)]
    pub center: Option<Center>,
    /// Neighbouring cities by position (moved to the nearest free border vertex).
    #[serde(default)]
    pub neighbour: Vec<Neighbour>,
    /// Or their number, placed on rays from the centre (§3.5); drawn as 4 + Binomial(6, ½) when
    /// neither is given.
    #[serde(default)]
    pub neighbours: Option<u32>,
    /// Water: polygons (lakes, sea) and rivers (polylines with a width).
    #[serde(default)]
    pub water: Vec<Water>,
    /// Forbidden areas (no roads).
    #[serde(default)]
    pub forbidden: Vec<Forbidden>,
    /// Existing roads the growth starts from (part of the initial network).
    #[serde(default)]
    pub road: Vec<Road>,
    /// Growth nuclei placed by the user, each from its step on.
    #[serde(default)]
    pub nucleus: Vec<NucleusSpec>,
    /// The terrain.
    #[serde(default)]
    pub terrain: Terrain,
    /// The time table and coefficients.
    #[serde(default)]
    pub params: Params,
    /// The minor-road patterns K(t), each from its `from` step on (default: organic, then radial
    /// from step 50, grid from step 100).
    #[serde(default = "d_patterns")]
    pub pattern: Vec<Pattern>,
    /// The directory relative paths (`terrain.file`) are read from.
    #[serde(skip)]
    pub base: PathBuf,
}

/// The city's centre: with it, the initial network joins every neighbouring city to this
/// point, and the centre nucleus sits there.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Center {
    /// Its position (metres).
    pub position: P,
}

/// An existing road: a polyline in map metres, inserted into the road graph before the initial
/// network is built (docs/grow.md, "Existing roads").
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Road {
    /// Its points (metres, within the map; at least two).
    pub points: Vec<P>,
    /// `major` (a trade road) or `minor` (a street).
    #[serde(default = "d_road_class")]
    pub class: RoadClass,
    /// Kept as given: never widened, never made major.
    #[serde(default)]
    pub fixed: bool,
    /// Lanes (default: A(0) for a major road, 1 for a minor one).
    #[serde(default)]
    pub lanes: Option<f64>,
}

/// The class of an existing road.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum RoadClass {
    /// A major road (carries trade).
    Major,
    /// A minor road (a street).
    Minor,
}

/// A growth nucleus placed by the user.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct NucleusSpec {
    /// Its position (metres, on land).
    pub position: P,
    /// STRENGTH(q) ∈ (0, 1].
    pub strength: f64,
    /// The step it appears in (0: with the initial network).
    #[serde(default)]
    pub from: u32,
}

/// A neighbouring city.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Neighbour {
    /// Its position (metres); the nearest border vertex not forbidden is used.
    pub position: P,
}

/// A water body: a polygon, or a river polyline with a width.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Water {
    /// A lake or sea outline.
    #[serde(default)]
    pub polygon: Option<Vec<P>>,
    /// A river's centre line.
    #[serde(default)]
    pub river: Option<Vec<P>>,
    /// The river's width (metres).
    #[serde(default)]
    pub width: Option<f64>,
}

/// A forbidden area.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Forbidden {
    /// Its outline.
    pub polygon: Vec<P>,
}

/// The terrain: an ESRI ASCII grid file, or a seeded generated heightmap.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Terrain {
    /// An ESRI ASCII grid (`ncols`, `nrows`, `xllcorner`, `yllcorner`, `cellsize`, rows from the
    /// north), relative to the context file; its lower-left corner is the map's origin.
    #[serde(default)]
    pub file: Option<PathBuf>,
    /// Generated terrain: elevation range (metres).
    #[serde(default = "d_relief")]
    pub relief: f64,
    /// Generated terrain: the size of the largest hills (metres).
    #[serde(default = "d_scale")]
    pub scale: f64,
}

impl Default for Terrain {
    fn default() -> Self {
        Terrain { file: None, relief: d_relief(), scale: d_scale() }
    }
}

/// Coefficients and the time table (docs/grow.md lists the defaults).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Params {
    /// Reuse coefficient μ ∈ (0, 1) of the initial paths (default: drawn from U(0.5, 0.9)).
    #[serde(default)]
    pub mu: Option<f64>,
    /// Traffic scale b (default: drawn from U(0.7, 1.3)).
    #[serde(default)]
    pub b: Option<f64>,
    /// Traffic units per growth seed: t(t) = b · demand · G(t).
    #[serde(default = "d_demand")]
    pub demand: f64,
    /// Steepest grade of a road (rise over run).
    #[serde(default = "d_slope_cut")]
    pub slope_cut: f64,
    /// O₁ (slope weight), O₂ (capacity per lane), O₃ (length weight), O₄ (cost weight).
    #[serde(default = "d_o")]
    pub o: [f64; 4],
    /// C₁…C₆: major, minor, unbuilt harbour, built harbour, unbuilt bridge, extendible; fixed
    /// or by era.
    #[serde(default = "d_c")]
    pub c: Eras<6>,
    /// G(t): minor-road seeds per step, `[[t, G], …]`, linear in between.
    #[serde(default = "d_growth")]
    pub growth: Vec<[f64; 2]>,
    /// A(t): lanes of new major roads, `[[t, A], …]`, each from its step on.
    #[serde(default = "d_widths")]
    pub widths: Vec<[f64; 2]>,
    /// The turn penalty P(α): centre and width (degrees; α = 180° is straight on) and height
    /// (metres of equivalent length); fixed or by era.
    #[serde(default = "d_turn")]
    pub turn: Eras<3>,
    /// The most lanes widening gives a road.
    #[serde(default = "d_max_lanes")]
    pub max_lanes: f64,
    /// The probability that a pair removed from the initial network's list is added back to the
    /// pairs whose roads are built (§3.5's variation).
    #[serde(default = "d_add_back")]
    pub add_back: f64,
    /// The largest built-up block (m²); larger faces are terrain blocks.
    #[serde(default = "d_block_area")]
    pub block_area: f64,
    /// Width of the built-up neighbourhood NB of block outlines (metres).
    #[serde(default = "d_nb")]
    pub nb: f64,
    /// Longest stitch from the road graph to the terrain lattice (metres).
    #[serde(default = "d_stitch")]
    pub stitch: f64,
    /// Longest water span of a bridge (metres).
    #[serde(default = "d_bridge")]
    pub bridge: f64,
    /// Smallest settlement (m² of built-up area).
    #[serde(default = "d_settlement")]
    pub settlement: f64,
    /// Strength cap of the centre nucleus for ranking (1 − ε).
    #[serde(default = "d_center_strength")]
    pub center_strength: f64,
}

impl Default for Params {
    fn default() -> Self {
        toml::from_str("").expect("the defaults deserialise")
    }
}

/// Coefficients that change by era: `[a, b, …]` for all time, or `[[t, [a, b, …]], …]`, each
/// entry from its step `t` on (the first also before it).
#[derive(Clone, Debug, PartialEq)]
pub struct Eras<const N: usize> {
    /// `(t, values)` in increasing `t`.
    pub table: Vec<(f64, [f64; N])>,
}

impl<const N: usize> Eras<N> {
    /// The same values for all time.
    pub fn fixed(v: [f64; N]) -> Eras<N> {
        Eras { table: vec![(0.0, v)] }
    }

    /// The values at step `t`: the last entry whose step is at most `t`, else the first.
    pub fn at(&self, t: u32) -> [f64; N] {
        self.table.iter().rev().find(|e| e.0 <= t as f64).unwrap_or(&self.table[0]).1
    }
}

impl<'de, const N: usize> Deserialize<'de> for Eras<N> {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let expected = || {
            let names = (1..=N).map(|i| format!("v{i}")).collect::<Vec<_>>().join(", ");
            D::Error::custom(format!("expected [{names}] or [[step, [{names}]], …] ({N} numbers per entry)"))
        };
        let v = toml::Value::deserialize(d)?;
        let number = |x: &toml::Value| x.as_float().or_else(|| x.as_integer().map(|i| i as f64));
        let values = |x: &toml::Value| -> Option<[f64; N]> {
            let a = x.as_array()?;
            let v: Vec<f64> = a.iter().map(number).collect::<Option<_>>()?;
            v.try_into().ok()
        };
        if let Some(v) = values(&v) {
            return Ok(Eras::fixed(v));
        }
        let entries = v.as_array().ok_or_else(expected)?;
        let mut table = Vec::new();
        for e in entries {
            let pair = e.as_array().filter(|p| p.len() == 2).ok_or_else(expected)?;
            let t = number(&pair[0]).ok_or_else(expected)?;
            table.push((t, values(&pair[1]).ok_or_else(expected)?));
        }
        if table.is_empty() {
            return Err(expected());
        }
        Ok(Eras { table })
    }
}

/// A minor-road pattern of K(t).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Pattern {
    /// The first step it applies to.
    pub from: u32,
    /// `organic`, `grid` or `radial`.
    pub kind: PatternKind,
    /// Mean segment length (metres).
    #[serde(default = "d_length")]
    pub length: f64,
    /// Relative length jitter.
    #[serde(default = "d_jitter")]
    pub jitter: f64,
    /// Heading jitter σ (degrees; organic).
    #[serde(default = "d_heading")]
    pub heading: f64,
    /// Segments per street.
    #[serde(default = "d_segments")]
    pub segments: u32,
    /// Probability of a ±90° branch after each segment (grid).
    #[serde(default)]
    pub branch: f64,
    /// Snap distance to nodes and segments (metres).
    #[serde(default = "d_snap")]
    pub snap: f64,
    /// Smallest angle between streets at a junction (degrees).
    #[serde(default = "d_min_angle")]
    pub min_angle: f64,
    /// How far past its end a street looks for a road to extend to (metres; 0: never).
    #[serde(default = "d_extend")]
    pub extend: f64,
    /// A grid's orientation (degrees from the x axis; default: the direction of the major road
    /// nearest to the nearest nucleus).
    #[serde(default)]
    pub angle: Option<f64>,
}

/// The street pattern kinds.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum PatternKind {
    /// Curving streets (heading jitter).
    Organic,
    /// Straight streets and right-angle branches.
    Grid,
    /// Along or across the direction to the nearest nucleus, whichever is nearer the street's
    /// base heading.
    Radial,
}

fn d_road_class() -> RoadClass {
    RoadClass::Major
}
fn d_spacing() -> f64 {
    20.0
}
fn d_radius() -> u32 {
    8
}
fn d_seed() -> u64 {
    1
}
fn d_steps() -> u32 {
    100
}
fn d_relief() -> f64 {
    30.0
}
fn d_scale() -> f64 {
    2000.0
}
fn d_demand() -> f64 {
    0.25
}
fn d_slope_cut() -> f64 {
    0.15
}
fn d_o() -> [f64; 4] {
    [20.0, 30.0, 1.0, 1.0]
}
fn d_c() -> Eras<6> {
    Eras::fixed([0.3, 1.5, 20.0, 2.0, 5.0, 0.6])
}
fn d_max_lanes() -> f64 {
    4.0
}
fn d_add_back() -> f64 {
    0.25
}
fn d_growth() -> Vec<[f64; 2]> {
    vec![[0.0, 10.0], [150.0, 60.0]]
}
fn d_widths() -> Vec<[f64; 2]> {
    vec![[0.0, 1.0], [60.0, 2.0]]
}
fn d_turn() -> Eras<3> {
    Eras::fixed([108.0, 72.0, 200.0])
}
fn d_block_area() -> f64 {
    50_000.0
}
fn d_nb() -> f64 {
    20.0
}
fn d_stitch() -> f64 {
    40.0
}
fn d_bridge() -> f64 {
    400.0
}
fn d_settlement() -> f64 {
    20_000.0
}
fn d_center_strength() -> f64 {
    0.95
}
fn d_length() -> f64 {
    40.0
}
fn d_jitter() -> f64 {
    0.2
}
fn d_heading() -> f64 {
    20.0
}
fn d_segments() -> u32 {
    4
}
fn d_snap() -> f64 {
    12.0
}
fn d_min_angle() -> f64 {
    30.0
}
fn d_extend() -> f64 {
    20.0
}
fn d_patterns() -> Vec<Pattern> {
    let p = |from, kind, length, branch| Pattern {
        from,
        kind,
        length,
        jitter: d_jitter(),
        heading: d_heading(),
        segments: d_segments(),
        branch,
        snap: d_snap(),
        min_angle: d_min_angle(),
        extend: d_extend(),
        angle: None,
    };
    vec![
        p(0, PatternKind::Organic, 40.0, 0.0),
        p(50, PatternKind::Radial, 60.0, 0.0),
        p(100, PatternKind::Grid, 80.0, 0.4),
    ]
}

impl Context {
    /// Reads and checks a context file.
    pub fn load(path: &Path) -> Result<Context, GrowError> {
        let text =
            std::fs::read_to_string(path).map_err(|source| GrowError::Io { path: path.to_path_buf(), source })?;
        let mut ctx = Context::from_toml(&text).map_err(|e| e.in_file(path))?;
        ctx.base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Ok(ctx)
    }

    /// Parses and checks TOML text (relative paths from the working directory).
    pub fn from_toml(text: &str) -> Result<Context, GrowError> {
        let value: toml::Value =
            toml::from_str(text).map_err(|e| GrowError::Toml { path: PathBuf::new(), message: e.to_string() })?;
        let ctx: Context = serde_path_to_error::deserialize(value).map_err(|e| {
            let field = e.path().to_string();
            GrowError::Field { path: PathBuf::new(), field, message: e.into_inner().to_string() }
        })?;
        ctx.check()?;
        Ok(ctx)
    }

    /// Lattice vertices along x and y.
    pub fn dims(&self) -> [usize; 2] {
        [(self.size[0] / self.spacing).floor() as usize + 1, (self.size[1] / self.spacing).floor() as usize + 1]
    }

    /// The working memory the map needs (bytes, estimated).
    pub fn memory_estimate(&self) -> u64 {
        let [nx, ny] = self.dims();
        (nx as u64).saturating_mul(ny as u64).saturating_mul(BYTES_PER_VERTEX)
    }

    /// The centre's position.
    pub fn center_position(&self) -> P {
        self.center.as_ref().map(|c| c.position).unwrap_or([self.size[0] / 2.0, self.size[1] / 2.0])
    }

    /// G(t), linear between the table's entries.
    pub fn growth(&self, t: u32) -> f64 {
        linear(&self.params.growth, t as f64)
    }

    /// A(t), each entry from its step on.
    pub fn width(&self, t: u32) -> f64 {
        let w = &self.params.widths;
        w.iter().rev().find(|e| e[0] <= t as f64).unwrap_or(&w[0])[1]
    }

    /// C₁…C₆ at step `t`.
    pub fn c(&self, t: u32) -> [f64; 6] {
        self.params.c.at(t)
    }

    /// The turn penalty's centre, width (degrees) and height (metres) at step `t`.
    pub fn turn(&self, t: u32) -> [f64; 3] {
        self.params.turn.at(t)
    }

    /// K(t): the last pattern whose `from` is at most `t`.
    pub fn pattern(&self, t: u32) -> &Pattern {
        self.pattern.iter().rev().find(|p| p.from <= t).unwrap_or(&self.pattern[0])
    }

    fn check(&self) -> Result<(), GrowError> {
        let bad =
            |field: &str, message: String| Err(GrowError::Field { path: PathBuf::new(), field: field.into(), message });
        let pos = |x: f64| x.is_finite() && x > 0.0;
        if !(pos(self.size[0]) && pos(self.size[1])) {
            return bad("size", format!("must be two positive lengths in metres, got {:?}", self.size));
        }
        if !pos(self.spacing) {
            return bad("spacing", format!("must be a positive length, got {}", self.spacing));
        }
        if !(1..=16).contains(&self.radius) {
            return bad("radius", format!("must be 1 to 16, got {}", self.radius));
        }
        let [nx, ny] = self.dims();
        if nx < 8 || ny < 8 {
            return bad("spacing", format!("gives a {nx} × {ny} lattice; at least 8 × 8 vertices are needed"));
        }
        let need = self.memory_estimate();
        if need > MAX_BYTES || (nx as u64) * (ny as u64) >= u32::MAX as u64 / 2 {
            return bad(
                "size",
                format!(
                    "a {nx} × {ny} lattice needs about {:.1} GiB of memory ({BYTES_PER_VERTEX} B per vertex); at most {} GiB: use a coarser `spacing` or a smaller map",
                    need as f64 / (1u64 << 30) as f64,
                    MAX_BYTES >> 30
                ),
            );
        }
        let inside = |p: P| {
            p.iter().all(|v| v.is_finite())
                && (0.0..=self.size[0]).contains(&p[0])
                && (0.0..=self.size[1]).contains(&p[1])
        };
        if let Some(c) = &self.center {
            if !inside(c.position) {
                return bad("center.position", format!("{:?} is outside the map", c.position));
            }
        }
        if let Some(o) = self.origin {
            if !((-180.0..=180.0).contains(&o[0]) && (-85.0..=85.0).contains(&o[1])) {
                return bad("origin", format!("{o:?} is not a WGS 84 [lon, lat]"));
            }
        }
        for (i, n) in self.neighbour.iter().enumerate() {
            if !inside(n.position) {
                return bad(&format!("neighbour[{i}].position"), format!("{:?} is outside the map", n.position));
            }
        }
        if let Some(n) = self.neighbours {
            if !self.neighbour.is_empty() {
                return bad("neighbours", "give either `neighbours = N` or `[[neighbour]]` tables, not both".into());
            }
            if !(2..=32).contains(&n) {
                return bad("neighbours", format!("must be 2 to 32, got {n}"));
            }
        }
        if self.neighbour.len() == 1 {
            return bad("neighbour", "at least two neighbouring cities are needed for a trade route".into());
        }
        for (i, w) in self.water.iter().enumerate() {
            match (&w.polygon, &w.river) {
                (Some(_), Some(_)) | (None, None) => {
                    return bad(&format!("water[{i}]"), "give exactly one of `polygon` and `river`".into())
                }
                (Some(poly), None) => {
                    if w.width.is_some() {
                        return bad(&format!("water[{i}].width"), "only a river has a width".into());
                    }
                    if poly.len() < 3
                        || ring_area2(poly).abs() <= 0.0
                        || poly.iter().any(|p| !p.iter().all(|v| v.is_finite()))
                    {
                        return bad(
                            &format!("water[{i}].polygon"),
                            "must be a ring of at least 3 finite points enclosing an area".into(),
                        );
                    }
                }
                (None, Some(line)) => {
                    if line.len() < 2
                        || polyline_length(line) <= 0.0
                        || line.iter().any(|p| !p.iter().all(|v| v.is_finite()))
                    {
                        return bad(
                            &format!("water[{i}].river"),
                            "must be a polyline of at least 2 distinct finite points".into(),
                        );
                    }
                    match w.width {
                        Some(x) if pos(x) => {}
                        Some(x) => return bad(&format!("water[{i}].width"), format!("must be positive, got {x}")),
                        None => return bad(&format!("water[{i}].width"), "a river needs a width (metres)".into()),
                    }
                }
            }
        }
        self.check_roads()?;
        for (i, n) in self.nucleus.iter().enumerate() {
            if !inside(n.position) {
                return bad(&format!("nucleus[{i}].position"), format!("{:?} is outside the map", n.position));
            }
            if !(n.strength > 0.0 && n.strength <= 1.0) {
                return bad(&format!("nucleus[{i}].strength"), format!("must be in (0, 1], got {}", n.strength));
            }
        }
        for (i, f) in self.forbidden.iter().enumerate() {
            if f.polygon.len() < 3 || ring_area2(&f.polygon).abs() <= 0.0 {
                return bad(
                    &format!("forbidden[{i}].polygon"),
                    "must be a ring of at least 3 points enclosing an area".into(),
                );
            }
        }
        if !(self.terrain.relief.is_finite() && self.terrain.relief >= 0.0) {
            return bad("terrain.relief", format!("must be a non-negative height, got {}", self.terrain.relief));
        }
        if !pos(self.terrain.scale) {
            return bad("terrain.scale", format!("must be a positive length, got {}", self.terrain.scale));
        }
        self.check_params()?;
        if self.pattern.is_empty() {
            return bad("pattern", "at least one minor-road pattern is needed".into());
        }
        for (i, p) in self.pattern.iter().enumerate() {
            let f = |k: &str| format!("pattern[{i}].{k}");
            if !pos(p.length) {
                return bad(&f("length"), format!("must be positive, got {}", p.length));
            }
            if !(0.0..1.0).contains(&p.jitter) {
                return bad(&f("jitter"), format!("must be in [0, 1), got {}", p.jitter));
            }
            if !(0.0..=1.0).contains(&p.branch) {
                return bad(&f("branch"), format!("must be a probability, got {}", p.branch));
            }
            if !(1..=50).contains(&p.segments) {
                return bad(&f("segments"), format!("must be 1 to 50, got {}", p.segments));
            }
            if !(p.extend.is_finite() && p.extend >= 0.0) {
                return bad(&f("extend"), format!("must be a length ≥ 0, got {}", p.extend));
            }
            if p.angle.is_some_and(|a| !a.is_finite()) {
                return bad(&f("angle"), "must be a finite angle in degrees".into());
            }
            let ok = p.snap.is_finite()
                && p.snap >= 0.0
                && (0.0..90.0).contains(&p.min_angle)
                && p.heading.is_finite()
                && p.heading >= 0.0;
            if !ok {
                return bad(&f("snap"), "snap ≥ 0, heading ≥ 0 and min_angle in [0, 90) are needed".into());
            }
            if i > 0 && p.from <= self.pattern[i - 1].from {
                return bad(&f("from"), "patterns must be in increasing `from` order".into());
            }
        }
        Ok(())
    }

    /// The `[[road]]` checks that need no terrain: at least two finite, distinct points, each
    /// within the map (or at most [`ROAD_EDGE_SLACK`] outside it, moved onto the edge when the
    /// road is inserted), positive lanes. Water and forbidden ground are checked against the
    /// lattice when the roads are inserted ([`super::roads`]).
    fn check_roads(&self) -> Result<(), GrowError> {
        let bad = |field: String, message: String| Err(GrowError::Field { path: PathBuf::new(), field, message });
        let [w, h] = self.size;
        let near = |p: P| {
            p.iter().all(|v| v.is_finite())
                && (-ROAD_EDGE_SLACK..=w + ROAD_EDGE_SLACK).contains(&p[0])
                && (-ROAD_EDGE_SLACK..=h + ROAD_EDGE_SLACK).contains(&p[1])
        };
        for (i, r) in self.road.iter().enumerate() {
            if r.points.len() < 2 {
                return bad(
                    format!("road[{i}].points"),
                    format!("a road needs at least 2 points, got {}", r.points.len()),
                );
            }
            if let Some(k) = r.points.iter().position(|&p| !near(p)) {
                return bad(
                    format!("road[{i}].points[{k}]"),
                    format!(
                        "{:?} is outside the map [0, {w}] × [0, {h}]: clip the road to the map (a road may end on its edge)",
                        r.points[k]
                    ),
                );
            }
            if polyline_length(&r.points) <= 0.0 {
                return bad(format!("road[{i}].points"), "the points must not all coincide".into());
            }
            if let Some(l) = r.lanes {
                if !(l.is_finite() && l > 0.0) {
                    return bad(format!("road[{i}].lanes"), format!("must be positive, got {l}"));
                }
            }
        }
        Ok(())
    }

    fn check_params(&self) -> Result<(), GrowError> {
        let p = &self.params;
        let field =
            |f: &str, message: String| GrowError::Field { path: PathBuf::new(), field: format!("params.{f}"), message };
        let bad = |field: &str, message: String| {
            Err(GrowError::Field { path: PathBuf::new(), field: format!("params.{field}"), message })
        };
        let pos = |x: f64| x.is_finite() && x > 0.0;
        if let Some(mu) = p.mu {
            if !(mu > 0.0 && mu <= 1.0) {
                return bad("mu", format!("must be in (0, 1], got {mu}"));
            }
        }
        if let Some(b) = p.b {
            if !pos(b) {
                return bad("b", format!("must be positive, got {b}"));
            }
        }
        for (k, v) in [
            ("demand", p.demand),
            ("slope_cut", p.slope_cut),
            ("block_area", p.block_area),
            ("nb", p.nb),
            ("stitch", p.stitch),
            ("bridge", p.bridge),
            ("settlement", p.settlement),
        ] {
            if !pos(v) {
                return bad(k, format!("must be positive, got {v}"));
            }
        }
        if !(p.center_strength > 0.0 && p.center_strength <= 1.0) {
            return bad("center_strength", format!("must be in (0, 1], got {}", p.center_strength));
        }
        if p.o.iter().any(|v| !pos(*v)) {
            return bad("o", format!("O₁…O₄ must be positive, got {:?}", p.o));
        }
        for (i, (t, c)) in p.c.table.iter().enumerate() {
            if c.iter().any(|v| !pos(*v)) {
                return bad(&format!("c[{i}]"), format!("C₁…C₆ must be positive, got {c:?}"));
            }
            check_era(&p.c.table, i, *t).map_err(|m| field(&format!("c[{i}]"), m))?;
        }
        for (i, (t, v)) in p.turn.table.iter().enumerate() {
            if !(v.iter().all(|v| v.is_finite()) && v[1] > 0.0 && v[2] >= 0.0) {
                return bad(&format!("turn[{i}]"), format!("must be [centre°, width° > 0, height ≥ 0], got {v:?}"));
            }
            check_era(&p.turn.table, i, *t).map_err(|m| field(&format!("turn[{i}]"), m))?;
        }
        if !(p.max_lanes.is_finite() && p.max_lanes >= 1.0) {
            return bad("max_lanes", format!("must be at least 1, got {}", p.max_lanes));
        }
        if !(0.0..=1.0).contains(&p.add_back) {
            return bad("add_back", format!("must be a probability, got {}", p.add_back));
        }
        for (k, table) in [("growth", &p.growth), ("widths", &p.widths)] {
            if table.is_empty() {
                return bad(k, "needs at least one [t, value] entry".into());
            }
            for (i, e) in table.iter().enumerate() {
                if !(e[0].is_finite() && e[0] >= 0.0 && e[1].is_finite() && e[1] >= 0.0) {
                    return bad(&format!("{k}[{i}]"), format!("must be [t ≥ 0, value ≥ 0], got {e:?}"));
                }
                if i > 0 && e[0] <= table[i - 1][0] {
                    return bad(&format!("{k}[{i}]"), "steps must increase".into());
                }
            }
        }
        if p.widths.iter().any(|e| e[1] <= 0.0) {
            return bad("widths", "lane counts must be positive".into());
        }
        Ok(())
    }
}

/// An era table's entry `i` at step `t`: a step, after the previous entry's.
fn check_era<const N: usize>(table: &[(f64, [f64; N])], i: usize, t: f64) -> Result<(), String> {
    if !(t.is_finite() && t >= 0.0) {
        return Err(format!("the step must be ≥ 0, got {t}"));
    }
    if i > 0 && t <= table[i - 1].0 {
        return Err("steps must increase".into());
    }
    Ok(())
}

/// A piecewise-linear table's value at `t` (constant beyond its ends).
fn linear(table: &[[f64; 2]], t: f64) -> f64 {
    if t <= table[0][0] {
        return table[0][1];
    }
    for w in table.windows(2) {
        if t <= w[1][0] {
            let f = (t - w[0][0]) / (w[1][0] - w[0][0]);
            return w[0][1] + f * (w[1][1] - w[0][1]);
        }
    }
    table[table.len() - 1][1]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_and_tables() {
        let c = Context::from_toml("size = [1000, 800]").unwrap();
        assert_eq!(c.dims(), [51, 41]);
        assert_eq!(c.growth(0), 10.0);
        assert_eq!(c.growth(75), 35.0);
        assert_eq!(c.growth(500), 60.0);
        assert_eq!(c.width(59), 1.0);
        assert_eq!(c.width(60), 2.0);
        assert_eq!(c.pattern(120).kind, PatternKind::Grid);
        assert_eq!(c.c(500), [0.3, 1.5, 20.0, 2.0, 5.0, 0.6]);
    }

    #[test]
    fn coefficients_change_by_era() {
        let c = Context::from_toml(
            "size = [1000, 800]\n[params]\nc = [[10, [1, 2, 3, 4, 5, 0.5]], [50, [0.2, 2, 3, 4, 5, 0.9]]]\nturn = [90, 60, 100]",
        )
        .unwrap();
        assert_eq!(c.c(0), [1.0, 2.0, 3.0, 4.0, 5.0, 0.5]);
        assert_eq!(c.c(49)[0], 1.0);
        assert_eq!(c.c(50), [0.2, 2.0, 3.0, 4.0, 5.0, 0.9]);
        assert_eq!(c.turn(70), [90.0, 60.0, 100.0]);
    }

    #[test]
    fn errors_name_the_field() {
        let e = Context::from_toml(
            "size = [1000, 1000]\n[[water]]\nriver = [[0, 0], [100, 0]]\nwidth = 20\n[[water]]\nriver = [[0, 0]]\nwidth = 30",
        )
        .unwrap_err();
        assert!(e.to_string().contains("water[1].river"), "{e}");
        let e = Context::from_toml("size = [1000, 1000]\nbogus = 1").unwrap_err();
        assert!(e.to_string().contains("bogus"), "{e}");
        let e = Context::from_toml("size = [1000, 1000]\n[params]\nc = [1, 2]").unwrap_err();
        assert!(e.to_string().contains("params.c") && e.to_string().contains("6 numbers"), "{e}");
        let e = Context::from_toml("size = [1000, 1000]\n[params]\nturn = [[0, [90, 60, 100]], [0, [90, 60, 50]]]")
            .unwrap_err();
        assert!(e.to_string().contains("params.turn[1]"), "{e}");
        let e = Context::from_toml("size = [1e7, 1e7]\nspacing = 1").unwrap_err();
        assert!(e.to_string().contains("GiB"), "{e}");
    }
}
