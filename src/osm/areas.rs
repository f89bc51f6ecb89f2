//! Areas of an extract as polygons in local metres: water (`natural=water`, `water=*`,
//! `waterway=riverbank|dock|canal`, `landuse=reservoir|basin`, and the sea on the water side of
//! `natural=coastline`), parks (`leisure=park`) and railway land (`landuse=railway`); closed
//! ways and multipolygon relations alike.

use super::read::{Extract, Tags};
use crate::geometry::planar::{polygon_label_point, PlanarGraph};
use crate::geometry::polygon::geo_polygon;
use crate::geometry::site::Projection;
use crate::geometry::{closest_on_segment, cross, dist, sub, P};
use geo::BooleanOps;
use std::collections::{BTreeMap, BTreeSet};

/// A class of area a site can make holes of.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum AreaClass {
    /// Lakes, rivers' water areas, docks, reservoirs, the sea.
    Water,
    /// Parks.
    Park,
    /// Railway land.
    Rail,
}

impl AreaClass {
    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            AreaClass::Water => "water",
            AreaClass::Park => "park",
            AreaClass::Rail => "rail",
        }
    }

    /// The class a name stands for.
    pub fn parse(s: &str) -> Option<AreaClass> {
        [AreaClass::Water, AreaClass::Park, AreaClass::Rail].into_iter().find(|c| c.name() == s)
    }

    /// The class of an area with these tags (a closed way or a multipolygon).
    pub fn of(tags: &Tags) -> Option<AreaClass> {
        let is = |k: &str, v: &[&str]| tags.get(k).is_some_and(|x| v.contains(&x.as_str()));
        if tags.contains_key("water")
            || is("natural", &["water", "bay"])
            || is("waterway", &["riverbank", "dock", "canal"])
            || is("landuse", &["reservoir", "basin"])
        {
            Some(AreaClass::Water)
        } else if is("leisure", &["park"]) {
            Some(AreaClass::Park)
        } else if is("landuse", &["railway"]) {
            Some(AreaClass::Rail)
        } else {
            None
        }
    }
}

/// Node-id lists joined end to end into closed rings (either direction); pieces that close no
/// ring (a relation cut by the extract's edge) are dropped.
pub fn rings(parts: Vec<Vec<i64>>) -> Vec<Vec<i64>> {
    let (mut closed, mut open): (Vec<Vec<i64>>, Vec<Vec<i64>>) =
        parts.into_iter().filter(|p| p.len() >= 2).partition(|p| p.len() >= 4 && p.first() == p.last());
    while let Some(mut ring) = open.pop() {
        loop {
            let last = ring[ring.len() - 1];
            if ring.len() >= 4 && ring[0] == last {
                closed.push(ring);
                break;
            }
            let Some(k) = open.iter().position(|p| p[0] == last || p[p.len() - 1] == last) else { break };
            let mut next = open.swap_remove(k);
            if next[0] != last {
                next.reverse();
            }
            ring.extend_from_slice(&next[1..]);
        }
    }
    closed
}

/// Directed lines joined head to tail (a coastline's ways keep their direction: land on the left).
pub fn lines(parts: Vec<Vec<i64>>) -> Vec<Vec<i64>> {
    let mut open: Vec<Vec<i64>> = parts.into_iter().filter(|p| p.len() >= 2).collect();
    let mut out = Vec::new();
    while let Some(mut line) = open.pop() {
        while let Some(k) = open.iter().position(|p| p[0] == line[line.len() - 1] && line[0] != line[line.len() - 1]) {
            let next = open.swap_remove(k);
            line.extend_from_slice(&next[1..]);
        }
        while let Some(k) = open.iter().position(|p| p[p.len() - 1] == line[0] && line[0] != line[line.len() - 1]) {
            let mut prev = open.swap_remove(k);
            prev.extend_from_slice(&line[1..]);
            line = prev;
        }
        out.push(line);
    }
    out.sort();
    out
}

/// Projects node ids; `None` if one is missing from the extract.
fn project(ex: &Extract, ids: &[i64], proj: &Projection) -> Option<Vec<P>> {
    ids.iter().map(|id| ex.nodes.get(id).and_then(|&ll| proj.to_local(ll).ok())).collect()
}

