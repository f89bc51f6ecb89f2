//! Major roads from streamlines: a city's domain split by `netspec layout`'s control loop
//! (cross field, streamlines, the quality score), keeping the first cuts as the city's major
//! roads, so the IP designs the streets of the parts between them.

use super::spec::{CitySpec, CitySpecErrorKind, RoadSpec};
pub use super::spec::{MajorMethod, MajorSpec};
use crate::geometry::{site, Polygon};
use crate::layout::region::Region;
use crate::layout::split::{Selection, SplitOptions};
use crate::layout::tree::split;
use rand::rngs::Xoshiro256PlusPlus;
use rand::SeedableRng;

/// The spec with its streamline major roads added as `[[road]]` entries (named `streamline
/// k`, in model units) and `[major]` removed, so the rest of the city — and `city.json` —
/// sees given roads. A spec with no `[major]` or `method = "given"` is returned unchanged.
pub fn expand(mut spec: CitySpec) -> Result<CitySpec, CitySpecErrorKind> {
    let Some(major) = spec.major.take() else { return Ok(spec) };
    if major.method == MajorMethod::Given {
        return Ok(spec);
    }
    let err = |message: String| CitySpecErrorKind::Field { field: "major".into(), message };
    if major.depth == 0 {
        return Err(err("depth must be at least 1".into()));
    }
    let m = spec.metres_per_unit;
    let metres = |p: &[f64; 2]| [p[0] * m, p[1] * m];
    let polygon = Polygon::new(spec.domain.outer.iter().map(metres).collect(), Vec::new())
        .map_err(|e| err(format!("the domain cannot be split: {e}")))?;
    let mut roads = Vec::new();
    for (i, r) in spec.roads.iter().enumerate() {
        let line: Vec<[f64; 2]> = r.points.iter().map(metres).collect();
        roads.extend(site::clip_road(&polygon, &line, &format!("road[{i}]")).map_err(|e| err(e.to_string()))?);
    }
    let region = Region { seed: major.seed, ..Region::with_defaults(&spec.name, polygon, roads) };
    let opts = SplitOptions::for_region(&region, major.field, Selection::Best);
    let mut rng = Xoshiro256PlusPlus::seed_from_u64(major.seed);
    let s = split(&region, &opts, &mut rng).map_err(|e| err(e.to_string()))?;
    let round = |x: f64| (x * 1e6).round() / 1e6;
    for (k, street) in s.streets.iter().filter(|st| (1..=major.depth).contains(&st.level)).enumerate() {
        spec.roads.push(RoadSpec {
            name: format!("streamline {}", k + 1),
            points: street.polyline.iter().map(|p| [round(p[0] / m), round(p[1] / m)]).collect(),
        });
    }
    Ok(spec)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPEC: &str = r#"
name = "t"
metres_per_unit = 20
domain = { outer = [[0, 0], [30, 0], [30, 20], [0, 20]] }
mesh = { spacing = 1 }
[levels.2]
coverage = { range = 3 }
"#;

    /// The first cut of a 600 × 400 m domain becomes a major road from boundary to boundary,
    /// in model units; the same spec gives the same roads; `[major]` is gone from the result.
    #[test]
    fn streamlines_become_given_roads() {
        let text = format!("{SPEC}[major]\nmethod = \"streamlines\"\n");
        let spec = CitySpec::from_toml(&text).unwrap_or_else(|e| panic!("{e}"));
        assert!(spec.major.is_none());
        assert!(!spec.roads.is_empty(), "no streamline road");
        let on_boundary = |p: [f64; 2]| {
            p[0].abs() < 0.05 || p[1].abs() < 0.05 || (p[0] - 30.0).abs() < 0.05 || (p[1] - 20.0).abs() < 0.05
        };
        for r in &spec.roads {
            assert!(r.name.starts_with("streamline"));
            assert!(on_boundary(r.points[0]) && on_boundary(*r.points.last().unwrap()), "{:?}", r.points);
        }
        assert_eq!(spec, CitySpec::from_toml(&text).unwrap());
        let deeper = CitySpec::from_toml(&format!("{text}depth = 2\n")).unwrap();
        assert!(deeper.roads.len() > spec.roads.len());
        let given = CitySpec::from_toml(&format!("{SPEC}[major]\nmethod = \"given\"\n")).unwrap();
        assert!(given.roads.is_empty());
        let e = CitySpec::from_toml(&format!("{text}depth = 0\n")).unwrap_err().to_string();
        assert!(e.contains("major") && e.contains("depth"), "{e}");
    }
}
