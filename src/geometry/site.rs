//! Sites: a region drawn in WGS 84 (GeoJSON, as QGIS and OpenStreetMap exports write it),
//! projected to local metres by a transverse Mercator centred on the site, and back.
//!
//! A site file is a GeoJSON `FeatureCollection` (or a single `Feature`/`Polygon`): its one
//! `Polygon` feature without a `use` property is the region (its inner rings are holes),
//! further `Polygon` features with a `use` property are zones (land marked for a use, one ring
//! each; the caller checks the use and where they lie), and `LineString` features whose
//! `kind` property is `"road"` are major roads. The polygon feature's `origin` property
//! (`[longitude, latitude]`), when present, is the projection's centre (so that several files
//! of one site share their metres, as `netspec site` writes them); otherwise the centre of the
//! region's bounding box is. A road is clipped to the region and split where it crosses a hole
//! (a bridge over water is no street of the site). The polygon feature's other properties are
//! returned to the caller (settings such as the parcel size).

use super::polygon::{Polygon, PolygonError};
use super::P;
use geo::BooleanOps;
use proj4rs::proj::Proj;
use serde_json::{Map, Value};
use thiserror::Error;

/// Why a site was refused. `feature` is the 0-based index in the collection.
#[derive(Debug, Error)]
pub enum SiteError {
    /// Not GeoJSON.
    #[error("not GeoJSON: {0}")]
    Json(String),
    /// No polygon feature.
    #[error("no Polygon feature: a site needs one polygon (the region)")]
    NoPolygon,
    /// More than one polygon feature.
    #[error("features[{second}] is a second Polygon (features[{first}] is the region); a site has one")]
    TwoPolygons {
        /// The first.
        first: usize,
        /// The second.
        second: usize,
    },
    /// A zone with inner rings, or whose `use` is not a string.
    #[error("features[{feature}] (a zone): {problem}")]
    Zone {
        /// The feature.
        feature: usize,
        /// Why.
        problem: String,
    },
    /// A geometry of a type the site does not use.
    #[error("features[{feature}].geometry: a {kind} is not part of a site (a Polygon region and LineString roads)")]
    Unsupported {
        /// The feature.
        feature: usize,
        /// Its geometry type.
        kind: String,
    },
    /// A position outside WGS 84's range or not finite.
    #[error("features[{feature}].geometry: position {position} ({lon}, {lat}) is not a WGS 84 longitude/latitude")]
    NotWgs84 {
        /// The feature.
        feature: usize,
        /// The position's index along the feature's rings or line.
        position: usize,
        /// Its longitude.
        lon: f64,
        /// Its latitude.
        lat: f64,
    },
    /// The region polygon is invalid.
    #[error("features[{feature}] (the region): {source}")]
    Polygon {
        /// The feature.
        feature: usize,
        /// Why.
        source: PolygonError,
    },
    /// A road is invalid or does not fit the region.
    #[error("{what}: {problem}")]
    Road {
        /// Which road (a GeoJSON feature path or a TOML key).
        what: String,
        /// Why.
        problem: RoadProblem,
    },
    /// The projection failed.
    #[error("projection: {0}")]
    Projection(String),
}

/// What is wrong with a road.
#[derive(Debug, Error, PartialEq)]
pub enum RoadProblem {
    /// Fewer than two distinct points.
    #[error("a road needs at least 2 distinct points")]
    TooShort,
    /// A coordinate is not finite.
    #[error("point {0} is not finite")]
    NotFinite(usize),
    /// No part of it is inside the region.
    #[error("the road lies outside the region")]
    Outside,
}

/// A transverse Mercator projection centred on a WGS 84 origin (metres east and north of it).
#[derive(Debug)]
pub struct Projection {
    origin: [f64; 2],
    local: Proj,
    wgs84: Proj,
}

impl Clone for Projection {
    fn clone(&self) -> Self {
        Projection::new(self.origin).expect("an origin that projected once projects again")
    }
}

