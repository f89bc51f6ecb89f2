//! OpenStreetMap extracts read into memory: OSM PBF (the `osmpbf` crate) and OSM XML
//! (`roxmltree`), told apart by their first bytes. Only what a site needs is kept: every node's
//! position, the ways a site can use (streets, water, coastline, parks, railway land, and the
//! members of multipolygon relations with such tags) and those relations.

use super::OsmError;
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::Path;

/// Tags of an element.
pub type Tags = BTreeMap<String, String>;

/// A way: its node ids and tags.
#[derive(Clone, Debug, PartialEq)]
pub struct Way {
    /// The OSM id.
    pub id: i64,
    /// Node ids, in order (a closed way repeats its first node).
    pub refs: Vec<i64>,
    /// Tags.
    pub tags: Tags,
}

impl Way {
    /// A tag's value.
    pub fn tag(&self, key: &str) -> Option<&str> {
        self.tags.get(key).map(String::as_str)
    }

    /// Whether the way is closed (a ring).
    pub fn is_closed(&self) -> bool {
        self.refs.len() >= 4 && self.refs.first() == self.refs.last()
    }
}

/// A multipolygon relation's way member.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// The way's id.
    pub way: i64,
    /// `outer`, `inner` or empty.
    pub role: String,
}

/// A relation (only `type=multipolygon` ones are kept), with its way members.
#[derive(Clone, Debug, PartialEq)]
pub struct Relation {
    /// The OSM id.
    pub id: i64,
    /// Way members.
    pub members: Vec<Member>,
    /// Tags.
    pub tags: Tags,
}

impl Relation {
    /// A tag's value.
    pub fn tag(&self, key: &str) -> Option<&str> {
        self.tags.get(key).map(String::as_str)
    }
}

/// What a site reads from an extract.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Extract {
    /// Node positions, `[longitude, latitude]` degrees.
    pub nodes: HashMap<i64, [f64; 2]>,
    /// The ways kept, by id order.
    pub ways: Vec<Way>,
    /// The multipolygon relations kept, by id order.
    pub relations: Vec<Relation>,
}

impl Extract {
    /// The longitude/latitude box of every node: `[west, south, east, north]`, or `None` without
    /// nodes.
    pub fn extent(&self) -> Option<[f64; 4]> {
        let mut it = self.nodes.values();
        let first = *it.next()?;
        Some(it.fold([first[0], first[1], first[0], first[1]], |b, p| {
            [b[0].min(p[0]), b[1].min(p[1]), b[2].max(p[0]), b[3].max(p[1])]
        }))
    }

    /// A way's positions (`None` if a node is missing from the extract).
    pub fn positions(&self, way: &Way) -> Option<Vec<[f64; 2]>> {
        way.refs.iter().map(|r| self.nodes.get(r).copied()).collect()
    }
}

/// Whether a way or relation with these tags is something a site uses.
pub fn wanted(tags: &Tags) -> bool {
    let has = |k: &str| tags.contains_key(k);
    let is = |k: &str, v: &[&str]| tags.get(k).is_some_and(|x| v.contains(&x.as_str()));
    has("highway")
        || has("water")
        || is("natural", &["water", "coastline", "bay"])
        || is("waterway", &["riverbank", "dock", "canal", "river"])
        || is("landuse", &["reservoir", "basin", "railway"])
        || is("leisure", &["park"])
}

/// Reads an extract (`.osm.pbf` or `.osm` XML, whatever the name says).
pub fn read(path: &Path) -> Result<Extract, OsmError> {
    let bad = |message: String| OsmError::NotOsm { path: path.to_path_buf(), message };
    let mut head = [0u8; 64];
    let n = {
        use std::io::Read;
        let mut f = std::fs::File::open(path).map_err(|source| OsmError::Io { path: path.to_path_buf(), source })?;
        f.read(&mut head).map_err(|source| OsmError::Io { path: path.to_path_buf(), source })?
    };
    let head = &head[..n];
    let text_start = String::from_utf8_lossy(head);
    let trimmed = text_start.trim_start_matches('\u{feff}').trim_start();
    let extract = if trimmed.starts_with('<') {
        read_xml(path)?
    } else if head.windows(9).any(|w| w == b"OSMHeader") {
        read_pbf(path).map_err(bad)?
    } else {
        return Err(bad("neither OSM XML (it does not start with `<`) nor OSM PBF (no OSMHeader block)".into()));
    };
    if extract.nodes.is_empty() {
        return Err(OsmError::Empty { path: path.to_path_buf() });
    }
    Ok(extract)
}

/// Keeps the ways a site uses, and the untagged members of kept relations.
fn finish(nodes: HashMap<i64, [f64; 2]>, mut ways: Vec<Way>, mut relations: Vec<Relation>) -> Extract {
    let members: BTreeSet<i64> = relations.iter().flat_map(|r| r.members.iter().map(|m| m.way)).collect();
    ways.retain(|w| wanted(&w.tags) || members.contains(&w.id));
    ways.sort_by_key(|w| w.id);
    relations.sort_by_key(|r| r.id);
    Extract { nodes, ways, relations }
}

fn is_multipolygon(tags: &Tags) -> bool {
    tags.get("type").is_some_and(|t| t == "multipolygon") && wanted(tags)
}

