//! What a context places on the map besides terrain and water: existing roads (`[[road]]`),
//! growth nuclei (`[[nucleus]]`) and the centre (`[center]`), checked against the lattice's
//! classes of land, water and forbidden ground, and the roads inserted into the road graph
//! before the initial network is built.
//!
//! A road is sampled every ℓ/8 and every sample takes the class of its nearest lattice vertex
//! (as the generator and [`super::validate`] decide ground). A stretch over water inside the
//! road longer than ℓ/4 is a bridge, which may span at most `params.bridge` metres; shorter
//! stretches (a road along a shore clipping a water vertex's cell) stay road. A stretch over
//! water or forbidden ground at an end of the road of at most ℓ is cut off (the road ends on
//! the last land sample), a longer one is an error, as is forbidden ground inside the road for
//! more than ℓ/4.

use super::context::{Context, RoadClass};
use super::graph::{Class, Graph, SNAP};
use super::terrain::{Terrain, FORBIDDEN, LAND, WATER};
use super::GrowError;
use crate::geometry::{closest_on_segment, dist, lerp, P};
use std::path::PathBuf;

/// Sample points per lattice spacing along a road.
const SAMPLES_PER_SPACING: f64 = 8.0;

/// A piece of an existing road: its points and its class (the road's own, or a bridge).
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Its points (metres).
    pub points: Vec<P>,
    /// [`Class::Major`], [`Class::Minor`] or [`Class::Bridge`].
    pub class: Class,
}

/// What inserting a context's roads did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Inserted {
    /// Bridges among the roads' pieces.
    pub bridges: usize,
    /// Road ends on the map's edge (nodes of degree 1 there): where neighbouring cities join
    /// existing roads.
    pub edge_ends: Vec<u32>,
}

fn error(field: String, message: String) -> GrowError {
    GrowError::Field { path: PathBuf::new(), field, message }
}

fn cover_name(c: u8) -> &'static str {
    if c == WATER {
        "water"
    } else {
        "forbidden ground"
    }
}

/// The extent of the lattice (the map up to the last whole spacing).
fn extent(t: &Terrain) -> P {
    [(t.nx - 1) as f64 * t.spacing, (t.ny - 1) as f64 * t.spacing]
}

/// Road `i`'s points moved onto the lattice's extent, points closer than the graph's snap to
/// the previous one dropped (the last point kept).
fn clean_points(ctx: &Context, i: usize, t: &Terrain) -> Result<Vec<P>, GrowError> {
    let [w, h] = extent(t);
    let mut out: Vec<P> = Vec::new();
    for p in &ctx.road[i].points {
        let q = [p[0].clamp(0.0, w), p[1].clamp(0.0, h)];
        match out.last() {
            Some(&last) if dist(last, q) < SNAP => {
                if out.len() > 1 {
                    *out.last_mut().expect("non-empty") = q;
                }
            }
            _ => out.push(q),
        }
    }
    if out.len() < 2 {
        return Err(error(format!("road[{i}].points"), format!("the road is shorter than {SNAP} m on the map")));
    }
    Ok(out)
}

/// The samples of a polyline: arc length, point and ground class.
fn samples(points: &[P], t: &Terrain) -> Vec<(f64, P, u8)> {
    let step = t.spacing / SAMPLES_PER_SPACING;
    let mut out = Vec::new();
    let mut s0 = 0.0;
    for w in points.windows(2) {
        let len = dist(w[0], w[1]);
        let n = (len / step).ceil().max(1.0) as usize;
        for j in 0..n {
            let f = j as f64 / n as f64;
            let p = lerp(w[0], w[1], f);
            out.push((s0 + len * f, p, t.class_at(p)));
        }
        s0 += len;
    }
    let last = *points.last().expect("two points");
    out.push((s0, last, t.class_at(last)));
    out
}

