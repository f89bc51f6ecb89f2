//! Streets of an extract: the drivable network as OSMnx's `network_type="drive"` selects it,
//! split into pieces between its junctions (with the OSM node ids at their ends, so a street
//! graph keeps OpenStreetMap's topology: a bridge over a street is no junction), and the major
//! roads merged into continuous lines.

use super::read::{Extract, Tags, Way};
use std::collections::{BTreeMap, BTreeSet};

/// The default major road classes of a site.
pub const MAJOR: [&str; 4] = ["motorway", "trunk", "primary", "secondary"];

/// The netspec level of a drivable street (1 major … 4 service), or `None` when it is not
/// drivable: OSMnx's `drive` filter (no `area=yes`, `access=private`, `motor_vehicle=no`,
/// `motorcar=no`, and no service roads of the kinds `alley`, `driveway`, `emergency_access`,
/// `parking`, `parking_aisle`, `private`), service roads only with `service`.
pub fn level(tags: &Tags, service: bool) -> Option<u8> {
    let is = |k: &str, v: &[&str]| tags.get(k).is_some_and(|x| v.contains(&x.as_str()));
    if is("area", &["yes"])
        || is("access", &["private"])
        || is("motor_vehicle", &["no"])
        || is("motorcar", &["no"])
        || is("service", &["alley", "driveway", "emergency_access", "parking", "parking_aisle", "private"])
    {
        return None;
    }
    let h = tags.get("highway")?.as_str();
    let base = h.strip_suffix("_link").unwrap_or(h);
    match base {
        "motorway" | "trunk" | "primary" | "secondary" => Some(1),
        "tertiary" => Some(2),
        "residential" | "unclassified" | "living_street" | "road" => Some(3),
        "service" if service => Some(4),
        _ => None,
    }
}

/// Whether the way is one-way, and whether against its node order (OSMnx's rule: `oneway` of
/// `yes`, `true`, `1`, or `-1`/`reverse` against the order; roundabouts are one-way).
pub fn oneway(tags: &Tags) -> (bool, bool) {
    match tags.get("oneway").map(String::as_str) {
        Some("yes" | "true" | "1") => (true, false),
        Some("-1" | "reverse") => (true, true),
        Some("no" | "false" | "0") => (false, false),
        _ => (tags.get("junction").is_some_and(|j| j == "roundabout"), false),
    }
}

/// A piece of a drivable way between two junctions or ends.
#[derive(Clone, Debug, PartialEq)]
pub struct StreetPiece {
    /// The way's id.
    pub way: i64,
    /// The OSM node id it starts at.
    pub u: i64,
    /// The OSM node id it ends at.
    pub v: i64,
    /// Its positions, `[longitude, latitude]`, from `u` to `v`.
    pub points: Vec<[f64; 2]>,
    /// The `highway` class.
    pub highway: String,
    /// The netspec level.
    pub level: u8,
    /// Traffic runs only from `u` to `v`.
    pub oneway: bool,
    /// The street's name, if tagged.
    pub name: Option<String>,
}

/// The drivable ways any of whose nodes `near` accepts, split at every node that ends a way or
/// is shared by two ways (or twice by one), one-way pieces turned to run in traffic's direction.
/// Runs of nodes missing from the extract split a way too.
pub fn street_pieces(ex: &Extract, service: bool, near: impl Fn([f64; 2]) -> bool) -> Vec<StreetPiece> {
    let ways: Vec<(&Way, u8)> = ex
        .ways
        .iter()
        .filter_map(|w| level(&w.tags, service).map(|l| (w, l)))
        .filter(|(w, _)| w.refs.iter().any(|r| ex.nodes.get(r).is_some_and(|&p| near(p))))
        .collect();
    let mut uses: BTreeMap<i64, usize> = BTreeMap::new();
    for (w, _) in &ways {
        for r in &w.refs {
            *uses.entry(*r).or_default() += 1;
        }
        for end in [w.refs[0], w.refs[w.refs.len() - 1]] {
            *uses.entry(end).or_default() += 2;
        }
    }
    let mut out = Vec::new();
    for (w, lvl) in ways {
        let (one, reverse) = oneway(&w.tags);
        let mut ids: Vec<i64> = Vec::new();
        let mut flush = |ids: &mut Vec<i64>| {
            if ids.len() >= 2 {
                let mut ids2 = ids.clone();
                if reverse {
                    ids2.reverse();
                }
                out.push(StreetPiece {
                    way: w.id,
                    u: ids2[0],
                    v: ids2[ids2.len() - 1],
                    points: ids2.iter().map(|r| ex.nodes[r]).collect(),
                    highway: w.tag("highway").unwrap_or_default().to_string(),
                    level: lvl,
                    oneway: one,
                    name: w.tag("name").map(str::to_string),
                });
            }
            ids.clear();
        };
        for &r in &w.refs {
            if !ex.nodes.contains_key(&r) {
                flush(&mut ids);
                continue;
            }
            ids.push(r);
            if ids.len() >= 2 && uses.get(&r).copied().unwrap_or(0) >= 2 {
                flush(&mut ids);
                ids.push(r);
            }
        }
        flush(&mut ids);
    }
    out
}