impl Projection {
    /// The projection centred on `origin` (`[longitude, latitude]` degrees).
    pub fn new(origin: [f64; 2]) -> Result<Projection, SiteError> {
        let [lon0, lat0] = origin;
        if !(lon0.is_finite() && lat0.is_finite() && lon0.abs() <= 180.0 && lat0.abs() < 90.0) {
            return Err(SiteError::Projection(format!("origin ({lon0}, {lat0}) is not a WGS 84 position")));
        }
        let def = format!("+proj=tmerc +lat_0={lat0} +lon_0={lon0} +k=1 +x_0=0 +y_0=0 +ellps=WGS84 +units=m +no_defs");
        let local = Proj::from_proj_string(&def).map_err(|e| SiteError::Projection(e.to_string()))?;
        let wgs84 = Proj::from_proj_string("+proj=longlat +ellps=WGS84 +datum=WGS84 +no_defs")
            .map_err(|e| SiteError::Projection(e.to_string()))?;
        Ok(Projection { origin, local, wgs84 })
    }

    /// The origin, `[longitude, latitude]` degrees.
    pub fn origin(&self) -> [f64; 2] {
        self.origin
    }

    /// A WGS 84 position (degrees) in local metres.
    pub fn to_local(&self, lonlat: [f64; 2]) -> Result<P, SiteError> {
        let mut p = (lonlat[0].to_radians(), lonlat[1].to_radians(), 0.0);
        proj4rs::transform::transform(&self.wgs84, &self.local, &mut p)
            .map_err(|e| SiteError::Projection(e.to_string()))?;
        Ok([p.0, p.1])
    }

    /// A local point (metres) as WGS 84 `[longitude, latitude]` degrees.
    pub fn to_wgs84(&self, p: P) -> Result<[f64; 2], SiteError> {
        let mut q = (p[0], p[1], 0.0);
        proj4rs::transform::transform(&self.local, &self.wgs84, &mut q)
            .map_err(|e| SiteError::Projection(e.to_string()))?;
        Ok([q.0.to_degrees(), q.1.to_degrees()])
    }
}

/// A site read from GeoJSON, in local metres.
#[derive(Clone, Debug)]
pub struct Site {
    /// The region.
    pub polygon: Polygon,
    /// Major roads, clipped to the region (a road leaving and re-entering gives several pieces).
    pub roads: Vec<Vec<P>>,
    /// The projection between the file's WGS 84 and the local metres.
    pub projection: Projection,
    /// The region feature's properties.
    pub properties: Map<String, Value>,
    /// The zones, in file order.
    pub zones: Vec<SiteZone>,
}

/// A zone of a site: a further `Polygon` feature with a `use` property, in local metres.
#[derive(Clone, Debug, PartialEq)]
pub struct SiteZone {
    /// Its index in the collection.
    pub feature: usize,
    /// Its ring.
    pub ring: Vec<P>,
    /// Its `use`, as written.
    pub use_: String,
}

/// The region feature: its index, rings (WGS 84) and properties.
type RegionFeature = (usize, Vec<Vec<[f64; 2]>>, Map<String, Value>);

