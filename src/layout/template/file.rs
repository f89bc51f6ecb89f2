//! Template files: one template per TOML file, read and checked with errors that name the file
//! and the field (`face[2].stretch`). The built-in library is embedded, so a clean clone works;
//! a region's `[templates] dir` adds the user's own files (a file of the same `name` replaces the
//! built-in one).
//!
//! Coordinates are metres for the default parcel (30 m deep, 18 m wide) and a 15 m street; a
//! template is scaled uniformly by `depth / 30` for other parcel sizes.

use crate::geometry::{ring_area2, P};
use crate::layout::Use;
use serde::Deserialize;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The built-in templates: (file name, text).
pub const BUILTIN: [(&str, &str); 13] = [
    ("row.toml", include_str!("../../../models/layout/templates/row.toml")),
    ("double.toml", include_str!("../../../models/layout/templates/double.toml")),
    ("spike.toml", include_str!("../../../models/layout/templates/spike.toml")),
    ("park.toml", include_str!("../../../models/layout/templates/park.toml")),
    ("townhouses.toml", include_str!("../../../models/layout/templates/townhouses.toml")),
    ("apartments.toml", include_str!("../../../models/layout/templates/apartments.toml")),
    ("mixed.toml", include_str!("../../../models/layout/templates/mixed.toml")),
    ("area-townhouses.toml", include_str!("../../../models/layout/templates/area-townhouses.toml")),
    ("area-apartments.toml", include_str!("../../../models/layout/templates/area-apartments.toml")),
    ("area-shops.toml", include_str!("../../../models/layout/templates/area-shops.toml")),
    ("area-park.toml", include_str!("../../../models/layout/templates/area-park.toml")),
    ("school.toml", include_str!("../../../models/layout/templates/school.toml")),
    ("commercial.toml", include_str!("../../../models/layout/templates/commercial.toml")),
];

/// The labels a template may fill (its `kind`): a part between streets (`block`), an area face of
/// another template (`area`), or a zone of that use.
pub const LABELS: [&str; 5] = ["block", "area", "park", "school", "commercial"];

pub use super::model::{Class, CornerKind, Face, Fill, Repeat, SideKind, Template};