/// The part of a polyline between arc lengths `a < b`.
fn between(points: &[P], a: f64, b: f64) -> Vec<P> {
    let mut out = Vec::new();
    let mut s0 = 0.0;
    for w in points.windows(2) {
        let len = dist(w[0], w[1]);
        let s1 = s0 + len;
        let at = |s: f64| {
            if s <= s0 + 1e-9 {
                w[0]
            } else if s >= s1 - 1e-9 {
                w[1]
            } else {
                lerp(w[0], w[1], (s - s0) / len)
            }
        };
        if out.is_empty() && a <= s1 {
            out.push(at(a.max(s0)));
        }
        if !out.is_empty() {
            if b <= s1 {
                out.push(at(b));
                break;
            }
            out.push(w[1]);
        }
        s0 = s1;
    }
    out.dedup_by(|x, y| dist(*x, *y) < 1e-9);
    out
}

/// Road `i` of the context cut into road and bridge pieces, after the rules of the module's
/// doc; errors name `road[i].points`.
pub fn pieces(ctx: &Context, i: usize, t: &Terrain) -> Result<Vec<Piece>, GrowError> {
    let road = &ctx.road[i];
    let points = clean_points(ctx, i, t)?;
    let smp = samples(&points, t);
    let last = smp.len() - 1;
    let total = smp[last].0;
    let (trim, bridge_min) = (t.spacing, t.spacing / 4.0);
    let field = || format!("road[{i}].points");
    let at = |p: P| format!("({:.0}, {:.0})", p[0], p[1]);
    let (mut start, mut end) = (0.0, total);
    let mut bridges: Vec<(f64, f64)> = Vec::new();
    let mut k = 0;
    while k <= last {
        let cover = smp[k].2;
        if cover == LAND {
            k += 1;
            continue;
        }
        let a = k;
        while k < last && smp[k + 1].2 == cover {
            k += 1;
        }
        let b = k;
        k += 1;
        let length = smp[b].0 - smp[a].0;
        if a == 0 && b == last {
            return Err(error(field(), format!("the road lies on {} all along", cover_name(cover))));
        }
        if a == 0 || b == last {
            if length > trim {
                let which = if a == 0 { "starts" } else { "ends" };
                return Err(error(
                    field(),
                    format!(
                        "the road {which} on {} for {length:.0} m at {}; a road must start and end on land",
                        cover_name(cover),
                        at(smp[if a == 0 { a } else { b }].1)
                    ),
                ));
            }
            if a == 0 {
                start = smp[b + 1].0;
            } else {
                end = smp[a - 1].0;
            }
            continue;
        }
        if length <= bridge_min {
            continue;
        }
        if cover == FORBIDDEN {
            return Err(error(
                field(),
                format!("the road crosses forbidden ground for {length:.0} m at {}", at(smp[a].1)),
            ));
        }
        let span = smp[b + 1].0 - smp[a - 1].0;
        if span > ctx.params.bridge {
            return Err(error(
                field(),
                format!(
                    "the road crosses water for {span:.0} m at {}: a bridge spans at most `params.bridge` = {} m",
                    at(smp[a].1),
                    ctx.params.bridge
                ),
            ));
        }
        bridges.push((smp[a - 1].0, smp[b + 1].0));
    }
    if end - start < SNAP {
        return Err(error(field(), "the road has less than 0.5 m on land".into()));
    }
    let own = match road.class {
        RoadClass::Major => Class::Major,
        RoadClass::Minor => Class::Minor,
    };
    let mut cuts: Vec<(f64, f64, Class)> = Vec::new();
    let mut from = start;
    for &(a, b) in bridges.iter().filter(|&&(a, b)| a >= start && b <= end) {
        cuts.push((from, a, own));
        cuts.push((a, b, Class::Bridge));
        from = b;
    }
    cuts.push((from, end, own));
    Ok(cuts
        .into_iter()
        .filter(|&(a, b, _)| b - a >= SNAP)
        .map(|(a, b, class)| Piece { points: between(&points, a, b), class })
        .collect())
}