/// Reads a site from GeoJSON text (see the module documentation).
pub fn read_geojson(text: &str) -> Result<Site, SiteError> {
    let gj: geojson::GeoJson = text.parse().map_err(|e: geojson::Error| SiteError::Json(e.to_string()))?;
    let features: Vec<geojson::Feature> = match gj {
        geojson::GeoJson::FeatureCollection(fc) => fc.features,
        geojson::GeoJson::Feature(f) => vec![f],
        geojson::GeoJson::Geometry(g) => vec![geojson::Feature { geometry: Some(g), ..Default::default() }],
    };
    let mut region: Option<RegionFeature> = None;
    let mut roads: Vec<(usize, Vec<[f64; 2]>)> = Vec::new();
    let mut zones: Vec<(usize, Vec<[f64; 2]>, String)> = Vec::new();
    for (i, f) in features.iter().enumerate() {
        let Some(g) = &f.geometry else { continue };
        let props = f.properties.clone().unwrap_or_default();
        match &g.value {
            geojson::GeometryValue::Polygon { coordinates } if props.contains_key("use") => {
                let zone = |problem: String| SiteError::Zone { feature: i, problem };
                let use_ =
                    props["use"].as_str().ok_or_else(|| zone(format!("use = {} is not a string", props["use"])))?;
                if coordinates.len() > 1 {
                    return Err(zone("a zone is one ring; it has inner rings".into()));
                }
                let ring = coordinates.first().map(|r| positions(i, r)).transpose()?.unwrap_or_default();
                zones.push((i, ring, use_.to_string()));
            }
            geojson::GeometryValue::Polygon { coordinates } => {
                if let Some((first, ..)) = &region {
                    return Err(SiteError::TwoPolygons { first: *first, second: i });
                }
                let rings = coordinates.iter().map(|r| positions(i, r)).collect::<Result<Vec<_>, _>>()?;
                region = Some((i, rings, props));
            }
            geojson::GeometryValue::LineString { coordinates } => {
                if props.get("kind").and_then(Value::as_str) == Some("road") {
                    roads.push((i, positions(i, coordinates)?));
                }
            }
            geojson::GeometryValue::Point { .. } | geojson::GeometryValue::MultiPoint { .. } => {}
            other => return Err(SiteError::Unsupported { feature: i, kind: other.type_name().to_string() }),
        }
    }
    let (feature, rings, properties) = region.ok_or(SiteError::NoPolygon)?;
    let origin = match properties.get("origin") {
        None => centre(&rings[0]),
        Some(v) => serde_json::from_value::<[f64; 2]>(v.clone()).map_err(|_| {
            SiteError::Projection(format!("features[{feature}].properties.origin: {v} is not [longitude, latitude]"))
        })?,
    };
    let projection = Projection::new(origin)?;
    let local = |ring: &[[f64; 2]]| ring.iter().map(|&q| projection.to_local(q)).collect::<Result<Vec<P>, _>>();
    let mut rings_m = rings.iter().map(|r| local(r)).collect::<Result<Vec<_>, _>>()?.into_iter();
    let outer = rings_m.next().unwrap_or_default();
    let polygon = Polygon::new(outer, rings_m.collect()).map_err(|source| SiteError::Polygon { feature, source })?;
    let mut clipped = Vec::new();
    for (i, road) in &roads {
        let what = format!("features[{i}] (a road)");
        clipped.extend(clip_road(&polygon, &local(road)?, &what)?);
    }
    let zones = zones
        .iter()
        .map(|(feature, ring, use_)| Ok(SiteZone { feature: *feature, ring: local(ring)?, use_: use_.clone() }))
        .collect::<Result<Vec<_>, SiteError>>()?;
    Ok(Site { polygon, roads: clipped, projection, properties, zones })
}

/// A road clipped to a region: the pieces inside it (split where it crosses a hole), or an error
/// naming `what` when the road has too few points, a non-finite one, or lies outside.
pub fn clip_road(polygon: &Polygon, road: &[P], what: &str) -> Result<Vec<Vec<P>>, SiteError> {
    let err = |problem| SiteError::Road { what: what.to_string(), problem };
    if let Some(i) = road.iter().position(|p| !(p[0].is_finite() && p[1].is_finite())) {
        return Err(err(RoadProblem::NotFinite(i)));
    }
    let mut pts: Vec<P> = Vec::new();
    for &p in road {
        if pts.last() != Some(&p) {
            pts.push(p);
        }
    }
    if pts.len() < 2 {
        return Err(err(RoadProblem::TooShort));
    }
    let line =
        geo::MultiLineString::new(vec![geo::LineString::from(pts.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>())]);
    let inside = polygon.to_geo().clip(&line, false);
    let pieces: Vec<Vec<P>> = inside
        .0
        .iter()
        .map(|l| l.0.iter().map(|c| [c.x, c.y]).collect::<Vec<P>>())
        .filter(|l| l.len() >= 2 && super::polyline_length(l) > 4.0 * SHORE)
        .map(|l| off_the_holes(polygon, l))
        .collect();
    if pieces.is_empty() {
        return Err(err(RoadProblem::Outside));
    }
    Ok(pieces)
}