fn read_pbf(path: &Path) -> Result<Extract, String> {
    use osmpbf::{Element, ElementReader, RelMemberType};
    let reader = ElementReader::from_path(path).map_err(|e| e.to_string())?;
    let mut nodes = HashMap::new();
    let mut ways = Vec::new();
    let mut relations = Vec::new();
    let tags_of = |it: &mut dyn Iterator<Item = (&str, &str)>| -> Tags {
        it.map(|(k, v)| (k.to_string(), v.to_string())).collect()
    };
    reader
        .for_each(|element| match element {
            Element::Node(n) => {
                nodes.insert(n.id(), [n.lon(), n.lat()]);
            }
            Element::DenseNode(n) => {
                nodes.insert(n.id(), [n.lon(), n.lat()]);
            }
            Element::Way(w) => {
                let tags = tags_of(&mut w.tags());
                // Untagged ways may be multipolygon members (relations come last in a PBF).
                if tags.is_empty() || wanted(&tags) {
                    ways.push(Way { id: w.id(), refs: w.refs().collect(), tags });
                }
            }
            Element::Relation(r) => {
                let tags = tags_of(&mut r.tags());
                if is_multipolygon(&tags) {
                    let members = r
                        .members()
                        .filter(|m| m.member_type == RelMemberType::Way)
                        .map(|m| Member { way: m.member_id, role: m.role().unwrap_or("").to_string() })
                        .collect();
                    relations.push(Relation { id: r.id(), members, tags });
                }
            }
        })
        .map_err(|e| e.to_string())?;
    Ok(finish(nodes, ways, relations))
}

fn read_xml(path: &Path) -> Result<Extract, OsmError> {
    let bad = |message: String| OsmError::NotOsm { path: path.to_path_buf(), message };
    let text = crate::io::read_utf8(path).map_err(|e| bad(e.to_string()))?;
    let doc = roxmltree::Document::parse(&text).map_err(|e| bad(e.to_string()))?;
    let root = doc.root_element();
    if root.tag_name().name() != "osm" {
        return Err(bad(format!("the root element is <{}>, not <osm>", root.tag_name().name())));
    }
    let line = |n: roxmltree::Node| doc.text_pos_at(n.range().start).row;
    let num = |n: roxmltree::Node, key: &str| -> Result<f64, OsmError> {
        n.attribute(key)
            .and_then(|v| v.parse::<f64>().ok())
            .ok_or_else(|| bad(format!("line {}: <{}> without a numeric `{key}`", line(n), n.tag_name().name())))
    };
    let id = |n: roxmltree::Node, key: &str| -> Result<i64, OsmError> {
        n.attribute(key)
            .and_then(|v| v.parse::<i64>().ok())
            .ok_or_else(|| bad(format!("line {}: <{}> without an integer `{key}`", line(n), n.tag_name().name())))
    };
    let tags = |n: roxmltree::Node| -> Tags {
        n.children()
            .filter(|c| c.has_tag_name("tag"))
            .filter_map(|c| Some((c.attribute("k")?.to_string(), c.attribute("v")?.to_string())))
            .collect()
    };
    let mut nodes = HashMap::new();
    let mut ways = Vec::new();
    let mut relations = Vec::new();
    for n in root.children().filter(|n| n.is_element()) {
        match n.tag_name().name() {
            "node" => {
                nodes.insert(id(n, "id")?, [num(n, "lon")?, num(n, "lat")?]);
            }
            "way" => {
                let refs =
                    n.children().filter(|c| c.has_tag_name("nd")).map(|c| id(c, "ref")).collect::<Result<_, _>>()?;
                ways.push(Way { id: id(n, "id")?, refs, tags: tags(n) });
            }
            "relation" => {
                let t = tags(n);
                if is_multipolygon(&t) {
                    let members = n
                        .children()
                        .filter(|c| c.has_tag_name("member") && c.attribute("type") == Some("way"))
                        .map(|c| Ok(Member { way: id(c, "ref")?, role: c.attribute("role").unwrap_or("").to_string() }))
                        .collect::<Result<_, OsmError>>()?;
                    relations.push(Relation { id: id(n, "id")?, members, tags: t });
                }
            }
            _ => {}
        }
    }
    Ok(finish(nodes, ways, relations))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn xml_is_read_and_bad_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("a.osm");
        std::fs::write(
            &f,
            r#"<?xml version="1.0"?><osm version="0.6">
            <node id="1" lat="60.0" lon="24.0"/><node id="2" lat="60.001" lon="24.0"/>
            <way id="10"><nd ref="1"/><nd ref="2"/><tag k="highway" v="residential"/></way>
            <way id="11"><nd ref="1"/><nd ref="2"/><tag k="building" v="yes"/></way>
            </osm>"#,
        )
        .unwrap();
        let e = read(&f).unwrap();
        assert_eq!(e.nodes.len(), 2);
        assert_eq!(e.ways.len(), 1, "the building is not kept");
        assert_eq!(e.ways[0].tag("highway"), Some("residential"));
        assert_eq!(e.extent(), Some([24.0, 60.0, 24.0, 60.001]));
        std::fs::write(&f, "hello").unwrap();
        assert!(matches!(read(&f), Err(OsmError::NotOsm { .. })));
        std::fs::write(&f, "<osm><node id=\"x\" lat=\"1\" lon=\"2\"/></osm>").unwrap();
        let err = read(&f).unwrap_err().to_string();
        assert!(err.contains("line 1") && err.contains("`id`"), "{err}");
        std::fs::write(&f, "<osm version=\"0.6\"></osm>").unwrap();
        assert!(matches!(read(&f), Err(OsmError::Empty { .. })));
    }
}