/// Inserts the context's roads into the graph (built at step 0), major roads with `lanes` or
/// `major_lanes` lanes, minor ones with `lanes` or 1; fixed roads' segments are marked.
pub fn insert(graph: &mut Graph, ctx: &Context, t: &Terrain, major_lanes: f64) -> Result<Inserted, GrowError> {
    let mut done = Inserted::default();
    let mut all = Vec::new();
    for i in 0..ctx.road.len() {
        all.push(pieces(ctx, i, t)?);
    }
    let [w, h] = extent(t);
    let on_edge = |p: P| p[0] <= 1e-6 || p[1] <= 1e-6 || p[0] >= w - 1e-6 || p[1] >= h - 1e-6;
    let mut ends = Vec::new();
    for (road, pieces) in ctx.road.iter().zip(all) {
        let lanes = road.lanes.unwrap_or(match road.class {
            RoadClass::Major => major_lanes,
            RoadClass::Minor => 1.0,
        });
        for piece in &pieces {
            done.bridges += (piece.class == Class::Bridge) as usize;
            for seg in piece.points.windows(2) {
                let (a, b) = (graph.node_at(seg[0], true), graph.node_at(seg[1], true));
                let chain = graph.insert(a, b, piece.class, lanes, 0);
                if road.fixed {
                    for c in chain.windows(2) {
                        if let Some(s) = graph.find(c[0], c[1]) {
                            graph.segs[s as usize].fixed = true;
                        }
                    }
                }
            }
        }
        for p in [pieces.first().and_then(|p| p.points.first()), pieces.last().and_then(|p| p.points.last())]
            .into_iter()
            .flatten()
        {
            if on_edge(*p) {
                ends.push(*p);
            }
        }
    }
    for p in ends {
        if let Some(&n) = graph.nodes_near(p, SNAP).first() {
            if graph.road_degree(n) == 1 && !done.edge_ends.contains(&n) {
                done.edge_ends.push(n);
            }
        }
    }
    Ok(done)
}

/// The lattice vertex nearest `p` that is land, searched within `r` metres.
fn nearest_land(t: &Terrain, p: P, r: f64) -> Option<usize> {
    let s = t.spacing;
    let k = (r / s).ceil() as i64;
    let c = t.nearest(p);
    let (cx, cy) = ((c % t.nx) as i64, (c / t.nx) as i64);
    let mut best: Option<(f64, usize)> = None;
    for y in (cy - k).max(0)..=(cy + k).min(t.ny as i64 - 1) {
        for x in (cx - k).max(0)..=(cx + k).min(t.nx as i64 - 1) {
            let v = y as usize * t.nx + x as usize;
            let d = dist([x as f64 * s, y as f64 * s], p);
            if t.class[v] == LAND && d <= r && best.is_none_or(|b| d < b.0) {
                best = Some((d, v));
            }
        }
    }
    best.map(|b| b.1)
}

/// The centre's lattice vertex when the context names a centre: the land vertex nearest to
/// `center.position`, which may be on water or forbidden ground by at most 2ℓ (a shore
/// drawn at lattice resolution).
pub fn centre_vertex(ctx: &Context, t: &Terrain) -> Result<Option<usize>, GrowError> {
    let Some(c) = &ctx.center else { return Ok(None) };
    match nearest_land(t, c.position, 2.0 * t.spacing) {
        Some(v) => Ok(Some(v)),
        None => Err(error(
            "center.position".into(),
            format!("{:?} is on {}: the centre must be on land", c.position, cover_name(t.class_at(c.position))),
        )),
    }
}

/// The point of an existing road (a segment built before the initial network) nearest `p`
/// within `r`, with its segment.
pub fn on_road(graph: &Graph, p: P, r: f64) -> Option<(u32, P)> {
    graph
        .segs_near(p, r)
        .into_iter()
        .filter(|&s| graph.segs[s].class.is_road())
        .map(|s| {
            let (a, b) = graph.ends(s as u32);
            (s as u32, closest_on_segment(p, a, b).0)
        })
        .filter(|(_, q)| dist(*q, p) <= r)
        .min_by(|x, y| dist(x.1, p).total_cmp(&dist(y.1, p)).then(x.0.cmp(&y.0)))
}