/// How far (metres) a road piece that ends on a hole's edge stops short of it.
const SHORE: f64 = 0.01;

/// A road piece whose end lies on a hole's edge (where the clip split it) pulled back by
/// [`SHORE`] along itself, so that no rounding puts the end inside the hole.
fn off_the_holes(polygon: &Polygon, mut piece: Vec<P>) -> Vec<P> {
    let on_hole = |p: P| {
        polygon.holes().iter().any(|h| {
            (0..h.len()).any(|k| super::dist(p, super::closest_on_segment(p, h[k], h[(k + 1) % h.len()]).0) <= SHORE)
        })
    };
    for reversed in [false, true] {
        if reversed {
            piece.reverse();
        }
        let (a, b) = (piece[0], piece[1]);
        let l = super::dist(a, b);
        if on_hole(a) && l > 2.0 * SHORE {
            piece[0] = super::lerp(a, b, SHORE / l);
        }
    }
    piece.reverse();
    piece
}

fn positions(feature: usize, ring: &[geojson::Position]) -> Result<Vec<[f64; 2]>, SiteError> {
    ring.iter()
        .enumerate()
        .map(|(position, p)| {
            let s = p.as_slice();
            let (lon, lat) = (s.first().copied().unwrap_or(f64::NAN), s.get(1).copied().unwrap_or(f64::NAN));
            if lon.is_finite() && lat.is_finite() && lon.abs() <= 180.0 && lat.abs() < 90.0 {
                Ok([lon, lat])
            } else {
                Err(SiteError::NotWgs84 { feature, position, lon, lat })
            }
        })
        .collect()
}

/// The centre of a ring's bounding box (the projection's origin).
fn centre(ring: &[[f64; 2]]) -> [f64; 2] {
    let [lo, hi] = super::polygon::bounds(ring);
    [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])]
}

#[cfg(test)]
mod tests {
    use super::*;

