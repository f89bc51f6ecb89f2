//! The one way out to GIS: features in a local plane (model units, scaled to metres east and
//! north of a projection's origin) written as a GeoJSON `FeatureCollection` (RFC 7946, WGS 84
//! longitude and latitude) through [`Projection`], the transverse Mercator every netspec file
//! shares. Built on the `geojson` crate's types; written with sorted keys (the order of
//! `serde_json`'s maps), so equal designs give equal bytes.

use super::site::{Projection, SiteError};
use super::P;
use geojson::{Feature, FeatureCollection, Geometry, GeometryValue, JsonObject, Position};
use serde_json::Value;

/// Decimal places of the degrees written by default: 1e-8° is about a millimetre.
pub const DEFAULT_DIGITS: i32 = 8;

/// Features being collected for one GeoJSON file.
pub struct GeoJsonWriter<'a> {
    proj: &'a Projection,
    metres_per_unit: f64,
    digits: i32,
    features: Vec<Feature>,
}

impl<'a> GeoJsonWriter<'a> {
    /// A writer whose points are metres in `proj`'s plane, rounded to [`DEFAULT_DIGITS`].
    pub fn new(proj: &'a Projection) -> GeoJsonWriter<'a> {
        GeoJsonWriter { proj, metres_per_unit: 1.0, digits: DEFAULT_DIGITS, features: Vec::new() }
    }

    /// Points are model units of `metres_per_unit` metres each.
    pub fn scaled(mut self, metres_per_unit: f64) -> GeoJsonWriter<'a> {
        self.metres_per_unit = metres_per_unit;
        self
    }

    /// Degrees are rounded to `digits` decimal places.
    pub fn digits(mut self, digits: i32) -> GeoJsonWriter<'a> {
        self.digits = digits;
        self
    }

    /// A local point as rounded WGS 84 `[longitude, latitude]` degrees.
    pub fn lonlat(&self, p: P) -> Result<[f64; 2], SiteError> {
        let q = self.proj.to_wgs84([p[0] * self.metres_per_unit, p[1] * self.metres_per_unit])?;
        let k = 10f64.powi(self.digits);
        Ok([(q[0] * k).round() / k, (q[1] * k).round() / k])
    }

    fn positions(&self, pts: &[P]) -> Result<Vec<Position>, SiteError> {
        pts.iter().map(|&p| self.lonlat(p).map(Position::from)).collect()
    }

    /// A ring's positions, closed (its first point repeated at the end).
    fn ring(&self, ring: &[P]) -> Result<Vec<Position>, SiteError> {
        let mut out = self.positions(ring)?;
        if let Some(first) = out.first().cloned() {
            out.push(first);
        }
        Ok(out)
    }

    /// A feature of `value` whose properties are `properties` (an object; anything else, such as
    /// `Value::Null`, gives none).
    fn push(&mut self, value: GeometryValue, properties: Value) {
        let properties = match properties {
            Value::Object(map) => map,
            _ => JsonObject::new(),
        };
        self.features.push(Feature {
            geometry: Some(Geometry::new(value)),
            properties: Some(properties),
            ..Default::default()
        });
    }

    /// A `LineString` through `pts`.
    pub fn line(&mut self, pts: &[P], properties: Value) -> Result<(), SiteError> {
        let coordinates = self.positions(pts)?;
        self.push(GeometryValue::LineString { coordinates }, properties);
        Ok(())
    }

    /// A `MultiLineString` of `lines`.
    pub fn lines<'p>(&mut self, lines: impl IntoIterator<Item = &'p [P]>, properties: Value) -> Result<(), SiteError> {
        let coordinates = lines.into_iter().map(|l| self.positions(l)).collect::<Result<_, _>>()?;
        self.push(GeometryValue::MultiLineString { coordinates }, properties);
        Ok(())
    }

    /// A `Polygon`: the outer ring, then the holes (rings not closed; the writer closes them).
    pub fn polygon<'p>(
        &mut self,
        rings: impl IntoIterator<Item = &'p [P]>,
        properties: Value,
    ) -> Result<(), SiteError> {
        let coordinates = rings.into_iter().map(|r| self.ring(r)).collect::<Result<_, _>>()?;
        self.push(GeometryValue::Polygon { coordinates }, properties);
        Ok(())
    }

    /// A `Point`.
    pub fn point(&mut self, p: P, properties: Value) -> Result<(), SiteError> {
        let coordinates = Position::from(self.lonlat(p)?);
        self.push(GeometryValue::Point { coordinates }, properties);
        Ok(())
    }

    /// The collection, with `members` (an object, or `Value::Null` for none) as its foreign
    /// members (`name`, `properties`, `attribution`, …).
    pub fn into_value(self, members: Value) -> Value {
        let foreign_members = match members {
            Value::Object(map) if !map.is_empty() => Some(map),
            _ => None,
        };
        let fc = FeatureCollection { bbox: None, features: self.features, foreign_members };
        // Through a `Value`, whose maps sort their keys: one byte order for every writer.
        serde_json::to_value(&fc).expect("a feature collection is JSON")
    }

    /// The collection as compact JSON with a final newline ([`GeoJsonWriter::into_value`]).
    pub fn to_json(self, members: Value) -> String {
        serde_json::to_string(&self.into_value(members)).expect("JSON serialises") + "\n"
    }

    /// The collection as indented JSON with a final newline.
    pub fn to_json_pretty(self, members: Value) -> String {
        serde_json::to_string_pretty(&self.into_value(members)).expect("JSON serialises") + "\n"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn features_are_projected_rounded_closed_and_sorted() {
        let proj = Projection::new([7.42, 43.73]).expect("a WGS 84 origin");
        let mut w = GeoJsonWriter::new(&proj).scaled(10.0);
        w.line(&[[0.0, 0.0], [100.0, 0.0]], json!({"level": 2, "kind": "street"})).expect("projects");
        w.polygon([&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]][..]], json!({"kind": "parcel"})).expect("projects");
        w.point([0.0, 0.0], Value::Null).expect("projects");
        let text = w.to_json(json!({"name": "t"}));
        let v: Value = serde_json::from_str(&text).expect("JSON");
        assert!(text.starts_with(r#"{"features":[{"geometry":{"coordinates":[[7.42,43.73],"#), "{text}");
        assert_eq!(v["name"], "t");
        assert_eq!(v["type"], "FeatureCollection");
        let end = v["features"][0]["geometry"]["coordinates"][1].clone();
        // 1 km east of the origin at 43.73° N is about 0.01243° of longitude.
        let lon = end[0].as_f64().expect("a number");
        assert!((lon - 7.42 - 1000.0 / (111_320.0 * 43.73f64.to_radians().cos())).abs() < 1e-4, "{lon}");
        let lat = end[1].as_f64().expect("a number");
        assert!((lat - 43.73).abs() < 1e-5, "a kilometre east stays on the parallel within a metre: {lat}");
        let ring = v["features"][1]["geometry"]["coordinates"][0].as_array().expect("a ring").clone();
        assert_eq!(ring.len(), 4);
        assert_eq!(ring[0], ring[3], "rings are closed");
        assert_eq!(v["features"][2]["properties"], json!({}));
        let keys: Vec<&String> = v["features"][0].as_object().expect("an object").keys().collect();
        assert_eq!(keys, ["geometry", "properties", "type"]);
    }
}