/// Every `[[nucleus]]` must be on land.
pub fn check_nuclei(ctx: &Context, t: &Terrain) -> Result<(), GrowError> {
    for (i, n) in ctx.nucleus.iter().enumerate() {
        let c = t.class_at(n.position);
        if c != LAND {
            return Err(error(
                format!("nucleus[{i}].position"),
                format!("{:?} is on {}: a nucleus must be on land", n.position, cover_name(c)),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn terrain(extra: &str) -> (Context, Terrain) {
        let ctx = Context::from_toml(&format!(
            "size = [1000, 1000]\n[terrain]\nrelief = 0\n[[water]]\nriver = [[0, 500], [1000, 500]]\nwidth = 60\n{extra}"
        ))
        .unwrap();
        let t = Terrain::build(&ctx, 1).unwrap();
        (ctx, t)
    }

    #[test]
    fn a_road_across_a_river_has_a_bridge_piece() {
        let (ctx, t) = terrain("[[road]]\npoints = [[500, 0], [500, 1000]]");
        let p = pieces(&ctx, 0, &t).unwrap();
        let classes: Vec<Class> = p.iter().map(|p| p.class).collect();
        assert_eq!(classes, [Class::Major, Class::Bridge, Class::Major]);
        let b = &p[1].points;
        // Water at the vertices y = 480, 500, 520: samples nearest them lie in [470, 530).
        assert!(b[0][1] < 470.0 && b[0][1] > 460.0 && b[1][1] >= 530.0 && b[1][1] < 540.0, "{b:?}");
        assert_eq!(p[0].points[0], [500.0, 0.0]);
        assert_eq!(*p[2].points.last().unwrap(), [500.0, 1000.0]);
    }

    #[test]
    fn long_spans_water_ends_and_forbidden_ground_are_refused() {
        let (ctx, t) = terrain("[params]\nbridge = 40\n[[road]]\npoints = [[500, 0], [500, 1000]]");
        let e = pieces(&ctx, 0, &t).unwrap_err().to_string();
        assert!(e.contains("road[0].points") && e.contains("params.bridge"), "{e}");
        let (ctx, t) = terrain("[[road]]\npoints = [[100, 100], [100, 500]]");
        let e = pieces(&ctx, 0, &t).unwrap_err().to_string();
        assert!(e.contains("ends on water"), "{e}");
        let (ctx, t) =
            terrain("[[forbidden]]\npolygon = [[200, 100], [300, 100], [300, 200], [200, 200]]\n[[road]]\npoints = [[100, 150], [400, 150]]");
        let e = pieces(&ctx, 0, &t).unwrap_err().to_string();
        assert!(e.contains("forbidden"), "{e}");
    }

    #[test]
    fn a_road_ending_a_little_into_water_is_cut_at_the_shore() {
        let (ctx, t) = terrain("[[road]]\npoints = [[100, 100], [100, 475]]");
        let p = pieces(&ctx, 0, &t).unwrap();
        assert_eq!(p.len(), 1);
        let end = *p[0].points.last().unwrap();
        assert!(end[1] < 470.0 && end[1] > 455.0, "{end:?}");
    }

    #[test]
    fn roads_are_inserted_with_their_ends_on_the_edge() {
        let (ctx, t) = terrain(
            "[[road]]\npoints = [[0, 100], [600, 100.2], [1000.3, 100]]\nfixed = true\n[[road]]\npoints = [[300, 0], [300, 300]]\nclass = \"minor\"",
        );
        let mut g = Graph::new(ctx.size);
        let done = insert(&mut g, &ctx, &t, 1.0).unwrap();
        assert_eq!(done.bridges, 0);
        assert_eq!(done.edge_ends.len(), 3);
        let minor = g.segs.iter().filter(|s| s.class == Class::Minor).count();
        let fixed = g.segs.iter().filter(|s| s.fixed).count();
        assert_eq!((minor, fixed), (2, 3), "the roads cross at a junction: both are split there");
        assert!(g.nodes.iter().any(|n| n.pos == [1000.0, 100.0]), "moved onto the edge");
    }
}