    const SITE: &str = r#"{"type": "FeatureCollection", "features": [
      {"type": "Feature", "properties": {"name": "block"}, "geometry": {"type": "Polygon", "coordinates": [
        [[11.0, 48.0], [11.01, 48.0], [11.01, 48.01], [11.0, 48.01], [11.0, 48.0]],
        [[11.004, 48.004], [11.004, 48.006], [11.006, 48.006], [11.006, 48.004], [11.004, 48.004]]]}},
      {"type": "Feature", "properties": {"kind": "road"}, "geometry": {"type": "LineString", "coordinates": [
        [10.99, 48.002], [11.02, 48.002]]}},
      {"type": "Feature", "properties": {"kind": "path"}, "geometry": {"type": "LineString", "coordinates": [
        [11.0, 48.0], [11.01, 48.01]]}}]}"#;

    #[test]
    fn a_site_is_projected_to_metres_and_back() {
        let site = read_geojson(SITE).unwrap();
        assert_eq!(site.polygon.holes().len(), 1);
        // 0.01° of longitude at 48° N is about 744 m, 0.01° of latitude about 1,112 m.
        let [lo, hi] = site.polygon.bounds();
        assert!((hi[0] - lo[0] - 744.5).abs() < 2.0, "{lo:?} {hi:?}");
        assert!((hi[1] - lo[1] - 1112.0).abs() < 2.0);
        assert_eq!(site.roads.len(), 1, "the road is clipped; the path is not a road");
        for end in [site.roads[0][0], *site.roads[0].last().unwrap()] {
            // Clipping works on a fixed-point grid (i_overlay): ends are within micrometres.
            assert!(site.polygon.boundary_distance(end) < 1e-5, "{end:?} ends on the boundary");
        }
        let back = site.projection.to_wgs84(site.polygon.outer()[0]).unwrap();
        assert!((back[0] - 11.0).abs() < 1e-9 && (back[1] - 48.0).abs() < 1e-9, "{back:?}");
        assert_eq!(site.properties["name"], "block");
    }

    #[test]
    fn a_road_across_a_hole_is_split_there_and_an_origin_fixes_the_frame() {
        let across = SITE.replace("[10.99, 48.002], [11.02, 48.002]", "[10.99, 48.005], [11.02, 48.005]");
        let site = read_geojson(&across).unwrap();
        assert_eq!(site.roads.len(), 2, "the bridge over the hole is left out");
        let hole = &site.polygon.holes()[0];
        for piece in &site.roads {
            let mids = piece.windows(2).map(|w| crate::geometry::lerp(w[0], w[1], 0.5));
            assert!(mids.clone().all(|p| !crate::geometry::ring_contains(hole, p)), "{piece:?}");
        }
        let fixed = SITE.replace("\"name\": \"block\"", "\"name\": \"block\", \"origin\": [11.0, 48.0]");
        let site = read_geojson(&fixed).unwrap();
        assert_eq!(site.projection.origin(), [11.0, 48.0]);
        let p = site.polygon.outer().iter().find(|p| p[0].abs() < 1e-6 && p[1].abs() < 1e-6);
        assert!(p.is_some(), "the corner at the origin is at (0, 0): {:?}", site.polygon.outer());
        let bad = SITE.replace("\"name\": \"block\"", "\"name\": \"block\", \"origin\": \"here\"");
        assert!(read_geojson(&bad).unwrap_err().to_string().contains("properties.origin"));
    }

    #[test]
    fn bad_sites_name_the_feature() {
        let e = read_geojson(&SITE.replace("[10.99, 48.002], [11.02, 48.002]", "[10.99, 48.002]")).unwrap_err();
        assert!(matches!(e, SiteError::Road { problem: RoadProblem::TooShort, .. }), "{e}");
        assert!(e.to_string().starts_with("features[1]"));
        let outside = SITE.replace("[10.99, 48.002], [11.02, 48.002]", "[12.0, 48.0], [12.1, 48.0]");
        assert!(matches!(read_geojson(&outside), Err(SiteError::Road { problem: RoadProblem::Outside, .. })));
        let bad = SITE.replace("[11.01, 48.0], [11.01, 48.01]", "[181.0, 48.0], [11.01, 48.01]");
        assert!(matches!(read_geojson(&bad), Err(SiteError::NotWgs84 { feature: 0, position: 1, .. })));
        let bow = SITE.replace("[11.01, 48.0], [11.01, 48.01]", "[11.01, 48.01], [11.01, 48.0]");
        assert!(matches!(read_geojson(&bow), Err(SiteError::Polygon { feature: 0, .. })));
        assert!(matches!(
            read_geojson("{\"type\": \"FeatureCollection\", \"features\": []}"),
            Err(SiteError::NoPolygon)
        ));
        assert!(matches!(read_geojson("not json"), Err(SiteError::Json(_))));
    }

    #[test]
    fn further_polygons_with_a_use_are_zones_and_a_second_region_is_still_refused() {
        let zone = r#"{"type": "Feature", "properties": {"use": "park"}, "geometry": {"type": "Polygon",
            "coordinates": [[[11.001, 48.001], [11.003, 48.001], [11.003, 48.003], [11.001, 48.003], [11.001, 48.001]]]}}"#;
        let with = SITE.replacen("\"features\": [", &format!("\"features\": [{zone}, "), 1);
        let site = read_geojson(&with).unwrap();
        assert_eq!(site.zones.len(), 1);
        assert_eq!((site.zones[0].feature, site.zones[0].use_.as_str(), site.zones[0].ring.len()), (0, "park", 5));
        assert_eq!(site.properties["name"], "block", "the region is the polygon without a use");
        assert_eq!(site.roads.len(), 1);
        let second = zone.replace("\"use\": \"park\"", "\"name\": \"another\"");
        let two = SITE.replacen("\"features\": [", &format!("\"features\": [{second}, "), 1);
        assert!(matches!(read_geojson(&two), Err(SiteError::TwoPolygons { first: 0, second: 1 })));
        let bad = SITE.replacen("\"features\": [", &format!("\"features\": [{}, ", zone.replace("\"park\"", "3")), 1);
        let e = read_geojson(&bad).unwrap_err().to_string();
        assert_eq!(e, "features[0] (a zone): use = 3 is not a string");
    }
}