/// A major road: ways of the chosen classes joined at nodes where exactly two of them end.
#[derive(Clone, Debug, PartialEq)]
pub struct MajorRoad {
    /// The ways, in order.
    pub ways: Vec<i64>,
    /// The `highway` class of its first way.
    pub highway: String,
    /// Its name, if its first way has one.
    pub name: Option<String>,
    /// Node ids in order.
    pub refs: Vec<i64>,
}

/// The ways whose `highway` is one of `classes`, merged into continuous lines: two ways are
/// joined where they are the only two of the kind ending at a node.
pub fn major_roads(ex: &Extract, classes: &[String]) -> Vec<MajorRoad> {
    let ways: Vec<&Way> = ex
        .ways
        .iter()
        .filter(|w| w.tag("highway").is_some_and(|h| classes.iter().any(|c| c == h)) && w.refs.len() >= 2)
        .collect();
    let mut ends: BTreeMap<i64, Vec<usize>> = BTreeMap::new();
    for (i, w) in ways.iter().enumerate() {
        ends.entry(w.refs[0]).or_default().push(i);
        ends.entry(w.refs[w.refs.len() - 1]).or_default().push(i);
    }
    let partner = |node: i64, me: usize, used: &BTreeSet<usize>| -> Option<usize> {
        match ends.get(&node).map(Vec::as_slice) {
            Some([a, b]) if (*a == me) != (*b == me) => {
                Some(if *a == me { *b } else { *a }).filter(|o| !used.contains(o))
            }
            _ => None,
        }
    };
    let mut used = BTreeSet::new();
    let mut out = Vec::new();
    for start in 0..ways.len() {
        if !used.insert(start) {
            continue;
        }
        let mut refs = ways[start].refs.clone();
        let mut ids = vec![ways[start].id];
        let mut me = start;
        // Forward, then backward.
        while let Some(o) = partner(refs[refs.len() - 1], me, &used) {
            used.insert(o);
            let mut r = ways[o].refs.clone();
            if r[0] != refs[refs.len() - 1] {
                r.reverse();
            }
            refs.extend_from_slice(&r[1..]);
            ids.push(ways[o].id);
            me = o;
        }
        me = start;
        while let Some(o) = partner(refs[0], me, &used) {
            used.insert(o);
            let mut r = ways[o].refs.clone();
            if r[r.len() - 1] != refs[0] {
                r.reverse();
            }
            r.extend_from_slice(&refs[1..]);
            refs = r;
            ids.insert(0, ways[o].id);
            me = o;
        }
        out.push(MajorRoad {
            ways: ids,
            highway: ways[start].tag("highway").unwrap_or_default().to_string(),
            name: ways[start].tag("name").map(str::to_string),
            refs,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn way(id: i64, refs: &[i64], tags: &[(&str, &str)]) -> Way {
        Way { id, refs: refs.to_vec(), tags: tags.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect() }
    }

    fn extract(ways: Vec<Way>) -> Extract {
        let nodes = (1..=9).map(|i| (i, [24.0 + i as f64 * 1e-3, 60.0])).collect();
        Extract { nodes, ways, relations: vec![] }
    }

    #[test]
    fn ways_split_at_junctions_and_major_roads_merge() {
        let ex = extract(vec![
            way(1, &[1, 2, 3, 4], &[("highway", "residential")]),
            way(2, &[3, 5], &[("highway", "primary"), ("oneway", "-1")]),
            way(3, &[5, 6], &[("highway", "primary")]),
            way(4, &[6, 7], &[("highway", "footway")]),
            way(5, &[4, 8], &[("highway", "service"), ("service", "parking_aisle")]),
        ]);
        let p = street_pieces(&ex, true, |_| true);
        let ends: Vec<(i64, i64, u8, bool)> = p.iter().map(|s| (s.u, s.v, s.level, s.oneway)).collect();
        // Way 1 splits at node 3 (shared with way 2); way 2 runs against its order.
        assert_eq!(ends, vec![(1, 3, 3, false), (3, 4, 3, false), (5, 3, 1, true), (5, 6, 1, false)]);
        let m = major_roads(&ex, &["primary".to_string()]);
        assert_eq!(m.len(), 1);
        assert_eq!(m[0].refs, vec![3, 5, 6]);
        assert_eq!(m[0].ways, vec![2, 3]);
        assert_eq!(level(&way(9, &[1], &[("highway", "tertiary_link")]).tags, false), Some(2));
        assert_eq!(level(&way(9, &[1], &[("highway", "residential"), ("access", "private")]).tags, false), None);
    }
}