/// Why a template file was refused; every variant names the file, and the field where one is at
/// fault.
#[derive(Debug, Error)]
pub enum TemplateError {
    /// A file or directory could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Malformed TOML, a missing, mistyped or unknown key (the message names the line and key).
    #[error("{path}: {message}")]
    Toml {
        /// The file.
        path: String,
        /// The parser's message.
        message: String,
    },
    /// A value out of range or inconsistent.
    #[error("{path}: {field}: {message}")]
    Field {
        /// The file.
        path: String,
        /// The field, e.g. `face[2].stretch`.
        field: String,
        /// What is wrong.
        message: String,
    },
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileToml {
    name: Option<String>,
    kind: String,
    #[serde(default)]
    max_uses: Option<usize>,
    #[serde(default)]
    min_uses: Option<usize>,
    #[serde(default)]
    probability: Option<f64>,
    #[serde(default)]
    threshold: Option<f64>,
    #[serde(default)]
    repeat: Option<RepeatToml>,
    #[serde(default)]
    side: Vec<SideToml>,
    #[serde(default)]
    corner: Vec<CornerToml>,
    face: Vec<FaceToml>,
    #[serde(default)]
    street: Vec<StreetToml>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RepeatToml {
    axis: String,
    unit: [f64; 2],
    #[serde(default = "one")]
    min: usize,
    #[serde(default = "forty")]
    max: usize,
}

fn one() -> usize {
    1
}
fn forty() -> usize {
    40
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct SideToml {
    at: [f64; 2],
    kind: SideKind,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct CornerToml {
    at: [f64; 2],
    kind: CornerKind,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FaceToml {
    polygon: Vec<[f64; 2]>,
    #[serde(rename = "use")]
    use_: String,
    #[serde(default = "affine")]
    class: String,
    #[serde(default)]
    scale: Option<[f64; 2]>,
    #[serde(default)]
    stretch: Option<[[f64; 2]; 2]>,
    #[serde(default)]
    area: Option<[f64; 2]>,
    #[serde(default = "three")]
    tolerance: f64,
}

fn affine() -> String {
    "affine".into()
}
fn three() -> f64 {
    3.0
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct StreetToml {
    line: Vec<[f64; 2]>,
}

/// Reads a template from TOML text; `path` names it in errors, `stem` is its default name.
pub fn parse_template(text: &str, path: &str, stem: &str) -> Result<Template, TemplateError> {
    let t: FileToml =
        toml::from_str(text).map_err(|e| TemplateError::Toml { path: path.into(), message: e.to_string() })?;
    let bad = |field: String, message: String| TemplateError::Field { path: path.into(), field, message };
    let positive_range = |field: String, r: [f64; 2]| {
        if r.iter().all(|v| v.is_finite() && *v > 0.0) && r[0] <= r[1] {
            Ok(r)
        } else {
            Err(bad(field, format!("[{}, {}] is not a range of positive numbers, low first", r[0], r[1])))
        }
    };
    if t.face.is_empty() {
        return Err(bad("face".into(), "a template needs at least one face".into()));
    }
    if !LABELS.contains(&t.kind.as_str()) {
        return Err(bad(
            "kind".into(),
            format!("\"{}\" is not a label a template fills ({})", t.kind, LABELS.join(", ")),
        ));
    }
    let mut faces = Vec::new();
    for (i, f) in t.face.iter().enumerate() {
        let mut polygon: Vec<P> = f.polygon.clone();
        if polygon.len() > 1 && polygon.first() == polygon.last() {
            polygon.pop();
        }
        if polygon.len() < 3 || polygon.iter().flatten().any(|v| !v.is_finite()) {
            return Err(bad(format!("face[{i}].polygon"), "needs at least three finite vertices".into()));
        }
        let a2 = ring_area2(&polygon);
        if a2.abs() < 1e-9 {
            return Err(bad(format!("face[{i}].polygon"), "encloses no area".into()));
        }
        if a2 < 0.0 {
            polygon.reverse();
        }
        let class = match (f.class.as_str(), f.scale, f.stretch, f.area) {
            ("rigid", None, None, None) => Class::Rigid,
            ("similarity", s, None, None) => {
                Class::Similarity { scale: positive_range(format!("face[{i}].scale"), s.unwrap_or([0.0001, 1e4]))? }
            }
            ("affine", None, None, None) => Class::Affine,
            ("affine", None, Some([x, y]), None) => Class::Stretch {
                x: positive_range(format!("face[{i}].stretch[0]"), x)?,
                y: positive_range(format!("face[{i}].stretch[1]"), y)?,
            },
            ("affine", None, None, Some(a)) => {
                Class::AreaAffine { area: positive_range(format!("face[{i}].area"), a)? }
            }
            ("rigid" | "similarity" | "affine", Some(_), _, _) => {
                return Err(bad(format!("face[{i}].scale"), "only a similarity has a scale range".into()))
            }
            ("rigid" | "similarity", _, Some(_), _) => {
                return Err(bad(format!("face[{i}].stretch"), "only an affine class has stretch ranges".into()))
            }
            ("rigid" | "similarity", _, _, Some(_)) => {
                return Err(bad(format!("face[{i}].area"), "only an affine class has an area range".into()))
            }
            ("affine", _, Some(_), Some(_)) => {
                return Err(bad(
                    format!("face[{i}].area"),
                    "an affine face takes stretch ranges or an area range, not both".into(),
                ))
            }
            (other, _, _, _) => {
                return Err(bad(format!("face[{i}].class"), format!("\"{other}\" is not rigid, similarity or affine")))
            }
        };
        if !(f.tolerance.is_finite() && f.tolerance > 0.0) {
            return Err(bad(format!("face[{i}].tolerance"), format!("{} is not a positive number", f.tolerance)));
        }
        let fill = match f.use_.as_str() {
            "area" => Fill::Area,
            "residential" => Fill::Use(Use::Residential),
            "park" => Fill::Use(Use::Park),
            "commercial" => Fill::Use(Use::Commercial),
            "school" => Fill::Use(Use::School),
            "other" => Fill::Use(Use::Other),
            other => {
                return Err(bad(
                    format!("face[{i}].use"),
                    format!("\"{other}\" is not residential, park, commercial, school, other or area"),
                ))
            }
        };
        faces.push(Face { polygon, fill, class, tolerance: f.tolerance });
    }
    let repeat = match &t.repeat {
        None => None,
        Some(r) => {
            let axis = match r.axis.as_str() {
                "x" => 0,
                "y" => 1,
                other => return Err(bad("repeat.axis".into(), format!("\"{other}\" is not \"x\" or \"y\""))),
            };
            if !(r.unit[0].is_finite() && r.unit[1].is_finite() && r.unit[1] > r.unit[0]) {
                return Err(bad("repeat.unit".into(), "needs [from, to] with from < to".into()));
            }
            if r.min == 0 || r.min > r.max {
                return Err(bad("repeat.min".into(), format!("needs 1 ≤ min ≤ max, got {} and {}", r.min, r.max)));
            }
            Some(Repeat { axis, unit: r.unit, min: r.min, max: r.max })
        }
    };
    if let Some(threshold) = t.threshold.filter(|v| !(v.is_finite() && *v > 0.0)) {
        return Err(bad("threshold".into(), format!("{threshold} is not a positive number")));
    }
    let probability = t.probability.unwrap_or(1.0);
    if !(probability.is_finite() && probability > 0.0) {
        return Err(bad("probability".into(), format!("{probability} is not a positive number")));
    }
    let min_uses = t.min_uses.unwrap_or(0);
    if let Some(max) = t.max_uses.filter(|&m| m < min_uses) {
        return Err(bad("min_uses".into(), format!("{min_uses} is more than max_uses = {max}")));
    }
    let vertices: Vec<P> = faces.iter().flat_map(|f| f.polygon.iter().copied()).collect();
    let is_vertex = |p: P| vertices.iter().any(|v| (v[0] - p[0]).abs() < 1e-6 && (v[1] - p[1]).abs() < 1e-6);
    for (i, s) in t.street.iter().enumerate() {
        if s.line.len() < 2 {
            return Err(bad(format!("street[{i}].line"), "needs at least two points".into()));
        }
        if let Some(k) = s.line.iter().position(|&p| !is_vertex(p)) {
            return Err(bad(format!("street[{i}].line[{k}]"), "is not a vertex of a face".into()));
        }
    }
    for (i, c) in t.corner.iter().enumerate() {
        if !is_vertex(c.at) {
            return Err(bad(format!("corner[{i}].at"), "is not a vertex of a face".into()));
        }
    }
    let template = Template {
        name: t.name.unwrap_or_else(|| stem.to_string()),
        kind: t.kind,
        faces,
        streets: t.street.into_iter().map(|s| s.line).collect(),
        sides: t.side.into_iter().map(|s| (s.at, s.kind)).collect(),
        corners: t.corner.into_iter().map(|c| (c.at, c.kind)).collect(),
        repeat,
        max_uses: t.max_uses,
        min_uses,
        probability,
        threshold: t.threshold,
        source: path.into(),
    };
    let units = template.repeat.map_or(1, |r| r.min);
    super::instance::instantiate(&template, units, 1.0).map_err(|e| bad("face".into(), e.to_string()))?;
    Ok(template)
}

/// The built-in templates.
pub fn builtin() -> Vec<Template> {
    BUILTIN
        .iter()
        .map(|(file, text)| {
            let stem = file.trim_end_matches(".toml");
            parse_template(text, &format!("builtin:{file}"), stem).expect("built-in templates are valid")
        })
        .collect()
}

/// The built-in templates (unless `with_builtin` is false) with the `*.toml` files of `dir` (in
/// file-name order); a user template replaces the built-in one of the same name.
pub fn library(dir: Option<&Path>, with_builtin: bool) -> Result<Vec<Template>, TemplateError> {
    let mut out = if with_builtin { builtin() } else { vec![] };
    let Some(dir) = dir else { return Ok(out) };
    let io = |source| TemplateError::Io { path: dir.into(), source };
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(io)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    for f in files {
        let text = std::fs::read_to_string(&f).map_err(|source| TemplateError::Io { path: f.clone(), source })?;
        let stem = f.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
        let t = parse_template(&text, &f.display().to_string(), &stem)?;
        out.retain(|b| b.name != t.name);
        out.push(t);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ROW: &str =
        "kind = \"block\"\n[[face]]\npolygon = [[0, 0], [18, 0], [18, 30], [0, 30]]\nuse = \"residential\"\n";

    fn err(text: &str) -> String {
        parse_template(text, "t.toml", "t").unwrap_err().to_string()
    }

    #[test]
    fn the_builtin_library_parses() {
        let lib = builtin();
        assert_eq!(lib.len(), 13);
        assert!(lib.iter().any(|t| !t.streets.is_empty()), "a template with a street");
        assert!(lib.iter().any(|t| t.kind == "area"), "an area template");
        assert!(lib.iter().any(|t| t.faces.iter().any(|f| f.fill == Fill::Area)), "a template with an area face");
        assert!(lib.iter().any(|t| t.faces.iter().any(|f| f.fill == Fill::Use(Use::Park))), "a private park");
        let school = lib.iter().find(|t| t.kind == "school").expect("a school template");
        assert!(school.faces.len() >= 2 && school.faces.iter().all(|f| f.fill == Fill::Use(Use::School)));
        assert!(lib.iter().any(|t| t.probability < 1.0), "a less common template");
    }

    #[test]
    fn errors_name_the_file_and_field() {
        let t = parse_template(ROW, "t.toml", "t").unwrap();
        assert_eq!((t.name.as_str(), t.faces[0].class), ("t", Class::Affine));
        assert!(err(&ROW.replace("use = \"residential\"", "use = \"mall\"")).contains("face[0].use"));
        let e = err(&ROW.replace("kind = \"block\"", "kind = \"row\""));
        assert!(e.starts_with("t.toml: kind: \"row\" is not a label"), "{e}");
        let e = err(&format!("max_uses = 1\nmin_uses = 2\n{ROW}"));
        assert!(e.starts_with("t.toml: min_uses:"), "{e}");
        let e = err(&format!("probability = 0\n{ROW}"));
        assert!(e.starts_with("t.toml: probability:"), "{e}");
        let e = err(&format!("{ROW}class = \"melt\"\n"));
        assert_eq!(e, "t.toml: face[0].class: \"melt\" is not rigid, similarity or affine");
        let e = err(&format!("{ROW}class = \"affine\"\nstretch = [[1.2, 0.8], [1, 1]]\n"));
        assert!(e.starts_with("t.toml: face[0].stretch[0]:"), "{e}");
        let e = err(&format!("{ROW}class = \"rigid\"\nscale = [1, 2]\n"));
        assert!(e.starts_with("t.toml: face[0].scale:"), "{e}");
        let e = err(&format!("{ROW}tolerance = -1\n"));
        assert!(e.starts_with("t.toml: face[0].tolerance:"), "{e}");
        let e = err(&format!("{ROW}[[street]]\nline = [[0, 0], [9, 15]]\n"));
        assert_eq!(e, "t.toml: street[0].line[1]: is not a vertex of a face");
        let e = err(&format!("{ROW}[repeat]\naxis = \"z\"\nunit = [0, 18]\n"));
        assert!(e.starts_with("t.toml: repeat.axis:"), "{e}");
        let e = err(&format!("colour = 3\n{ROW}"));
        assert!(e.contains("colour"), "{e}");
        assert!(err("kind = \"block\"\n").contains("face"));
        let apart = format!("{ROW}[[face]]\npolygon = [[50, 0], [60, 0], [60, 10]]\nuse = \"park\"\n");
        assert_eq!(err(&apart), "t.toml: face: the faces do not form one polygon without holes");
    }

    #[test]
    fn an_affine_face_takes_an_area_range() {
        let t = parse_template(&format!("{ROW}class = \"affine\"\narea = [0.8, 1.25]\n"), "t.toml", "t").unwrap();
        assert_eq!(t.faces[0].class, Class::AreaAffine { area: [0.8, 1.25] });
        let e = err(&format!("{ROW}class = \"affine\"\nstretch = [[0.8, 1.25], [0.8, 1.25]]\narea = [0.8, 1.25]\n"));
        assert_eq!(e, "t.toml: face[0].area: an affine face takes stretch ranges or an area range, not both");
        let e = err(&format!("{ROW}class = \"similarity\"\narea = [0.8, 1.25]\n"));
        assert_eq!(e, "t.toml: face[0].area: only an affine class has an area range");
        let e = err(&format!("{ROW}class = \"rigid\"\narea = [0.8, 1.25]\n"));
        assert_eq!(e, "t.toml: face[0].area: only an affine class has an area range");
        let e = err(&format!("{ROW}area = [1.25, 0.8]\n"));
        assert_eq!(e, "t.toml: face[0].area: [1.25, 0.8] is not a range of positive numbers, low first");
        let e = err(&format!("{ROW}area = [0, 1]\n"));
        assert_eq!(e, "t.toml: face[0].area: [0, 1] is not a range of positive numbers, low first");
    }
}