/// The areas of `classes` that meet `region` (local metres), united, not clipped (so that their
/// edges cross the region's rather than run along them): closed ways, multipolygon relations
/// (outer rings less inner rings) and, for water, the sea beside the coastline (found on the
/// region grown by a few metres). Returns the polygons and how many areas were skipped because
/// the extract lacks some of their nodes.
pub(crate) fn areas(
    ex: &Extract,
    classes: &BTreeSet<AreaClass>,
    proj: &Projection,
    region: &geo::Polygon<f64>,
) -> (geo::MultiPolygon<f64>, usize) {
    let mut polys: Vec<geo::Polygon<f64>> = Vec::new();
    let mut skipped = 0;
    let wanted = |tags: &Tags| AreaClass::of(tags).is_some_and(|c| classes.contains(&c));
    for w in ex.ways.iter().filter(|w| w.is_closed() && wanted(&w.tags)) {
        match project(ex, &w.refs, proj) {
            Some(r) => polys.push(geo_polygon(&r, &[])),
            None => skipped += 1,
        }
    }
    let ways: BTreeMap<i64, &super::read::Way> = ex.ways.iter().map(|w| (w.id, w)).collect();
    for r in ex.relations.iter().filter(|r| wanted(&r.tags)) {
        let part = |role: &str| -> Vec<Vec<i64>> {
            r.members
                .iter()
                .filter(|m| (m.role == role) || (role == "outer" && m.role.is_empty()))
                .filter_map(|m| ways.get(&m.way).map(|w| w.refs.clone()))
                .collect()
        };
        let to_multi = |rs: Vec<Vec<i64>>, skipped: &mut usize| -> geo::MultiPolygon<f64> {
            let mut m = geo::MultiPolygon::new(vec![]);
            for ring in rs {
                match project(ex, &ring, proj) {
                    Some(p) => m = m.union(&geo::MultiPolygon::new(vec![geo_polygon(&p, &[])])),
                    None => *skipped += 1,
                }
            }
            m
        };
        let outer = to_multi(rings(part("outer")), &mut skipped);
        let inner = to_multi(rings(part("inner")), &mut skipped);
        polys.extend(outer.difference(&inner).0);
    }
    let mut all = geo::MultiPolygon::new(vec![]);
    for p in polys {
        all = all.union(&geo::MultiPolygon::new(vec![p]));
    }
    if classes.contains(&AreaClass::Water) {
        use geo::Buffer;
        if let Some(grown) = region.buffer(5.0).0.into_iter().next() {
            all = all.union(&sea(ex, proj, &grown));
        }
    }
    use geo::Intersects;
    all.0.retain(|p| p.intersects(region));
    (all, skipped)
}

/// The sea inside `region`: the parts of the region that the coastline (land on its left) leaves
/// on its water side. Each face of the region cut by the coastline is sea when the nearest
/// coastline segment has the face's label point on its right.
pub(crate) fn sea(ex: &Extract, proj: &Projection, region: &geo::Polygon<f64>) -> geo::MultiPolygon<f64> {
    let coast: Vec<Vec<i64>> =
        ex.ways.iter().filter(|w| w.tag("natural") == Some("coastline")).map(|w| w.refs.clone()).collect();
    let outer: Vec<P> = region.exterior().coords().map(|c| [c.x, c.y]).collect();
    let Ok(area) = crate::geometry::Polygon::new(outer.clone(), vec![]) else { return geo::MultiPolygon::new(vec![]) };
    let mut segments: Vec<[P; 2]> = Vec::new();
    for line in lines(coast) {
        // Runs of nodes the extract has.
        let pts: Vec<Option<P>> =
            line.iter().map(|id| ex.nodes.get(id).and_then(|&ll| proj.to_local(ll).ok())).collect();
        for run in pts.split(Option::is_none) {
            let run: Vec<P> = run.iter().flatten().copied().collect();
            for piece in area.clip_polyline(&run, 1e-6) {
                segments.extend(piece.windows(2).map(|w| [w[0], w[1]]));
            }
        }
    }
    if segments.is_empty() {
        return geo::MultiPolygon::new(vec![]);
    }
    let mut all = segments.clone();
    let n = outer.len();
    all.extend((0..n).map(|i| [outer[i], outer[(i + 1) % n]]));
    let g = PlanarGraph::from_segments(&all, 1e-6);
    let at = |r: &[u32]| r.iter().map(|&v| g.positions[v as usize]).collect::<Vec<P>>();
    let mut sea = Vec::new();
    for f in g.faces().faces {
        let ring = at(&f.boundary);
        let holes: Vec<Vec<P>> = f.holes.iter().map(|h| at(h)).collect();
        let Some(p) = polygon_label_point(&ring, &holes) else { continue };
        let nearest = segments.iter().min_by(|a, b| {
            dist(p, closest_on_segment(p, a[0], a[1]).0).total_cmp(&dist(p, closest_on_segment(p, b[0], b[1]).0))
        });
        if let Some(s) = nearest {
            if cross(sub(s[1], s[0]), sub(p, s[0])) < 0.0 {
                sea.push(geo_polygon(&ring, &holes));
            }
        }
    }
    let mut out = geo::MultiPolygon::new(vec![]);
    for p in sea {
        out = out.union(&geo::MultiPolygon::new(vec![p]));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_join_into_rings_and_lines() {
        let r = rings(vec![vec![1, 2, 3], vec![5, 4, 3], vec![5, 1], vec![7, 8]]);
        assert_eq!(r, vec![vec![5, 1, 2, 3, 4, 5]]);
        let l = lines(vec![vec![3, 4], vec![1, 2, 3], vec![9, 8]]);
        assert_eq!(l, vec![vec![1, 2, 3, 4], vec![9, 8]]);
    }
}
